#pragma once
/// \file collisional.hpp
/// Direct conduction during an impact (J. Sun, M. M. Chen, Int. J. Heat Mass Transfer 31 (1988)
/// 969, with the correction factor of J. H. Zhou, A. B. Yu, M. Horio, Chem. Eng. J. 139 (2008)
/// 510), followed by static Batchelor-O'Brien conduction if the contact lasts longer than the
/// impact.
///
/// At the first step of a contact, the impact velocity v0 = d(delta)/dt > 0 [m/s] fixes the
/// undamped Hertz impact of the pair (effective mass m* [kg], radius R* [m], modulus E* [Pa]):
///
///   a_max = (15 m* R*^2 v0^2 / (16 E*))^(1/5)                  maximum contact radius [m]
///   t_c   = c_t (m*^2 / (R* E*^2 v0))^(1/5),  c_t = 2.8682657   contact duration [s]
///   Fo    = k t_c / (rho c a_max^2)                             Fourier number [-]
///           (particle-particle: the mean of both particles' values; particle-wall: the particle's)
///   b     = rho_i c_i / (rho_j c_j)
///   C1 = -2.300 b^2 + 8.909 b - 4.235,  C2 = 8.169 b^2 - 33.770 b + 24.885,
///   C3 = -5.758 b^2 + 24.464 b - 20.511
///   C  = 0.435 (sqrt(C2^2 - 4 C1 (C3 - Fo)) - C2) / C1          correction factor [-]
///        (= 0.87 x, x the root of C1 x^2 + C2 x + C3 = Fo near 1)
///   H_coll = C pi a_max^2 t_c^(-1/2) / ((rho_i c_i k_i)^(-1/2) + (rho_j c_j k_j)^(-1/2))  [W/K]
///
/// (rho [kg/m^3], c [J/(kg K)], k [W/(m K)]; i the particle, j the partner particle or the wall's
/// material). The heat exchanged over the impact is H_coll t_c (T_j - T_i), i.e.
/// C pi a_max^2 t_c^(1/2) (T_j - T_i) / ((rho_i c_i k_i)^(-1/2) + (rho_j c_j k_j)^(-1/2)), Sun &
/// Chen's result with their constant 0.87 replaced by the Fourier-number fit C of Zhou et al.
/// (`Params::coefficient` > 0 fixes C instead, e.g. 0.87). c_t is the exact Hertz value; Sun & Chen
/// round it to 2.87 (0.06 % more).
///
/// Conductance of each step: H = H_coll while the contact time is below t_c, then the static
/// H = 4 k* a (`BatchelorOBrien`, k* = k_i k_j/(k_i + k_j), a the area-corrected contact radius).
/// The step that crosses t_c returns the time-weighted mix of both, so the heat of the impact is
/// H_coll t_c whatever the time step. A contact that starts with v0 <= 0 (a resting contact, or a
/// purely thermal simulation with fixed particles) has no impact phase: BOB throughout, also if
/// the pair later moves towards each other. The simulation resets the history when the pair
/// separates, so each new impact is evaluated afresh.
///
/// Modulus: E* is the simulated `PairProperties::young_eff`, so that a_max and t_c are those of
/// the simulated (undamped) impact and the impact phase ends when the simulated contact does.
/// With a softened modulus the heat per impact, proportional to a_max^2 t_c^(1/2) ~ E*^(-3/5), is
/// overestimated by (E*_0/E*)^(3/5) (an area correction changes only the static phase).
///
/// Validity: elastic Hertz impacts of spheres, short contacts (small Fo), vacuum or a poorly
/// conducting gas; the fit C(b, Fo) stays between 0.84 and 1.52 for 0.01 <= b <= 20 and
/// 0 <= Fo <= 1 (the seed's quotient by C1 is undefined at b = 0.555 and 3.319; not here). 2D
/// disks use the sphere formulas with their own m*. For b != 1 the fit is not symmetric in the
/// two partners: i is the particle that is first in the pair at the impact step. If either side
/// has no heat capacity (rho c = 0) the impact phase is skipped (BOB throughout).
///
/// History (24 bytes): `conductance` H_coll [W/K], `duration` t_c [s] (0: no step seen yet, < 0:
/// resting contact), `elapsed` contact time [s]. It does not depend on the orientation of the pair.

#include <algorithm>
#include <cmath>
#include <grain/core/error.hpp>
#include <grain/models/concepts.hpp>
#include <grain/models/normal/hertz_equivalent.hpp>
#include <numbers>

namespace grain::conduction {

struct Collisional {
  static constexpr Slot slot = Slot::conduction;
  static constexpr const char* name = "collisional";
  static constexpr bool thermal = true;
  static constexpr bool uses_distance = false; ///< needs the contact radius only

