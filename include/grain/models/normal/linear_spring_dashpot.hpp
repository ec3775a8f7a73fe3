#pragma once
/// \file linear_spring_dashpot.hpp
/// Linear visco-elastic normal force (Cundall & Strack, Geotechnique 29 (1979) 47-65).
///
///   F_n = K delta + eta d(delta)/dt        [N], repulsive positive
///
/// - K [N/m]: `stiffness` if given (> 0); otherwise the Hertz-equivalent stiffness of the
///   formulation `equivalence` at the impact velocity v (see hertz_equivalent.hpp), with
///   X = (v R* E*^2 sqrt(m*))^(2/5) and beta = pi / ln e:
///   - `energy` (default): K = (16/15)^(4/5) X = 1.0530 X. Undamped, the contact reaches the
///     maximum overlap and the maximum strain energy (1/2 m* v^2) of the undamped Hertz impact.
///   - `overlap`: K = 1.0530 X exp(-atan(beta)/beta)^2. With its damping, the contact reaches
///     the maximum overlap of the undamped Hertz impact.
///   - `time`: K = (pi/c_t)^2 X (1 + beta^-2) = 1.1997 X (1 + beta^-2). With its damping, the
///     contact lasts as long as the undamped Hertz impact, c_t (m*^2/(R* E*^2 v))^(1/5),
///     c_t = 2.8683.
///   The formulations use the pair's restitution e even when `damping` is given.
/// - v [m/s], chosen at compile time:
///   - `LinearSpringDashpot` (= `BasicLinearSpringDashpot<ReferenceVelocity>`): v =
///     `reference_velocity` for every contact; no per-contact history (zero bytes).
///   - `LinearSpringDashpotPerContact` (= `BasicLinearSpringDashpot<PerContactVelocity>`):
///     v = |d(delta)/dt| at the first step of each contact, kept in the contact's history (one
///     double) until the contact ends, as in DEMLab. A measured v below `min_impact_velocity`
///     is replaced by `reference_velocity`, so a contact that forms slowly never gets a
///     vanishing stiffness (DEMLab gives it K = 0).
/// - eta [N s/m]: `damping` if given (>= 0); otherwise `damping_ratio` zeta if given (>= 0),
///   eta = 2 zeta sqrt(m* K) with each contact's effective mass m* (the third seed's GRANULAR
///   damper: zeta = 1 is critical damping, zeta > 1 overdamped; an isolated contact rebounds
///   with e = exp(-pi zeta / sqrt(1 - zeta^2)) for zeta < 1 and not at all for zeta >= 1,
///   whatever the masses); otherwise from the pair's restitution e,
///   eta = 2 zeta sqrt(m* K), zeta = -ln e / sqrt(ln^2 e + pi^2), which gives exactly e for an
///   isolated contact without force clamping. It is evaluated with the contact's current K
///   (DEMLab keeps the first value of a contact object even after K changes).
/// - `no_cohesion`: clamp F_n >= 0 (no artificial attraction at the end of a damped contact; the
///   achieved restitution is then above e, e.g. 0.2527 for e = 0.1; see docs/models/normal.md).
///
/// Isolated contact: e = exp(-pi zeta / sqrt(1 - zeta^2)); t_c = pi sqrt(m*/K) sqrt(1 + beta^-2);
/// delta_max = v sqrt(m*/K) exp(-atan(beta)/beta). Elastic energy 1/2 K delta^2; tangent
/// stiffness K; damping coefficient eta.

#include <cmath>
#include <grain/models/concepts.hpp>
#include <grain/models/normal/hertz_equivalent.hpp>
#include <numbers>
#include <type_traits>

namespace grain::normal {

template <class ImpactVelocity = ReferenceVelocity>
struct BasicLinearSpringDashpot {
  static_assert(std::is_same_v<ImpactVelocity, ReferenceVelocity> ||
                    std::is_same_v<ImpactVelocity, PerContactVelocity>,
                "grain::normal::BasicLinearSpringDashpot: the argument must be "
                "normal::ReferenceVelocity or normal::PerContactVelocity");
  static constexpr Slot slot = Slot::normal;
  static constexpr const char* name = ImpactVelocity::per_contact
                                          ? "linear spring-dashpot, per-contact impact velocity"
                                          : "linear spring-dashpot";
  static constexpr const char* object = ImpactVelocity::per_contact
                                            ? "normal::LinearSpringDashpotPerContact"
                                            : "normal::LinearSpringDashpot";

