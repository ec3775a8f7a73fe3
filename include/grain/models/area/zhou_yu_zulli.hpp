#pragma once
/// \file zhou_yu_zulli.hpp
/// Contact-area correction for a softened Young's modulus derived from Hertz impacts (J. H. Zhou,
/// A. B. Yu, P. Zulli, AIChE J. 56 (2010) 1453):
///
///   a' = (E* / E*_0)^(1/5) sqrt(R* delta)                                   [m]
///
/// E* [Pa] is the simulated effective modulus (`PairProperties::young_eff`), E*_0 [Pa] the one of
/// the real moduli (`young_real_eff`; taken equal to E* if it is not positive), R* [m] the
/// effective radius and delta [m] the simulated overlap. No parameters, no history.
///
/// Validity: exact for the maximum contact radius of an undamped Hertz impact at a given impact
/// velocity (a_max ~ E*^(-1/5) at fixed v), so it suits collision-dominated flows. Under a static
/// load (a ~ E*^(-1/3) at fixed force) it overestimates the real radius
/// (3 F R*/(4 E*_0))^(1/3) by the factor (E*_0/E*)^(2/15), e.g. 2.51 for E*_0/E* = 1000; use
/// `MorrisPannalaMaHrenya` or `LuMorrisLiBenyahia` for enduring contacts. 2D disks use the same
/// expression.

#include <algorithm>
#include <cmath>
#include <grain/models/concepts.hpp>

namespace grain::area {

struct ZhouYuZulli {
  static constexpr Slot slot = Slot::area;
  static constexpr const char* name = "Zhou-Yu-Zulli";
  struct Params {};
  template <int D>
  struct History {};
  static void validate(const Params&) {}

  /// (E*/E*_0)^(1/5), 1 without a real modulus.
  static double factor(const PairProperties& pair) {
    return pair.young_real_eff > 0.0 ? std::pow(pair.young_eff / pair.young_real_eff, 0.2) : 1.0;
  }

  template <int D>
  GRAIN_INLINE static double radius(const ContactGeometry<D>& g, const PairProperties& pair,
                                    const NormalResult&, const Params&) {
    return factor(pair) * std::sqrt(g.r_eff * std::max(g.overlap, 0.0));
  }
};

} // namespace grain::area
