#pragma once
/// \file ranz_marshall.hpp
/// Heat transfer from a sphere to the surrounding fluid (W. E. Ranz, W. R. Marshall, Chem. Eng.
/// Prog. 48 (1952) 141-146 and 173-180):
///
///   Nu = 2 + 0.6 Re^(1/2) Pr^(1/3)                                          [-]
///
/// Re = rho_f 2R |v_f - v| / mu_f and Pr = mu_f c_f / k_f are given by the simulation, which
/// applies h = Nu k_f / (2R) [W/(m^2 K)] over the particle surface. Nu = 2 is pure conduction
/// into a still, unbounded fluid. No parameters.
///
/// Validity: single spheres (evaporating drops in the original work), about 0 <= Re < 200 and
/// 0 <= Pr < 250; widely used beyond. 2D disks use the same correlation with their diameter and
/// lateral surface.

#include <cmath>
#include <grain/models/concepts.hpp>

namespace grain::convection {

struct RanzMarshall {
  static constexpr Slot slot = Slot::convection;
  static constexpr const char* name = "Ranz-Marshall";
  static constexpr bool active = true;
  struct Params {};
  static void validate(const Params&) {}
  static double nusselt(double re, double pr, const Params&) {
    return 2.0 + 0.6 * std::sqrt(re) * std::cbrt(pr);
  }
};

} // namespace grain::convection
