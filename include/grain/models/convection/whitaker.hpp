#pragma once
/// \file whitaker.hpp
/// Heat transfer from a sphere to the surrounding fluid (S. Whitaker, AIChE J. 18 (1972)
/// 361-371):
///
///   Nu = 2 + (0.4 Re^(1/2) + 0.06 Re^(2/3)) Pr^(2/5) (mu_f/mu_s)^(1/4)       [-]
///
/// with the viscosity-ratio factor (fluid viscosity at the fluid and at the surface temperature)
/// taken as 1, since the fluid has a single viscosity. Re = rho_f 2R |v_f - v| / mu_f and
/// Pr = mu_f c_f / k_f are given by the simulation, which applies h = Nu k_f / (2R) [W/(m^2 K)]
/// over the particle surface. No parameters.
///
/// Validity (Whitaker's data): 3.5 <= Re <= 7.6e4, 0.71 <= Pr <= 380, 1 <= mu_f/mu_s <= 3.2;
/// Nu -> 2 as Re -> 0. 2D disks use the same correlation with their diameter and lateral surface.

#include <cmath>
#include <grain/models/concepts.hpp>

namespace grain::convection {

struct Whitaker {
  static constexpr Slot slot = Slot::convection;
  static constexpr const char* name = "Whitaker";
  static constexpr bool active = true;
  struct Params {};
  static void validate(const Params&) {}
  static double nusselt(double re, double pr, const Params&) {
    return 2.0 + (0.4 * std::sqrt(re) + 0.06 * std::cbrt(re * re)) * std::pow(pr, 0.4);
  }
};

} // namespace grain::convection
