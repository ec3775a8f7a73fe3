#pragma once
/// \file dashpot.hpp
/// Linear tangential dashpot without slider (viscous, no friction limit).
///
///   F_t = -eta_t v_t                                                               [N]
///
/// v_t [m/s] is the tangential relative velocity at the contact point. No history.
///
/// - eta_t [N s/m]: `damping` if > 0, else `damping_ratio` zeta_t times the critical damping of
///   the tangential motion on the normal model's tangent stiffness k_n,
///   eta_t = 2 zeta_t sqrt(m* k_n / kappa), kappa = 1 + m R^2/I (7/2 spheres, 3 solid disks;
///   `kappa` > 1 overrides, e.g. 3.5 for 2D disks with sphere mass).
///
/// Defaults: damping 0 (derived), damping_ratio 1, kappa 0 (by dimension).

#include <grain/models/tangent/stick_slip.hpp>

namespace grain::tangent {

namespace detail {
/// Dashpot coefficient [N s/m] of the dashpot models.
template <int D>
inline double dashpot_damping(double given, double ratio, double kappa_given,
                              const ContactGeometry<D>& g, const NormalResult& n) {
  if (given > 0.0) return given;
  return 2.0 * ratio * std::sqrt(g.m_eff * std::max(n.stiffness, 0.0) / kappa<D>(kappa_given));
}
inline void validate_dashpot(const char* m, double damping, double ratio, double kappa) {
  grain::detail::require_non_negative(m, "damping", damping);
  grain::detail::require_non_negative(m, "damping_ratio", ratio);
  validate_kappa(m, kappa);
}
} // namespace detail

struct Dashpot {
  static constexpr Slot slot = Slot::tangent;
  static constexpr const char* name = "dashpot";

  struct Params {
    double damping = 0.0;       ///< eta_t [N s/m]; 0 = damping_ratio x critical
    double damping_ratio = 1.0; ///< zeta_t, used if damping = 0
    double kappa = 0.0;         ///< 1 + m R^2/I; 0 = 7/2 (3D) or 3 (2D)
  };
  template <int D>
  struct History {};

  static void validate(const Params& p) {
    detail::validate_dashpot("tangent::Dashpot", p.damping, p.damping_ratio, p.kappa);
  }

  template <int D>
  GRAIN_INLINE static TangentResult<D> force(const ContactGeometry<D>& g, const PairProperties&,
                                             const NormalResult& n, const Params& p, History<D>&,
                                             double) {
    TangentResult<D> r;
    if (!(g.overlap > 0.0)) return r;
    r.force = -detail::dashpot_damping<D>(p.damping, p.damping_ratio, p.kappa, g, n) *
              g.tangential_velocity;
    return r;
  }
};

} // namespace grain::tangent
