#pragma once
/// \file hertz_equivalent.hpp
/// What the linear normal models share: the closed forms of an undamped Hertz impact, the
/// "Hertz-equivalent" linear stiffness formulations, and the choice of the impact velocity those
/// formulations use.
///
/// Undamped Hertz impact (m* d''delta + K_hz delta^(3/2) = 0, delta(0) = 0, delta'(0) = v;
/// K_hz = 4/3 E* sqrt(R*); Johnson, Contact Mechanics, 1985, ch. 11):
///
///   delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5)                                  [m]
///   t_c       = 2 I delta_max / v,  I = int_0^1 dx / sqrt(1 - x^(5/2))
///             = sqrt(pi) Gamma(7/5)/Gamma(9/10) = 1.4716376
///             = c_t (m*^2 / (R* E*^2 v))^(1/5),  c_t = 2 I (15/16)^(2/5) = 2.8682657     [s]
///
/// A linear spring K reaches delta_max = v sqrt(m*/K) undamped, and with the damping ratio
/// zeta = -ln e / sqrt(ln^2 e + pi^2) (restitution e, beta = pi / ln e < 0)
///
///   delta_max = v sqrt(m*/K) exp(-atan(beta)/beta),   t_c = pi sqrt(m*/K) sqrt(1 + beta^-2).
///
/// With X = (v R* E*^2 sqrt(m*))^(2/5) [N/m], the Hertz-equivalent stiffness is
///
/// | formulation | K | the linear contact then has |
/// |---|---|---|
/// | `energy`  | (16/15)^(4/5) X = 1.0529869 X | undamped: the Hertz delta_max and the Hertz maximum strain energy 1/2 m* v^2 |
/// | `overlap` | 1.0529869 X exp(-atan(beta)/beta)^2 | damped: the maximum overlap of the undamped Hertz impact |
/// | `time`    | (pi/c_t)^2 X (1 + beta^-2) = 1.1996678 X (1 + beta^-2) | damped: the contact duration of the undamped Hertz impact |
///
/// (DEMLab, rlrangel/DEMLab, uses 1.053 and 1.198 and its header comments swap the overlap and
/// time factors; the table above is derived from the closed forms and checked in
/// tests/physics/normal_impact_test.cpp.) For e = 1 the overlap factor and 1 + beta^-2 are 1.
///
/// Impact-velocity policies (a template argument of the linear models):
/// - `ReferenceVelocity`: v is the model parameter `reference_velocity`; no per-contact state.
/// - `PerContactVelocity`: v is |d(delta)/dt| measured at the first step of each contact and kept
///   in the contact's history until the contact ends (as DEMLab does). A measured velocity below
///   the parameter `min_impact_velocity` is replaced by `reference_velocity`, so a contact that
///   forms slowly never gets a vanishing stiffness.

#include <algorithm>
#include <cmath>
#include <grain/particles/material.hpp>
#include <numbers>

