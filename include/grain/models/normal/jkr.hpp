#pragma once
/// \file jkr.hpp
/// Adhesive elastic normal force of Johnson, Kendall and Roberts (JKR), with a viscous part:
///
///   delta = a^2 / R* - sqrt(2 pi w a / E*)                                          [m]
///   F_n   = 4 E* a^3 / (3 R*) - sqrt(8 pi w E* a^3) + eta d(delta)/dt               [N]
///
/// (Johnson, Kendall & Roberts, Proc. R. Soc. Lond. A 324 (1971) 301; Johnson, Contact
/// Mechanics, 1985, sec. 5.5.) a [m] is the contact radius, delta [m] the overlap (negative
/// across a gap), E* [Pa] and R* [m] the effective modulus and radius of the pair (R* = R on a
/// flat wall), w [J/m^2] the work of adhesion (`work_of_adhesion`: the energy per unit area to
/// separate the two surfaces; 2 gamma for two surfaces of one material of surface energy gamma).
/// F_n is repulsive positive; the same law acts on 2D disks.
///
/// The contact radius is the root of the first equation on its stable branch (a above
/// a_f = (pi w R*^2 / (8 E*))^(1/3), where d(delta)/da = 0), found by Newton's method from above.
/// Closed forms the tests check:
/// - load-controlled pull-off (the largest tension): F_c = 3/2 pi w R*;
/// - the contact snaps in at first touch (delta = 0) to F_n = -4/3 pi w R*;
/// - the neck holds across a gap until delta_c = -3/4 (pi^2 w^2 R* / E*^2)^(1/3), where
///   F_n = -5/6 pi w R*; beyond delta_c it breaks, and forms again only when the surfaces touch.
/// The search reaches |delta_c| beyond contact (`reach`, with R* up to the largest radius).
///
/// Damping: eta = 2 xi sqrt(2 E* a m*) (`damping_ratio` xi >= 0, default 0), the viscous
/// coefficient of a linear oscillator of the contact stiffness 2 E* a (the Hertz stiffness at
/// the same contact radius, reported as `stiffness` for the tangential and rolling models and the
/// time step). Elastic energy: the work of F_n along the JKR curve since the snap-in,
/// E* (8 a^5 / (15 R*^2) - 4/3 c a^(7/2) / R* + c^2 a^2 / 2) minus its value at the snap-in
/// radius, c = sqrt(2 pi w / E*).
///
/// Friction under tension: the tangential and rolling models limit their forces with the load
/// F_n + 2 F_c = F_n + 3 pi w R* (`NormalResult::adhesion` = 3 pi w R*; Thornton & Yin, Powder
/// Technol. 65 (1991) 153), so an adhesive contact resists sliding under a net pull up to the
/// pull-off. Across a gap (delta <= 0, the neck) only the normal force acts: the tangential and
/// rolling histories are cleared and no heat flows.
///
/// History: whether the pair is bonded (touched since the neck last broke), one byte.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <grain/core/error.hpp>
#include <grain/models/concepts.hpp>
#include <numbers>
#include <string>

namespace grain::normal {

struct Jkr {
  static constexpr Slot slot = Slot::normal;
  static constexpr const char* name = "JKR adhesion";
  static constexpr const char* object = "normal::Jkr";
  /// Acts across gaps up to `reach` (see concepts.hpp, `cohesive_model`).
  static constexpr bool cohesive = true;

  struct Params {
    double work_of_adhesion = 0.0; ///< w [J/m^2] (>= 0; 0 = Hertz without adhesion)
    double damping_ratio = 0.0;    ///< xi [-] of the viscous part (>= 0)
  };
  template <int D>
  struct History {
    std::uint8_t bonded = 0; ///< 1 while the surfaces are bonded (touched, neck not broken)
    /// False if the bytes read from a file are not a history (a bonded flag other than 0 or 1).
    static bool valid_bytes(const History& h) {
      std::uint8_t b;
      std::memcpy(&b, &h.bonded, 1);
      return b <= 1;
    }
  };

  static void validate(const Params& p) {
    detail::require(std::isfinite(p.work_of_adhesion) && p.work_of_adhesion >= 0.0, object,
                    "work_of_adhesion", p.work_of_adhesion, "[0, inf) J/m^2");
    detail::require(std::isfinite(p.damping_ratio) && p.damping_ratio >= 0.0, object,
                    "damping_ratio", p.damping_ratio, "[0, inf)");
  }