  struct Params {
    double stiffness = 0.0;          ///< K [N/m]; 0 = Hertz-equivalent (see `equivalence`)
    double reference_velocity = 1.0; ///< impact velocity v for the Hertz-equivalent K [m/s]
    double damping = -1.0;           ///< eta [N s/m]; < 0 = from the restitution coefficient
    bool no_cohesion = false;        ///< clamp the force at zero (no attraction)
    Equivalence equivalence = Equivalence::energy; ///< formulation of the Hertz-equivalent K
    /// per-contact velocity only: measured impact velocities below this use
    /// `reference_velocity` [m/s]
    double min_impact_velocity = 0.01;
    /// zeta [-]: eta = 2 zeta sqrt(m* K) when `damping` is not given; < 0 = from the restitution
    /// coefficient
    double damping_ratio = -1.0;
  };
  /// Empty (zero bytes) unless the impact velocity is per contact.
  template <int D>
  struct History : detail::ImpactRecord<ImpactVelocity> {};

  static void validate(const Params& p) {
    detail::require_non_negative(object, "stiffness", p.stiffness);
    if (p.stiffness == 0.0) {
      detail::require_positive(object, "reference_velocity", p.reference_velocity);
      if constexpr (ImpactVelocity::per_contact)
        detail::require_positive(object, "min_impact_velocity", p.min_impact_velocity);
    }
    detail::require(std::isfinite(p.damping), object, "damping", p.damping,
                    "[0, inf) N s/m, or < 0 for damping from restitution");
    detail::require(std::isfinite(p.damping_ratio), object, "damping_ratio", p.damping_ratio,
                    "[0, inf), or < 0 for damping from restitution");
    detail::require(hertz_equivalent::valid(p.equivalence), object, "equivalence",
                    static_cast<int>(p.equivalence),
                    "Equivalence::energy, Equivalence::overlap or Equivalence::time");
  }

  /// K [N/m] of a contact with effective radius r_eff, mass m_eff and impact velocity v.
  static double stiffness(const PairProperties& pair, const Params& p, double r_eff, double m_eff,
                          double v) {
    if (p.stiffness > 0.0) return p.stiffness;
    return hertz_equivalent::linear_stiffness(p.equivalence, pair, r_eff, m_eff, v);
  }
  /// K [N/m] at the reference velocity.
  static double stiffness(const PairProperties& pair, const Params& p, double r_eff, double m_eff) {
    return stiffness(pair, p, r_eff, m_eff, p.reference_velocity);
  }
  /// eta [N s/m].
  static double damping(const PairProperties& pair, const Params& p, double k, double m_eff) {
    if (p.damping >= 0.0) return p.damping;
    return 2.0 * (p.damping_ratio >= 0.0 ? p.damping_ratio : pair.damping_ratio()) *
           std::sqrt(m_eff * k);
  }

  template <int D>
  GRAIN_INLINE static NormalResult force(const ContactGeometry<D>& g, const PairProperties& pair,
                                         const Params& p, History<D>& h) {
    double k = p.stiffness;
    if (k <= 0.0) {
      const double v = detail::impact_velocity<ImpactVelocity>(
          h, g.normal_velocity, p.reference_velocity, p.min_impact_velocity);
      k = hertz_equivalent::linear_stiffness(p.equivalence, pair, g.r_eff, g.m_eff, v);
    }
    const double eta = damping(pair, p, k, g.m_eff);
    const double fe = k * g.overlap;
    double f = fe + eta * g.normal_velocity;
    if (p.no_cohesion && f < 0.0) f = 0.0;
    return {.force = f,
            .stiffness = k,
            .damping = eta,
            .elastic_energy = 0.5 * k * g.overlap * g.overlap,
            .viscous = f - fe};
  }

  /// Stiffness of a contact with impact velocity v [m/s] (for the critical time step): K at
  /// `reference_velocity`, or at max(v, reference_velocity) for per-contact velocities.
  static double stiffness_estimate(const PairProperties& pair, const Params& p, double r_eff,
                                   double m_eff, double v) {
    return stiffness(pair, p, r_eff, m_eff,
                     detail::impact_velocity_estimate<ImpactVelocity>(v, p.reference_velocity));
  }
};

/// Linear spring-dashpot with the Hertz-equivalent stiffness at `reference_velocity`.
using LinearSpringDashpot = BasicLinearSpringDashpot<ReferenceVelocity>;
/// Linear spring-dashpot with the Hertz-equivalent stiffness at each contact's impact velocity.
using LinearSpringDashpotPerContact = BasicLinearSpringDashpot<PerContactVelocity>;

} // namespace grain::normal
