#pragma once
/// \file walton_braun.hpp
/// Linear elasto-plastic (hysteretic) normal force of Walton & Braun (J. Rheol. 30 (1986) 949),
/// with the options of DEMLab's "elastoplastic_linear" model, tracked from the contact's actual
/// history. No dashpot; the force is never attractive.
///
///   loading (delta >= delta_max, the largest overlap so far):  F = K_L delta       (capped)
///   unloading and re-loading (delta < delta_max):             F = K_U (delta - delta_res) >= 0
///   delta_res = delta_max - F_max / K_U                                               [m]
///
/// F_max [N] is the force reached at delta_max; without a cap F_max = K_L delta_max and
/// delta_res = delta_max (1 - K_L/K_U). Re-loading before the contact has fully unloaded climbs
/// back along the unloading line up to (delta_max, F_max) and only then continues on the loading
/// line; below delta_res the force is zero (the pair has separated from its plastic dent while
/// the undeformed shapes still overlap).
///
/// - K_L [N/m]: `stiffness` if given (> 0); otherwise Hertz-equivalent at the impact velocity v
///   (X = (v R* E*^2 sqrt(m*))^(2/5), see hertz_equivalent.hpp):
///   - `energy` (default) and `overlap`: K_L = (16/15)^(4/5) X. The loading branch is undamped,
///     so the contact reaches the maximum overlap and strain energy of the undamped Hertz impact
///     (the two criteria coincide for this model).
///   - `time`: K_L = (pi/c_t)^2 X (1 + e)^2 / 4, so that the Walton-Braun contact duration
///     (pi/2) sqrt(m*/K_L) (1 + e) equals the undamped Hertz one, c_t (m*^2/(R* E*^2 v))^(1/5).
///     e is the model's own restitution: the pair's e for constant unloading; for a given K_U,
///     e = sqrt(K_L/K_U), and with A = (pi/c_t)^2 X / 4, sqrt(K_L) = sqrt(A) / (1 - sqrt(A/K_U))
///     (K_L = K_U, elastic, when A >= K_U / 4); for variable
///     unloading e = (1 + S v sqrt(m*/K_L))^(-1/2) depends on K_L, and K_L = A s^2 (A =
///     (pi/c_t)^2 X / 4, s = 1 + e) solves s^3 + (b - 2) s^2 - 2 b s + b = 0 on (1, 2],
///     b = S v sqrt(m*/A) (Newton's method). DEMLab reuses the linear spring-dashpot factor
///     1 + beta^-2 here, which does not match the Walton-Braun duration.
///   v is `reference_velocity` (`WaltonBraun`) or the contact's impact velocity measured at its
///   first step (`WaltonBraunPerContact`; below `min_impact_velocity` the reference is used).
/// - K_U [N/m]: `Unloading::constant` (default): K_U = K_L / e^2 (e: the pair's restitution), so
///   an isolated contact rebounds with e = sqrt(K_L/K_U) exactly. `Unloading::variable`:
///   K_U = K_L + S F_max with S = `unloading_slope` [1/m], so e = (1 + S v sqrt(m*/K_L))^(-1/2)
///   decreases with the impact velocity. `Unloading::given`: K_U = `unloading_stiffness` [N/m]
///   (the seed's UnloadingStiffCoeffValue), so e = sqrt(K_L/K_U); a K_U below the contact's K_L
///   is taken as K_L (an elastic contact: a smaller one would give back more energy than it
///   took).
/// - `max_force` [N] (0 = none): the loading force is capped (perfectly plastic beyond it); the
///   unloading line then starts from (delta_max, max_force).
///
/// DEMLab computes the residual overlap a priori from the impact velocity, delta_res =
/// v sqrt(m*/K_L) (1 - e^2), which is wrong for the variable unloading (where the true value is
/// delta_max (1 - K_L/K_U)), for a capped force and for any contact that is not an isolated
/// impact; it also switches branches on the sign of d(delta)/dt, so re-loading jumps to the
/// loading line and a contact at rest carries no force. Here everything follows from delta and
/// the tracked delta_max and F_max.
///
/// Isolated impact without cap: delta_max = v sqrt(m*/K_L), F_max = v sqrt(m* K_L),
/// t_c = (pi/2) sqrt(m*/K_L) (1 + sqrt(K_L/K_U)), e = sqrt(K_L/K_U).
/// Result: `stiffness` = K_L while the contact carries a force, on every branch (loading,
/// unloading, cap), 0 once separated. It is the stiffness the tangential and rolling models scale
/// with (k_t = ratio K_L, as in Walton and Braun and the seed program): reporting the unloading
/// slope K_U = K_L / e^2 instead would multiply a stuck tangential spring's force by 1/e^2 at the
/// turn from loading to unloading, with no tangential motion, creating energy.
/// Below the residual overlap the result is `detached` (no force, stiffness 0, no heat flow).
/// The slopes of the force itself are K_L and K_U (see `unloading_stiffness`);
/// damping 0; elastic energy = the energy the contact gives back on unloading, F^2 / (2 K_U).
/// History: delta_max and F_max (two doubles; plus the impact velocity for
/// `WaltonBraunPerContact`).