  struct Params {
    /// Correction factor C' [-] of the impact heat; 0 = the Zhou, Yu & Horio fit C(b, Fo);
    /// > 0 = this constant (Sun & Chen: 0.87).
    double coefficient = 0.0;
  };

  template <int D>
  struct History {
    double conductance = 0.0; ///< H_coll of the current impact [W/K]
    double duration = 0.0;    ///< t_c [s]; 0: no step seen yet; < 0: resting contact (BOB only)
    double elapsed = 0.0;     ///< contact time so far [s]
  };

  static void validate(const Params& p) {
    detail::require_non_negative("conduction::Collisional", "coefficient", p.coefficient);
  }

  /// What an impact at velocity v0 gives (see the file comment).
  struct Impact {
    double radius = 0.0;      ///< a_max [m]
    double duration = 0.0;    ///< t_c [s]
    double fourier = 0.0;     ///< Fo [-]
    double correction = 0.0;  ///< C [-]
    double conductance = 0.0; ///< H_coll [W/K]
  };

  /// The correction factor C(b, Fo) of Zhou, Yu & Horio: C = 0.87 x with x the root of
  /// C1 x^2 + C2 x + C3 = Fo given in the file comment, evaluated without cancellation (as
  /// 2 (Fo - C3)/(C2 + sqrt(C2^2 - 4 C1 (C3 - Fo))) when C2 > 0, where C1 may vanish).
  static double correction(double b, double fo) {
    const double b2 = b * b;
    const double c1 = -2.300 * b2 + 8.909 * b - 4.235;
    const double c2 = 8.169 * b2 - 33.770 * b + 24.885;
    const double c3 = -5.758 * b2 + 24.464 * b - 20.511;
    const double s = std::sqrt(std::max(c2 * c2 - 4.0 * c1 * (c3 - fo), 0.0));
    const double x = c2 > 0.0 ? 2.0 * (fo - c3) / (s + c2) : (s - c2) / (2.0 * c1);
    return std::max(0.87 * x, 0.0);
  }

  /// The impact of a pair at normal velocity v0 > 0 [m/s]; `wall`: j is a wall (Fo of i only).
  static Impact impact(const PairProperties& pair, double r_eff, double m_eff, double v0, bool wall,
                       const Params& p) {
    Impact r;
    const double ci = pair.density_i * pair.heat_capacity_i;
    const double cj = pair.density_j * pair.heat_capacity_j;
    r.radius =
        std::sqrt(r_eff * normal::hertz_equivalent::hertz_max_overlap(pair, r_eff, m_eff, v0));
    r.duration = normal::hertz_equivalent::hertz_contact_time(pair, r_eff, m_eff, v0);
    const double a2 = r.radius * r.radius;
    const double fo_i = pair.conductivity_i * r.duration / (ci * a2);
    r.fourier = wall ? fo_i : 0.5 * (fo_i + pair.conductivity_j * r.duration / (cj * a2));
    r.correction = p.coefficient > 0.0 ? p.coefficient : correction(ci / cj, r.fourier);
    const double ei = ci * pair.conductivity_i, ej = cj * pair.conductivity_j;
    if (ei > 0.0 && ej > 0.0)
      r.conductance = r.correction * std::numbers::pi * a2 / std::sqrt(r.duration) /
                      (1.0 / std::sqrt(ei) + 1.0 / std::sqrt(ej));
    return r;
  }

  template <int D>
  static double conductance(const ContactGeometry<D>& g, const PairProperties& pair,
                            const HeatContext& c, const Params& p, History<D>& h) {
    if (!c.touching) return 0.0;
    const double h_static = 4.0 * pair.conductivity_eff * c.contact_radius;
    if (h.duration == 0.0) { // first step of the contact: record the impact
      const double v0 = g.normal_velocity;
      const bool capacities = pair.density_i * pair.heat_capacity_i > 0.0 &&
                              pair.density_j * pair.heat_capacity_j > 0.0;
      if (v0 > 0.0 && capacities && g.r_eff > 0.0 && g.m_eff > 0.0 && pair.young_eff > 0.0) {
        const Impact im = impact(pair, g.r_eff, g.m_eff, v0, g.wall, p);
        h.conductance = im.conductance;
        h.duration = im.duration;
      } else {
        h.duration = -1.0;
      }
    }
    const double t0 = h.elapsed;
    const double dt = c.time_step;
    h.elapsed += dt;
    if (h.duration <= t0) return h_static; // resting contact, or the impact is over
    // share of this step that lies within the impact: 1 until the step that crosses t_c
    const double f = dt > 0.0 ? std::min((h.duration - t0) / dt, 1.0) : 1.0;
    return f * h.conductance + (1.0 - f) * h_static;
  }
};

} // namespace grain::conduction
