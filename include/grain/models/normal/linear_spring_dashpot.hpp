#pragma once
/// \file linear_spring_dashpot.hpp
/// Linear spring-dashpot normal force (Cundall & Strack, Geotechnique 29 (1979) 47-65).
///
///   F_n = K delta + eta d(delta)/dt        [N], repulsive positive
///
/// - K [N/m]: `stiffness` if given (> 0); otherwise the Hertz-equivalent stiffness at the
///   reference impact velocity v = `reference_velocity` [m/s] that reproduces the maximum overlap
///   of an undamped Hertz impact (Hertz "energy" equivalence):
///   K = (16/15)^(4/5) (v R* E*^2 sqrt(m*))^(2/5)  (= 1.053 (...)^(2/5)).
/// - eta [N s/m]: `damping` if given (>= 0); otherwise from the pair's restitution e:
///   eta = 2 zeta sqrt(m* K), zeta = -ln e / sqrt(ln^2 e + pi^2), which gives exactly e for an
///   isolated contact without force clamping.
/// - `no_cohesion`: clamp F_n >= 0 (no artificial attraction at the end of a damped contact; the
///   achieved restitution is then above e, see docs/validation.md).
///
/// Contact duration t_c = pi / sqrt(K/m* - (eta/(2 m*))^2). History: none.

#include <grain/models/concepts.hpp>
#include <cmath>
#include <numbers>

namespace grain::normal {

struct LinearSpringDashpot {
  static constexpr Slot slot = Slot::normal;
  static constexpr const char* name = "linear spring-dashpot";

  struct Params {
    double stiffness = 0.0;          ///< K [N/m]; 0 = Hertz-equivalent at reference_velocity
    double reference_velocity = 1.0; ///< impact velocity for the Hertz-equivalent K [m/s]
    double damping = -1.0;           ///< eta [N s/m]; < 0 = from the restitution coefficient
    bool no_cohesion = false;        ///< clamp the force at zero (no attraction)
  };
  template <int D>
  struct History {};

  static void validate(const Params& p) {
    detail::require_non_negative("normal::LinearSpringDashpot", "stiffness", p.stiffness);
    if (p.stiffness == 0.0)
      detail::require_positive("normal::LinearSpringDashpot", "reference_velocity",
                               p.reference_velocity);
    detail::require(std::isfinite(p.damping), "normal::LinearSpringDashpot", "damping", p.damping,
                    "[0, inf), or < 0 for damping from restitution");
  }

  /// K [N/m] of a contact with effective radius r_eff and mass m_eff.
  static double stiffness(const PairProperties& pair, const Params& p, double r_eff,
                          double m_eff) {
    if (p.stiffness > 0.0) return p.stiffness;
    const double x = p.reference_velocity * r_eff * pair.young_eff * pair.young_eff * std::sqrt(m_eff);
    return std::pow(16.0 / 15.0, 0.8) * std::pow(x, 0.4);
  }
  /// eta [N s/m].
  static double damping(const PairProperties& pair, const Params& p, double k, double m_eff) {
    if (p.damping >= 0.0) return p.damping;
    return 2.0 * pair.damping_ratio() * std::sqrt(m_eff * k);
  }

  template <int D>
  static NormalResult force(const ContactGeometry<D>& g, const PairProperties& pair,
                            const Params& p, History<D>&) {
    const double k = stiffness(pair, p, g.r_eff, g.m_eff);
    const double eta = damping(pair, p, k, g.m_eff);
    double f = k * g.overlap + eta * g.normal_velocity;
    if (p.no_cohesion && f < 0.0) f = 0.0;
    return {f, k, eta, 0.5 * k * g.overlap * g.overlap};
  }

  /// Largest stiffness expected at impact velocity v [m/s] (for the stable time step).
  static double stiffness_estimate(const PairProperties& pair, const Params& p, double r_eff,
                                   double m_eff, double /*v*/) {
    return stiffness(pair, p, r_eff, m_eff);
  }
};

} // namespace grain::normal
