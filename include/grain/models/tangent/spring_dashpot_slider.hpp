#pragma once
/// \file spring_dashpot_slider.hpp
/// Linear spring-dashpot-slider tangential force with an incremental spring (Cundall & Strack
/// 1979; history handling as in Luding, Granular Matter 10 (2008) 235).
///
/// History: the spring elongation xi [m], a vector in the tangent plane. Each step
/// 1. xi is rotated into the current tangent plane, keeping its length (the contact frame turns);
/// 2. xi += v_s dt (v_s: the tangential relative velocity at the contact point that moved the
///    contact over the step, `ContactGeometry::slip_velocity`);
/// 3. trial force F_t = -k_t xi - eta_t v_t [N];
/// 4. if |F_t| > mu |F_n| the contact slides: F_t is scaled to mu |F_n| and the spring is
///    truncated to the Coulomb limit, xi = -F_t / k_t (no damping while sliding).
///
/// - k_t [N/m]: `stiffness` if given, else `stiffness_ratio` x the normal model's tangent
///   stiffness; the default ratio (1 - nu)/(1 - nu/2) (nu: mean Poisson ratio of the pair) makes
///   k_t the Mindlin no-slip stiffness 8 G* a for a Hertz contact.
/// - eta_t [N s/m]: `damping` if given, else the normal damping scaled to the same damping ratio,
///   eta_t = eta_n sqrt(k_t / k_n).
/// - mu: the pair's friction coefficient (static while sticking, dynamic while sliding).

#include <grain/models/concepts.hpp>
#include <cmath>

namespace grain::tangent {

struct SpringDashpotSlider {
  static constexpr Slot slot = Slot::tangent;
  static constexpr const char* name = "spring-dashpot-slider";

  struct Params {
    double stiffness = 0.0;       ///< k_t [N/m]; 0 = stiffness_ratio x normal stiffness
    double stiffness_ratio = 0.0; ///< k_t/k_n; 0 = (1 - nu)/(1 - nu/2)
    double damping = -1.0;        ///< eta_t [N s/m]; < 0 = same damping ratio as normal
  };
  template <int D>
  struct History {
    PlainVec<D> spring{}; ///< elongation xi [m]
    bool sliding = false;
  };

  static void validate(const Params& p) {
    detail::require_non_negative("tangent::SpringDashpotSlider", "stiffness", p.stiffness);
    detail::require_non_negative("tangent::SpringDashpotSlider", "stiffness_ratio",
                                 p.stiffness_ratio);
    detail::require(std::isfinite(p.damping), "tangent::SpringDashpotSlider", "damping",
                    p.damping, "[0, inf), or < 0 for the normal damping ratio");
  }

  template <int D>
  static void reverse(History<D>& h) {
    for (auto& c : h.spring) c = -c;
  }

  template <int D>
  static TangentResult<D> force(const ContactGeometry<D>& g, const PairProperties& pair,
                                const NormalResult& n, const Params& p, History<D>& h,
                                double dt) {
    double kt = p.stiffness;
    if (kt <= 0.0) {
      const double nu = pair.poisson_avg;
      const double ratio = p.stiffness_ratio > 0.0 ? p.stiffness_ratio : (1.0 - nu) / (1.0 - 0.5 * nu);
      kt = ratio * n.stiffness;
    }
    const double eta = p.damping >= 0.0 ? p.damping
                       : n.stiffness > 0.0 ? n.damping * std::sqrt(kt / n.stiffness)
                                           : 0.0;
    // rotate the old spring into the current tangent plane, keeping its length
    Vec<D> xi = load<D>(h.spring);
    const double old2 = xi.squaredNorm();
    if (old2 > 0.0) {
      xi -= xi.dot(g.normal) * g.normal;
      const double new2 = xi.squaredNorm();
      if (new2 > 0.0) xi *= std::sqrt(old2 / new2);
    }
    xi += g.slip_velocity * dt;
    TangentResult<D> r;
    r.force = -kt * xi - eta * g.tangential_velocity;
    const double mu = h.sliding ? pair.friction : pair.friction_static;
    const double limit = mu * std::abs(n.force);
    const double f2 = r.force.squaredNorm();
    if (f2 > limit * limit) {
      // Coulomb: the force has the limit magnitude; the spring is truncated to it.
      const double dyn = pair.friction * std::abs(n.force);
      r.force *= dyn / std::sqrt(f2);
      xi = kt > 0.0 ? Vec<D>(-r.force / kt) : Vec<D>(Vec<D>::Zero());
      h.sliding = true;
      r.sliding = true;
    } else {
      h.sliding = false;
    }
    store<D>(h.spring, xi);
    r.elastic_energy = 0.5 * kt * xi.squaredNorm();
    return r;
  }
};

} // namespace grain::tangent
