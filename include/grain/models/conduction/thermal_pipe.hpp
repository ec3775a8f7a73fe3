#pragma once
/// \file thermal_pipe.hpp
/// Direct conduction along a "thermal pipe" joining the centres of two touching particles, whose
/// cross-section is the contact area (O. D. Quintana-Ruiz, E. M. B. Campello, J. Braz. Soc. Mech.
/// Sci. Eng. 42 (2020) 387):
///
///   H = A k_avg / d_c                                                       [W/K]
///   A = pi a^2 (spheres, `HeatContext::length` == 0),  A = 2 a L (2D disks as cylinders of
///   length L)                                                               [m^2]
///   k_avg = (R_i + R_j) / (R_i/k_i + R_j/k_j)                              [W/(m K)]
///
/// a [m] is the contact radius after the area correction, d_c [m] the centre distance consistent
/// with a (`HeatContext::distance`), R_i, R_j [m] the radii and k_i, k_j [W/(m K)] the
/// conductivities. k_avg is the series conductivity of two rods of lengths R_i and R_j, so that
/// for d_c ~ R_i + R_j the pipe is the series resistance R_i/(k_i A) + R_j/(k_j A).
///
/// Particle-wall contacts. A wall has no centre: its temperature is the temperature of the wall
/// body, which (like `BatchelorOBrien`, where the wall conducts with its material's
/// conductivity) conducts with the wall material's conductivity k_w. The pipe continues into the
/// wall as the mirror image of the particle's segment (the image of the particle in the wall
/// plane, made of the wall material), which gives
///
///   H_wall = A / (d/k_i + d/k_w) = A k_i k_w / ((k_i + k_w) d)             [W/K]
///
/// with d the centre-to-surface distance (`HeatContext::distance`). A particle on a wall of its
/// own material thus conducts exactly as it does to its mirror image particle (the same holds for
/// `BatchelorOBrien`), an insulating wall (k_w = 0) conducts nothing, and a perfectly conducting
/// wall (k_w -> infinity) gives A k_i / d: the wall's surface is then held at the wall
/// temperature. The seed program uses that limit, k_avg = k_i, for every wall with a material;
/// `Params::isothermal_walls = true` selects it.
///
/// Validity: slender-pipe picture of conduction through the solid, A << pi R^2; it ignores the
/// constriction of the heat flow towards the contact (which `BatchelorOBrien` models) and the
/// interstitial fluid. History: none.

#include <grain/models/concepts.hpp>
#include <numbers>

namespace grain::conduction {

struct ThermalPipe {
  static constexpr Slot slot = Slot::conduction;
  static constexpr const char* name = "thermal pipe";
  static constexpr bool thermal = true;
  struct Params {
    /// true: walls are ideal conductors whose surface is at the wall temperature
    /// (H = A k_i / d, the seed program's form); false: the wall conducts with its material.
    bool isothermal_walls = false;
  };
  template <int D>
  struct History {};
  static void validate(const Params&) {}

  /// Cross-section of the pipe [m^2]: pi a^2, or 2 a L for cylinders of length L > 0.
  static double area(double a, double length) {
    return length > 0.0 ? 2.0 * a * length : std::numbers::pi * a * a;
  }

  /// Series conductivity [W/(m K)] of the pipe: (R_i + R_j)/(R_i/k_i + R_j/k_j) for particles;
  /// for walls 2 k_i k_w/(k_i + k_w) over the doubled length (image), or k_i (isothermal).
  template <int D>
  GRAIN_INLINE static double conductance(const ContactGeometry<D>& g, const PairProperties& pair,
                                         const HeatContext& c, const Params& p, History<D>&) {
    const double ki = pair.conductivity_i, kj = pair.conductivity_j;
    if (!c.touching || !(c.distance > 0.0) || !(ki > 0.0)) return 0.0;
    const double a_pipe = area(c.contact_radius, c.length);
    if (g.wall) {
      if (p.isothermal_walls) return a_pipe * ki / c.distance;
      if (!(kj > 0.0)) return 0.0;
      return a_pipe * (ki * kj / (ki + kj)) / c.distance;
    }
    if (!(kj > 0.0)) return 0.0;
    const double k_avg = (g.radius_i + g.radius_j) / (g.radius_i / ki + g.radius_j / kj);
    return a_pipe * k_avg / c.distance;
  }
};

} // namespace grain::conduction