  /// c = sqrt(2 pi w / E*) [m^(1/2)].
  static double c_of(const PairProperties& pair, const Params& p) {
    return std::sqrt(2.0 * std::numbers::pi * p.work_of_adhesion / pair.young_eff);
  }

  /// delta_c = -3/4 (pi^2 w^2 R* / E*^2)^(1/3) [m]: the overlap at which the neck breaks.
  static double rupture_overlap(const PairProperties& pair, const Params& p, double r_eff) {
    const double w = p.work_of_adhesion, e = pair.young_eff;
    return -0.75 * std::cbrt(std::numbers::pi * std::numbers::pi * w * w * r_eff / (e * e));
  }

  /// Largest gap [m] across which a pair of effective radius up to `r_eff` acts: -delta_c.
  static double reach(const Params& p, const PairProperties& pair, double r_eff) {
    return p.work_of_adhesion > 0.0 ? -rupture_overlap(pair, p, r_eff) : 0.0;
  }

  /// The contact radius a [m] at overlap delta on the stable branch: the root of
  /// x^4 / R* - c x - delta = 0 with x = sqrt(a), by Newton's method from
  /// x0 = max((2 R* max(delta, 0))^(1/4), (2 R* c)^(1/3)), where the function is positive and
  /// convex (the iterates fall monotonically to the root).
  static double contact_radius(double delta, double r_eff, double c) {
    double x = std::max(std::sqrt(std::sqrt(2.0 * r_eff * std::max(delta, 0.0))),
                        std::cbrt(2.0 * r_eff * c));
    for (int k = 0; k < 60; ++k) {
      const double x3 = x * x * x;
      const double f = x3 * x / r_eff - c * x - delta;
      const double step = f / (4.0 * x3 / r_eff - c);
      if (!(step > 1e-15 * x)) break; // converged (monotone from above)
      x -= step;
    }
    return x * x;
  }

  /// The work of the elastic JKR force from a = 0 to a, divided by E*.
  static double energy_of(double a, double r_eff, double c) {
    const double a2 = a * a, sa = std::sqrt(a);
    return 8.0 * a2 * a2 * a / (15.0 * r_eff * r_eff) - 4.0 / 3.0 * c * a2 * a * sa / r_eff +
           0.5 * c * c * a2;
  }

  template <int D>
  static NormalResult force(const ContactGeometry<D>& g, const PairProperties& pair,
                            const Params& p, History<D>& h) {
    const double delta = g.overlap;
    if (delta > 0.0)
      h.bonded = 1;
    else if (h.bonded == 0 || delta <= rupture_overlap(pair, p, g.r_eff)) {
      h.bonded = 0;
      return {.detached = true};
    }
    const double e = pair.young_eff, r = g.r_eff;
    const double c = c_of(pair, p);
    const double a = contact_radius(delta, r, c);
    const double a3 = a * a * a;
    const double fe = e * (4.0 * a3 / (3.0 * r) - 2.0 * c * a * std::sqrt(a));
    const double k = 2.0 * e * a;
    const double eta = 2.0 * p.damping_ratio * std::sqrt(k * g.m_eff);
    const double a0 = std::cbrt(c * r * c * r); // snap-in radius: a^(3/2) = c R*
    NormalResult n;
    n.force = fe + eta * g.normal_velocity;
    n.viscous = eta * g.normal_velocity;
    n.stiffness = k;
    n.damping = eta;
    n.elastic_energy = e * (energy_of(a, r, c) - energy_of(a0, r, c));
    n.detached = !(delta > 0.0);
    n.adhesion = 3.0 * std::numbers::pi * p.work_of_adhesion * r;
    return n;
  }

  /// Contact stiffness 2 E* a at the larger of the Hertz contact radius of an impact at v
  /// (delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5)) and the JKR radius at zero load,
  /// a = (9 pi w R*^2 / (2 E*))^(1/3).
  static double stiffness_estimate(const PairProperties& pair, const Params& p, double r_eff,
                                   double m_eff, double v) {
    const double e = pair.young_eff;
    const double dmax = std::pow(15.0 * m_eff * v * v / (16.0 * e * std::sqrt(r_eff)), 0.4);
    const double a_hertz = std::sqrt(r_eff * dmax);
    const double a_zero =
        std::cbrt(4.5 * std::numbers::pi * p.work_of_adhesion * r_eff * r_eff / e);
    return 2.0 * e * std::max(a_hertz, a_zero);
  }
};

} // namespace grain::normal
