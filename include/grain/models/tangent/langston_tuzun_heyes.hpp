#pragma once
/// \file langston_tuzun_heyes.hpp
/// Nonlinear spring-dashpot-slider of Langston, Tuzun & Heyes (Chem. Eng. Sci. 49 (1994) 1259),
/// the Mindlin-Deresiewicz loading curve with a stiffness-proportional dashpot, in the seed
/// program's form and with a vector history.
///
///   delta_t,max = mu_s delta (2 - nu) / (2 (1 - nu))                                 [m]
///   s = 1 - min(|xi|, delta_t,max) / delta_t,max                                     [-]
///   F_t = -mu_s |F_n| (1 - s^(3/2)) xi/|xi|
///         - eta_t sqrt(6 m* mu_s |F_n| sqrt(s) / delta_t,max) v_t,  |F_t| <= mu |F_n|     [N]
///
/// delta [m] normal overlap, nu mean Poisson ratio, m* [kg] effective mass, v_t [m/s]
/// tangential relative velocity, xi [m] the elongation vector in the tangent plane (rotated with
/// the contact, stick_slip.hpp). The spring's slope at xi = 0 is 3 mu_s |F_n| / (2 delta_t,max),
/// which for a Hertz normal force of one material is Mindlin's 8 G* a; the dashpot is eta_t
/// times the critical damping 2 sqrt(m* k) of that slope k. Sticking is tested against mu_s;
/// a sliding contact carries mu_d |F_n| and its elongation is truncated to the point of the
/// curve where the spring holds mu_d |F_n|, so |xi| <= delta_t,max always (with mu_s = mu_d this
/// is the seed's cap min(|delta_t|, delta_t,max), applied to the history instead of only to the
/// force). Elastic energy: the integral of the spring force along |xi|.
///
/// - eta_t [-]: `damping`, a dimensionless damping ratio (default 0: no dashpot).

#include <algorithm>
#include <cmath>
#include <grain/models/tangent/stick_slip.hpp>

namespace grain::tangent {

namespace detail {
/// delta_t,max = mu_s delta (2 - nu) / (2 (1 - nu)) [m].
template <int D>
inline double full_slip_elongation(const ContactGeometry<D>& g, const PairProperties& pair) {
  const double nu = pair.poisson_avg;
  return static_friction(pair) * std::max(g.overlap, 0.0) * (2.0 - nu) / (2.0 * (1.0 - nu));
}
} // namespace detail

struct LangstonTuzunHeyes {
  static constexpr Slot slot = Slot::tangent;
  static constexpr const char* name = "Langston-Tuzun-Heyes";

  struct Params {
    double damping = 0.0; ///< eta_t [-], dimensionless damping ratio
  };
  template <int D>
  using History = detail::SpringHistory<D>;

  static void validate(const Params& p) {
    grain::detail::require_non_negative("tangent::LangstonTuzunHeyes", "damping", p.damping);
  }

  template <int D>
  static void reverse(History<D>& h) {
    detail::negate<D>(h.spring);
  }

  struct Law : detail::SaturatingSpring {
    double eta = 0.0, m_eff = 0.0;
    double damping(double x, double) const {
      if (dmax <= 0.0) return 0.0;
      return eta * std::sqrt(6.0 * m_eff * fs * root_remaining(x) / dmax);
    }
  };

  template <int D>
  GRAIN_INLINE static TangentResult<D> force(const ContactGeometry<D>& g,
                                             const PairProperties& pair, const NormalResult& n,
                                             const Params& p, History<D>& h, double dt) {
    Law law;
    law.fs = detail::static_friction(pair) * std::max(n.force, 0.0);
    law.dmax = detail::full_slip_elongation<D>(g, pair);
    law.eta = p.damping;
    law.m_eff = g.m_eff;
    return detail::spring_step<D>(g, pair, n.force, law, h.spring, &h.sliding, dt);
  }
};

} // namespace grain::tangent
