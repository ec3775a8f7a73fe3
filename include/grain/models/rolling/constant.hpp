#pragma once
/// \file constant.hpp
/// Constant directional rolling resistance ("model A" of Ai, Chen, Rotter & Ooi, Powder
/// Technol. 206 (2011) 269; Zhou, Wright, Yang, Xu & Yu, Physica A 269 (1999) 536).
///
///   M_i = -mu_r R* |F_n| w_r / |w_r|,   M_j = -M_i   (M = 0 for w_r = 0)          [N m]
///
/// mu_r [-] rolling-resistance coefficient (a length mu_r R* is the lever arm of the normal
/// force), R* [m] effective radius, F_n [N] normal force, w_r [rad/s] the rolling part of
/// w_i - w_j (relative_rotation.hpp). The torque on the partner is equal and opposite, so the
/// pair's angular momentum is conserved (the seed program added the same torque to both bodies).
/// The model has no static regime: a contact that must hold a rolling moment below
/// mu_r R* |F_n| (a ball at rest on a gentle slope) chatters about w_r = 0 with an angular
/// velocity of order mu_r R* |F_n| dt / I; use rolling::EPSD where that matters. No history.
///
/// - mu_r: `coefficient` if >= 0, else the pair's `rolling_friction` (default -1).

#include <algorithm>
#include <grain/models/rolling/relative_rotation.hpp>

namespace grain::rolling {

struct Constant {
  static constexpr Slot slot = Slot::rolling;
  static constexpr const char* name = "constant";

  struct Params {
    double coefficient = -1.0; ///< mu_r [-]; < 0 = the pair's rolling_friction
  };
  template <int D>
  struct History {};

  static void validate(const Params& p) {
    detail::validate_coefficient("rolling::Constant", p.coefficient);
  }

  template <int D, class A>
  GRAIN_INLINE static void torque(const ContactGeometry<D>& g, const PairProperties& pair,
                                  const NormalResult& n, const Params& p, History<D>&, double,
                                  A& ti, A& tj) {
    if (!(g.overlap > 0.0)) return;
    const A w = detail::rolling_omega(g);
    const double s = norm(w);
    if (!(s > 0.0)) return;
    const double mr = detail::coefficient(p.coefficient, pair) * g.r_eff * std::max(n.force, 0.0);
    detail::apply<A>(A((-mr / s) * w), ti, tj);
  }
};

} // namespace grain::rolling
