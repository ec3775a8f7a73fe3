#pragma once
/// \file hertz.hpp
/// Hertz elastic normal force with a viscous part chosen by a damping policy.
///
///   F_n = K_hz delta^(3/2) + F_damping,   K_hz = 4/3 E* sqrt(R*)      [N]
///
/// (Hertz 1882; Johnson, Contact Mechanics, 1985.) E* [Pa] and R* [m] are the effective modulus
/// and radius of the pair (a flat wall has infinite radius; its material enters E*). Elastic energy 2/5 K_hz delta^(5/2); tangent stiffness
/// dF/d delta = 3/2 K_hz sqrt(delta) = 2 E* a, a = sqrt(R* delta).
///
/// Damping policies:
/// - `TsujiDamping` (default; Tsuji, Tanaka & Ishida, Powder Technol. 71 (1992) 239):
///   F_damping = alpha sqrt(m* K_hz) delta^(1/4) d(delta)/dt with the exact restitution map
///   alpha = sqrt(5) |ln e| / sqrt(ln^2 e + pi^2) (Antypov & Elliott, EPL 94 (2011) 50004), so an
///   isolated contact rebounds with the pair's restitution e for any impact velocity. This is
///   also the damping of LIGGGHTS' "hertz" model.
///
/// `no_cohesion` clamps F_n >= 0.

#include <grain/models/concepts.hpp>
#include <cmath>
#include <numbers>

namespace grain::normal {

/// Tsuji-type damping with a restitution-derived coefficient.
struct TsujiDamping {
  static constexpr const char* name = "Tsuji";
  /// alpha(e) = sqrt(5) |ln e| / sqrt(ln^2 e + pi^2).
  static double alpha(const PairProperties& pair) { return std::sqrt(5.0) * pair.damping_ratio(); }
};

template <class Damping = TsujiDamping>
struct Hertz {
  static constexpr Slot slot = Slot::normal;
  static constexpr const char* name = "Hertz";

  struct Params {
    bool no_cohesion = false; ///< clamp the force at zero (no attraction)
  };
  template <int D>
  struct History {};

  static void validate(const Params&) {}

  /// K_hz = 4/3 E* sqrt(R*) [N/m^1.5].
  static double k_hertz(const PairProperties& pair, double r_eff) {
    return 4.0 / 3.0 * pair.young_eff * std::sqrt(r_eff);
  }

  template <int D>
  static NormalResult force(const ContactGeometry<D>& g, const PairProperties& pair,
                            const Params& p, History<D>&) {
    const double kh = k_hertz(pair, g.r_eff);
    const double sd = std::sqrt(g.overlap);
    const double fe = kh * g.overlap * sd;
    const double eta = Damping::alpha(pair) * std::sqrt(g.m_eff * kh * sd);
    double f = fe + eta * g.normal_velocity;
    if (p.no_cohesion && f < 0.0) f = 0.0;
    return {f, 1.5 * kh * sd, eta, 0.4 * fe * g.overlap};
  }

  /// Tangent stiffness at the maximum overlap of an undamped impact at velocity v [m/s]:
  /// delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5).
  static double stiffness_estimate(const PairProperties& pair, const Params&, double r_eff,
                                   double m_eff, double v) {
    const double kh = k_hertz(pair, r_eff);
    const double dmax = std::pow(15.0 * m_eff * v * v / (16.0 * pair.young_eff * std::sqrt(r_eff)), 0.4);
    return 1.5 * kh * std::sqrt(dmax);
  }
};

} // namespace grain::normal
