#pragma once
/// \file hertz.hpp
/// Nonlinear visco-elastic normal force: Hertz elastic force plus a viscous part chosen by a
/// damping policy (the template argument).
///
///   F_n = K_hz delta^(3/2) + eta(delta) d(delta)/dt,   K_hz = 4/3 E* sqrt(R*)      [N]
///
/// (Hertz, J. reine angew. Math. 92 (1882) 156; Johnson, Contact Mechanics, 1985.) E* [Pa] and
/// R* [m] are the effective modulus and radius of the pair (a flat wall has infinite radius, so
/// R* = R; its E* comes from the wall's material). Elastic energy 2/5 K_hz delta^(5/2); tangent
/// stiffness dF/d delta = 3/2 K_hz sqrt(delta) = 2 E* a, a = sqrt(R* delta).
///
/// Damping policies (hertz_damping.hpp), each with its own parameters in `Params::damping`:
/// - `TsujiDamping` (default): eta = alpha sqrt(m* K_hz) delta^(1/4), alpha from the pair's
///   restitution by the exact map sqrt(5) |ln e| / sqrt(ln^2 e + pi^2) (or DEMLab's Norouzi fit,
///   or given); an isolated contact rebounds with e for any impact velocity.
/// - `CriticalRatioDamping`: eta = xi sqrt(8 E* m* sqrt(R*)) delta^(1/4), xi given.
/// - `KuwabaraKonoDamping`: eta = eta_KK delta^(1/2), eta_KK given.
/// - `LeeHerrmannDamping`: eta = eta_LH m*, eta_LH given.
///
/// `no_cohesion` clamps F_n >= 0 (no attraction at the end of a damped contact; the rebound is
/// then faster than the unclamped one, e.g. e = 0.1 gives 0.2527 with Tsuji damping).
/// History: none.
///
/// `hertz_contact_time(E*, R*, m*, v)` gives the duration of an undamped Hertz impact, for
/// choosing a time step (see its comment for the derivation).

#include <cmath>
#include <grain/core/error.hpp>
#include <grain/models/concepts.hpp>
#include <grain/models/normal/hertz_damping.hpp>
#include <grain/models/normal/hertz_equivalent.hpp>
#include <string>

namespace grain::detail {
/// The readable name of `Hertz<Damping>`: the policy's `hertz_name`, or "Hertz".
template <class Damping>
constexpr const char* hertz_name() {
  if constexpr (requires { Damping::hertz_name; })
    return Damping::hertz_name;
  else
    return "Hertz";
}
} // namespace grain::detail

namespace grain::normal {

template <class Damping = TsujiDamping>
struct Hertz {
  static constexpr Slot slot = Slot::normal;
  /// e.g. "Hertz with Tsuji damping"
  static constexpr const char* name = detail::hertz_name<Damping>();

  struct Params {
    bool no_cohesion = false;           ///< clamp the force at zero (no attraction)
    typename Damping::Params damping{}; ///< coefficients of the damping policy
  };
  template <int D>
  struct History {};

  static std::string object() {
    return std::string("normal::Hertz<normal::") + Damping::name + ">";
  }

  static void validate(const Params& p) { Damping::validate(p.damping, object()); }
  /// The damping policy's per-pair constants worked out (see Interaction::resolve).
  static Params resolve(Params p, const PairProperties& pair) {
    if constexpr (requires { Damping::resolve(p.damping, pair); })
      p.damping = Damping::resolve(p.damping, pair);
    return p;
  }

  /// K_hz = 4/3 E* sqrt(R*) [N/m^1.5].
  static double k_hertz(const PairProperties& pair, double r_eff) {
    return 4.0 / 3.0 * pair.young_eff * std::sqrt(r_eff);
  }

  template <int D>
  GRAIN_INLINE static NormalResult force(const ContactGeometry<D>& g, const PairProperties& pair,
                                         const Params& p, History<D>&) {
    // one square root: K_hz sqrt(delta) = 4/3 E* a with a = sqrt(R* delta)
    const double ks = 4.0 / 3.0 * pair.young_eff * std::sqrt(g.r_eff * g.overlap);
    const double fe = ks * g.overlap;
    const double eta = Damping::coefficient(pair, p.damping, ks, g.r_eff, g.m_eff, g.overlap);
    double f = fe + eta * g.normal_velocity;
    if (p.no_cohesion && f < 0.0) f = 0.0;
    return {.force = f,
            .stiffness = 1.5 * ks,
            .damping = eta,
            .elastic_energy = 0.4 * fe * g.overlap,
            .viscous = f - fe};
  }