namespace grain::normal {

/// Which impact quantity a Hertz-equivalent linear stiffness reproduces (see the file comment).
enum class Equivalence {
  energy,  ///< undamped maximum overlap and strain energy of the Hertz impact (default)
  overlap, ///< maximum overlap of the undamped Hertz impact, reached with damping
  time     ///< contact duration of the undamped Hertz impact, reached with damping
};

/// Impact velocity = the model's `reference_velocity` (zero bytes of history).
struct ReferenceVelocity {
  static constexpr bool per_contact = false;
};
/// Impact velocity measured at the first step of each contact and kept for the contact.
struct PerContactVelocity {
  static constexpr bool per_contact = true;
};

namespace hertz_equivalent {

/// (16/15)^(4/5): K = this x X matches the undamped Hertz maximum overlap.
inline constexpr double energy_coefficient = 1.0529869257785707;
/// c_t = 2 sqrt(pi) Gamma(7/5)/Gamma(9/10) (15/16)^(2/5): Hertz t_c = c_t (m*^2/(R* E*^2 v))^(1/5).
inline constexpr double hertz_time_coefficient = 2.868265699195333;
/// (pi/c_t)^2: K = this x X makes an undamped linear contact last the Hertz t_c.
inline constexpr double time_coefficient = 1.1996677571941659;

/// X = (v R* E*^2 sqrt(m*))^(2/5) [N/m].
inline double scale(const PairProperties& pair, double r_eff, double m_eff, double v) {
  return std::pow(v * r_eff * pair.young_eff * pair.young_eff * std::sqrt(m_eff), 0.4);
}

/// atan(beta)/beta for beta = pi/ln e, written with x = |ln e|/pi (0 for e = 1).
inline double atan_beta_over_beta(double log_e) {
  const double x = std::abs(log_e) / std::numbers::pi;
  return x * (0.5 * std::numbers::pi - std::atan(x));
}
/// exp(-atan(beta)/beta)^2: the factor of the `overlap` formulation.
inline double overlap_factor(double log_e) { return std::exp(-2.0 * atan_beta_over_beta(log_e)); }
/// 1 + beta^-2 = 1 + ln^2 e / pi^2: the factor of the `time` formulation.
inline double time_factor(double log_e) {
  return 1.0 + log_e * log_e / (std::numbers::pi * std::numbers::pi);
}

/// Hertz-equivalent stiffness [N/m] of a linear spring-dashpot of restitution e = exp(log_e).
inline double linear_stiffness(Equivalence q, const PairProperties& pair, double r_eff,
                               double m_eff, double v) {
  const double x = scale(pair, r_eff, m_eff, v);
  switch (q) {
  case Equivalence::overlap:
    return energy_coefficient * x * overlap_factor(pair.log_restitution);
  case Equivalence::time:
    return time_coefficient * x * time_factor(pair.log_restitution);
  case Equivalence::energy:
  default:
    return energy_coefficient * x;
  }
}

/// Maximum overlap of the undamped Hertz impact at velocity v [m].
inline double hertz_max_overlap(const PairProperties& pair, double r_eff, double m_eff, double v) {
  return std::pow(15.0 * m_eff * v * v / (16.0 * pair.young_eff * std::sqrt(r_eff)), 0.4);
}
/// Contact duration of the undamped Hertz impact at velocity v [s].
inline double hertz_contact_time(const PairProperties& pair, double r_eff, double m_eff, double v) {
  return hertz_time_coefficient *
         std::pow(m_eff * m_eff / (r_eff * pair.young_eff * pair.young_eff * v), 0.2);
}

/// True if q is one of the enumerators (guards against values cast from integers).
inline bool valid(Equivalence q) {
  return q == Equivalence::energy || q == Equivalence::overlap || q == Equivalence::time;
}

} // namespace hertz_equivalent
} // namespace grain::normal

namespace grain::detail {

/// Per-contact record of the impact velocity: empty for `ReferenceVelocity`.
template <class ImpactVelocity>
struct ImpactRecord {};
template <>
struct ImpactRecord<normal::PerContactVelocity> {
  double impact_velocity = 0.0; ///< |d(delta)/dt| at the first contact step [m/s]; 0 = not yet
};

/// The impact velocity of a contact [m/s]; records it at the first contact step.
template <class ImpactVelocity>
inline double impact_velocity(ImpactRecord<ImpactVelocity>& h, double normal_velocity,
                              double reference_velocity, double min_impact_velocity) {
  if constexpr (ImpactVelocity::per_contact) {
    if (h.impact_velocity <= 0.0) {
      const double v = std::abs(normal_velocity);
      h.impact_velocity = v >= min_impact_velocity ? v : reference_velocity;
    }
    return h.impact_velocity;
  } else {
    (void)h;
    (void)normal_velocity;
    (void)min_impact_velocity;
    return reference_velocity;
  }
}

/// The impact velocity to assume for the critical time step [m/s].
template <class ImpactVelocity>
inline double impact_velocity_estimate(double v, double reference_velocity) {
  if constexpr (ImpactVelocity::per_contact)
    return std::max(v, reference_velocity);
  else
    return reference_velocity;
}

} // namespace grain::detail
