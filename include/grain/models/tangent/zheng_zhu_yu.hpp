#pragma once
/// \file zheng_zhu_yu.hpp
/// Nonlinear spring-dashpot-slider of Zheng, Zhu & Yu (Powder Technol. 226 (2012) 130, "Finite
/// element analysis of the contact forces between a viscoelastic sphere and rigid plane"), in
/// the seed program's form and with a vector history.
///
///   delta_t,max = mu_s delta (2 - nu) / (2 (1 - nu))                                 [m]
///   s = 1 - min(|xi|, delta_t,max) / delta_t,max                                     [-]
///   c = eta_t/(2 G* delta_t,max) max(0, 1 - 0.4 eta_t |v_t|/(2 G* delta_t,max))
///       1.5 mu_s |F_n| sqrt(s)                                                    [N s/m]
///   F_t = -mu_s |F_n| (1 - s^(3/2)) xi/|xi| - c v_t,  |F_t| <= mu |F_n|                [N]
///
/// delta [m] normal overlap, nu mean Poisson ratio, G* [Pa] effective shear modulus, v_t [m/s]
/// tangential relative velocity, xi [m] the elongation vector in the tangent plane (rotated with
/// the contact, stick_slip.hpp). The spring is the Mindlin-Deresiewicz loading curve (slope
/// 3 mu_s |F_n| / (2 delta_t,max) at xi = 0); the dashpot coefficient eta_t has the units of a
/// viscosity. The factor max(0, ...) keeps the dashpot from turning into a source of energy
/// at slip rates above 2.5 (2 G* delta_t,max)/eta_t, where the seed's expression changes sign.
/// Sticking is tested against mu_s; a sliding contact carries mu_d |F_n| and its elongation is
/// truncated to the point of the curve where the spring holds mu_d |F_n|.
///
/// - eta_t [Pa s]: `viscosity` (default 0: no dashpot).

#include <algorithm>
#include <cmath>
#include <grain/models/tangent/langston_tuzun_heyes.hpp>
#include <grain/models/tangent/stick_slip.hpp>

namespace grain::tangent {

struct ZhengZhuYu {
  static constexpr Slot slot = Slot::tangent;
  static constexpr const char* name = "Zheng-Zhu-Yu";

  struct Params {
    double viscosity = 0.0; ///< eta_t [Pa s]
  };
  template <int D>
  using History = detail::SpringHistory<D>;

  static void validate(const Params& p) {
    grain::detail::require_non_negative("tangent::ZhengZhuYu", "viscosity", p.viscosity);
  }

  template <int D>
  static void reverse(History<D>& h) {
    detail::negate<D>(h.spring);
  }

  struct Law : detail::SaturatingSpring {
    double eta = 0.0, shear = 0.0;
    double damping(double x, double speed) const {
      if (dmax <= 0.0 || shear <= 0.0) return 0.0;
      const double tau = eta / (2.0 * shear * dmax); // [s/m]
      return tau * std::max(0.0, 1.0 - 0.4 * tau * speed) * 1.5 * fs * root_remaining(x);
    }
  };

  template <int D>
  GRAIN_INLINE static TangentResult<D> force(const ContactGeometry<D>& g,
                                             const PairProperties& pair, const NormalResult& n,
                                             const Params& p, History<D>& h, double dt) {
    Law law;
    law.fs = detail::static_friction(pair) * std::max(n.force, 0.0);
    law.dmax = detail::full_slip_elongation<D>(g, pair);
    law.eta = p.viscosity;
    law.shear = pair.shear_eff;
    return detail::spring_step<D>(g, pair, n.force, law, h.spring, &h.sliding, dt);
  }
};

} // namespace grain::tangent