  /// Tangent stiffness at the maximum overlap of an undamped impact at velocity v [m/s]:
  /// delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5) (damping only lowers delta_max).
  static double stiffness_estimate(const PairProperties& pair, const Params&, double r_eff,
                                   double m_eff, double v) {
    const double kh = k_hertz(pair, r_eff);
    const double dmax =
        std::pow(15.0 * m_eff * v * v / (16.0 * pair.young_eff * std::sqrt(r_eff)), 0.4);
    return 1.5 * kh * std::sqrt(dmax);
  }
};

/// Duration t_c [s] of a head-on impact of two elastic spheres under the Hertz force
/// F = K_hz delta^(3/2), K_hz = 4/3 E* sqrt(R*), without damping (`normal::Hertz` with zero
/// damping, restitution 1), at the normal approach velocity v:
///
///   t_c = c_t (m*^2 / (R* E*^2 v))^(1/5),   c_t = 2 I (15/16)^(2/5) = 2.8682657
///
/// with
/// - E* [Pa], 1/E* = (1 - nu_1^2)/E_1 + (1 - nu_2^2)/E_2 (`PairProperties::young_eff`, e.g.
///   `PairProperties::mix(a, b).young_eff` for materials a, b; for a wall, its material's);
/// - R* [m], 1/R* = 1/R_1 + 1/R_2 (R* = R for a sphere on a flat wall);
/// - m* [kg], 1/m* = 1/m_1 + 1/m_2 (m* = m on a wall);
/// - v [m/s] > 0, the relative normal velocity at first touch.
///
/// Derivation: m* delta'' = -K_hz delta^(3/2), delta(0) = 0, delta'(0) = v. Energy conservation,
/// 1/2 m* delta'^2 + 2/5 K_hz delta^(5/2) = 1/2 m* v^2, gives the largest overlap
/// delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5) and the rate
/// delta' = v sqrt(1 - (delta/delta_max)^(5/2)), so t_c = 2 int_0^delta_max d(delta)/delta'
/// = 2 I delta_max / v with I = int_0^1 dx / sqrt(1 - x^(5/2)) = sqrt(pi) Gamma(7/5) / Gamma(9/10)
/// = 1.4716376. Hence t_c = 2.9432752 delta_max / v
/// = 2.9432752 ((15/16)^2 m*^2 / (R* E*^2 v))^(1/5), the constants 2.94 and 2.87 of Johnson,
/// Contact Mechanics (1985), ch. 11. The same law holds for 2D disks in grain (the Hertz force is
/// applied to disks unchanged), with the disks' masses in m*.
///
/// t_c falls slowly with v (as v^(-1/5)): take the largest impact velocity expected. A time step
/// dt = t_c / N resolves a contact with about N steps (the impact tests measure t_c to 0.5 % with
/// N = 100). Damping lowers delta_max and, for Tsuji damping, changes t_c by a factor that
/// depends on the restitution only. Throws `InputError` for an argument that is not finite and
/// > 0.
inline double hertz_contact_time(double young_eff, double r_eff, double m_eff, double v) {
  const std::string obj = "normal::hertz_contact_time";
  detail::require(std::isfinite(young_eff) && young_eff > 0.0, obj, "young_eff", young_eff,
                  "(0, inf) Pa (the effective modulus E*)");
  detail::require(std::isfinite(r_eff) && r_eff > 0.0, obj, "r_eff", r_eff,
                  "(0, inf) m (the effective radius R*)");
  detail::require(std::isfinite(m_eff) && m_eff > 0.0, obj, "m_eff", m_eff,
                  "(0, inf) kg (the effective mass m*)");
  detail::require(std::isfinite(v) && v > 0.0, obj, "v", v,
                  "(0, inf) m/s (the normal approach velocity at first touch)");
  return hertz_equivalent::hertz_time_coefficient *
         std::pow(m_eff * m_eff / (r_eff * young_eff * young_eff * v), 0.2);
}

} // namespace grain::normal