#include <algorithm>
#include <cmath>
#include <grain/models/concepts.hpp>
#include <grain/models/normal/hertz_equivalent.hpp>
#include <type_traits>

namespace grain::normal {

/// Unloading stiffness of `WaltonBraun`.
enum class Unloading {
  constant, ///< K_U = K_L / e^2 (default)
  variable, ///< K_U = K_L + S F_max
  given     ///< K_U = Params::unloading_stiffness
};

template <class ImpactVelocity = ReferenceVelocity>
struct BasicWaltonBraun {
  static_assert(std::is_same_v<ImpactVelocity, ReferenceVelocity> ||
                    std::is_same_v<ImpactVelocity, PerContactVelocity>,
                "grain::normal::BasicWaltonBraun: the argument must be normal::ReferenceVelocity "
                "or normal::PerContactVelocity");
  static constexpr Slot slot = Slot::normal;
  static constexpr const char* name =
      ImpactVelocity::per_contact ? "Walton-Braun, per-contact impact velocity" : "Walton-Braun";
  static constexpr const char* object =
      ImpactVelocity::per_contact ? "normal::WaltonBraunPerContact" : "normal::WaltonBraun";

  struct Params {
    double stiffness = 0.0;          ///< K_L [N/m]; 0 = Hertz-equivalent (see `equivalence`)
    double reference_velocity = 1.0; ///< impact velocity v for the Hertz-equivalent K_L [m/s]
    Equivalence equivalence = Equivalence::energy; ///< formulation of the Hertz-equivalent K_L
    Unloading unloading = Unloading::constant;     ///< unloading stiffness K_U
    double unloading_slope = 0.0; ///< S [1/m] of K_U = K_L + S F_max; required (> 0) if variable
    /// K_U [N/m] of Unloading::given; required (> 0) there
    double unloading_stiffness = 0.0;
    double max_force = 0.0; ///< cap of the normal force [N]; 0 = no cap
    /// per-contact velocity only: measured impact velocities below this use
    /// `reference_velocity` [m/s]
    double min_impact_velocity = 0.01;
  };
  template <int D>
  struct History : detail::ImpactRecord<ImpactVelocity> {
    double max_overlap = 0.0; ///< delta_max, the largest overlap of this contact so far [m]
    double max_force = 0.0;   ///< F_max, the force reached at delta_max [N]
  };

  static void validate(const Params& p) {
    detail::require_non_negative(object, "stiffness", p.stiffness);
    if (p.stiffness == 0.0) {
      detail::require_positive(object, "reference_velocity", p.reference_velocity);
      detail::require(hertz_equivalent::valid(p.equivalence), object, "equivalence",
                      static_cast<int>(p.equivalence),
                      "Equivalence::energy, Equivalence::overlap or Equivalence::time");
      if constexpr (ImpactVelocity::per_contact)
        detail::require_positive(object, "min_impact_velocity", p.min_impact_velocity);
    }
    detail::require(p.unloading == Unloading::constant || p.unloading == Unloading::variable ||
                        p.unloading == Unloading::given,
                    object, "unloading", static_cast<int>(p.unloading),
                    "Unloading::constant, Unloading::variable or Unloading::given");
    if (p.unloading == Unloading::given)
      detail::require(std::isfinite(p.unloading_stiffness) && p.unloading_stiffness > 0.0, object,
                      "unloading_stiffness", p.unloading_stiffness,
                      "(0, inf) N/m (required by Unloading::given)");
    if (p.unloading == Unloading::variable)
      detail::require(std::isfinite(p.unloading_slope) && p.unloading_slope > 0.0, object,
                      "unloading_slope", p.unloading_slope,
                      "(0, inf) 1/m (required by Unloading::variable)");
    detail::require_non_negative(object, "max_force", p.max_force);
  }

