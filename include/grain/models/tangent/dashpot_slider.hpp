#pragma once
/// \file dashpot_slider.hpp
/// Dashpot with a Coulomb slider (Haff & Werner, Powder Technol. 48 (1986) 239): a viscous
/// regularisation of Coulomb friction.
///
///   F_t = -eta_t v_t,  |F_t| <= mu |F_n|                                           [N]
///
/// v_t [m/s] is the tangential relative velocity at the contact point. The contact is in the
/// viscous ("sticking") regime while |eta_t v_t| <= mu_s |F_n| (mu_d |F_n| right after a
/// sliding step) and slides with mu_d |F_n| against v_t otherwise. History: the sliding state.
/// A static tangential load F is carried with a creep velocity F/eta_t; choose eta_t large
/// (within the stability limit eta_t kappa dt / m* < 2) to approach Coulomb friction.
///
/// - eta_t [N s/m]: `damping` if > 0, else `damping_ratio` zeta_t times the critical damping of
///   the tangential motion on the normal model's tangent stiffness k_n,
///   eta_t = 2 zeta_t sqrt(m* k_n / kappa), kappa = 1 + m R^2/I (7/2 spheres, 3 solid disks).
/// - mu_s, mu_d: the pair's static and dynamic friction coefficients.
///
/// Defaults: damping 0 (derived), damping_ratio 1, kappa 0 (by dimension).

#include <grain/models/tangent/dashpot.hpp>

namespace grain::tangent {

struct DashpotSlider {
  static constexpr Slot slot = Slot::tangent;
  static constexpr const char* name = "dashpot-slider";

  struct Params {
    double damping = 0.0;       ///< eta_t [N s/m]; 0 = damping_ratio x critical
    double damping_ratio = 1.0; ///< zeta_t, used if damping = 0
    double kappa = 0.0;         ///< 1 + m R^2/I; 0 = 7/2 (3D) or 3 (2D)
  };
  template <int D>
  using History = detail::SlipHistory<D>;

  static void validate(const Params& p) {
    detail::validate_dashpot("tangent::DashpotSlider", p.damping, p.damping_ratio, p.kappa);
  }

  template <int D>
  GRAIN_INLINE static TangentResult<D> force(const ContactGeometry<D>& g,
                                             const PairProperties& pair, const NormalResult& n,
                                             const Params& p, History<D>& h, double) {
    TangentResult<D> r;
    if (!(g.overlap > 0.0)) {
      h.sliding = false;
      return r;
    }
    r.force = -detail::dashpot_damping<D>(p.damping, p.damping_ratio, p.kappa, g, n) *
              g.tangential_velocity;
    r.sliding = detail::coulomb<D>(r.force, pair, n.force, h.sliding);
    h.sliding = r.sliding;
    return r;
  }
};

} // namespace grain::tangent