  /// Loading stiffness K_L [N/m] for impact velocity v [m/s].
  static double loading_stiffness(const PairProperties& pair, const Params& p, double r_eff,
                                  double m_eff, double v) {
    if (p.stiffness > 0.0) return p.stiffness;
    const double x = hertz_equivalent::scale(pair, r_eff, m_eff, v);
    if (p.equivalence != Equivalence::time) return hertz_equivalent::energy_coefficient * x;
    const double a = 0.25 * hertz_equivalent::time_coefficient * x;
    double s = 1.0 + pair.restitution;
    if (p.unloading == Unloading::given) {
      // K_L = A (1 + sqrt(K_L/K_U))^2: sqrt(K_L) = sqrt(A) / (1 - sqrt(A/K_U)); no solution
      // with K_L < K_U when A >= K_U/4: the contact is then elastic, K_L = K_U
      const double r = std::sqrt(a / p.unloading_stiffness);
      if (r >= 0.5) return p.unloading_stiffness;
      const double u = std::sqrt(a) / (1.0 - r);
      return u * u;
    }
    if (p.unloading == Unloading::variable) {
      // s^3 + (b - 2) s^2 - 2 b s + b = 0 on (1, 2]: increasing and convex there, so Newton's
      // method from s = 2 decreases monotonically to the root.
      const double b = p.unloading_slope * v * std::sqrt(m_eff / a);
      s = 2.0;
      for (int k = 0; k < 60; ++k) {
        const double poly = ((s + (b - 2.0)) * s - 2.0 * b) * s + b;
        const double slope = (3.0 * s + 2.0 * (b - 2.0)) * s - 2.0 * b;
        const double step = poly / slope;
        s -= step;
        if (std::abs(step) <= 1e-15 * s) break;
      }
    }
    return a * s * s;
  }
  /// Unloading stiffness K_U [N/m] after reaching the force f_max [N].
  static double unloading_stiffness(const PairProperties& pair, const Params& p, double k_load,
                                    double f_max) {
    if (p.unloading == Unloading::variable) return k_load + p.unloading_slope * f_max;
    if (p.unloading == Unloading::given) return std::max(p.unloading_stiffness, k_load);
    return k_load / (pair.restitution * pair.restitution);
  }

  template <int D>
  GRAIN_INLINE static NormalResult force(const ContactGeometry<D>& g, const PairProperties& pair,
                                         const Params& p, History<D>& h) {
    double kl = p.stiffness;
    if (kl <= 0.0) {
      const double v = detail::impact_velocity<ImpactVelocity>(
          h, g.normal_velocity, p.reference_velocity, p.min_impact_velocity);
      kl = loading_stiffness(pair, p, g.r_eff, g.m_eff, v);
    }
    const double d = g.overlap;
    NormalResult r;
    if (d >= h.max_overlap) {
      // loading line (first loading, or re-loading past the previous maximum)
      double f = kl * std::max(d, 0.0);
      const bool capped = p.max_force > 0.0 && f > p.max_force;
      if (capped) f = p.max_force;
      h.max_overlap = std::max(d, 0.0);
      h.max_force = f;
      const double ku = unloading_stiffness(pair, p, kl, f);
      r.force = f;
      r.stiffness = kl;
      r.elastic_energy = f * f / (2.0 * ku);
    } else {
      // unloading (or re-loading) line through (delta_max, F_max)
      const double ku = unloading_stiffness(pair, p, kl, h.max_force);
      const double residual = h.max_overlap - h.max_force / ku;
      if (d > residual) {
        r.force = ku * (d - residual);
        r.stiffness = kl;
        r.elastic_energy = r.force * r.force / (2.0 * ku);
      } else {
        r.detached = true; // off the dent: no force, no stiffness, no heat flow
      }
    }
    return r;
  }

  /// Residual overlap delta_res [m] of a contact with this history (0 before any loading).
  template <int D>
  static double residual_overlap(const PairProperties& pair, const Params& p, double k_load,
                                 const History<D>& h) {
    return h.max_overlap - h.max_force / unloading_stiffness(pair, p, k_load, h.max_force);
  }

  /// Unloading stiffness of an impact at velocity v [m/s] (for the critical time step):
  /// K_U with F_max = v sqrt(m* K_L) (or the cap).
  static double stiffness_estimate(const PairProperties& pair, const Params& p, double r_eff,
                                   double m_eff, double v) {
    const double kl = loading_stiffness(
        pair, p, r_eff, m_eff,
        detail::impact_velocity_estimate<ImpactVelocity>(v, p.reference_velocity));
    double f = v * std::sqrt(m_eff * kl);
    if (p.max_force > 0.0) f = std::min(f, p.max_force);
    return unloading_stiffness(pair, p, kl, f);
  }
};

/// Walton-Braun with the Hertz-equivalent loading stiffness at `reference_velocity`.
using WaltonBraun = BasicWaltonBraun<ReferenceVelocity>;
/// Walton-Braun with the Hertz-equivalent loading stiffness at each contact's impact velocity.
using WaltonBraunPerContact = BasicWaltonBraun<PerContactVelocity>;

} // namespace grain::normal
