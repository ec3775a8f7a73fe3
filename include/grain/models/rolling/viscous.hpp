#pragma once
/// \file viscous.hpp
/// Viscous rolling resistance (Brilliantov & Poschel, Europhys. Lett. 42 (1998) 511: the rolling
/// friction of viscoelastic spheres is proportional to the rolling velocity), in the form of
/// the seed program and of Ai, Chen, Rotter & Ooi, Powder Technol. 206 (2011) 269 (model B).
///
///   M_i = -mu_r R* |F_n| v_r w_r / |w_r| = -mu_r R*^2 |F_n| w_r,   M_j = -M_i      [N m]
///
/// mu_r [s/m] rolling-resistance coefficient, R* [m] effective radius, F_n [N] normal force,
/// w_r [rad/s] the rolling part of w_i - w_j, v_r = R* |w_r| [m/s] the rolling velocity
/// (relative_rotation.hpp). A ball of radius R rolling on a plane slows as
/// v = v0 exp(-(5/7) mu_r g t) (disk: 2/3 instead of 5/7). Equal and opposite torques conserve
/// the pair's angular momentum. No history.
///
/// - mu_r: `coefficient` if >= 0, else the pair's `rolling_friction`, read in s/m (default -1).

#include <algorithm>
#include <grain/models/rolling/relative_rotation.hpp>

namespace grain::rolling {

struct Viscous {
  static constexpr Slot slot = Slot::rolling;
  static constexpr const char* name = "viscous";

  struct Params {
    double coefficient = -1.0; ///< mu_r [s/m]; < 0 = the pair's rolling_friction
  };
  template <int D>
  struct History {};

  static void validate(const Params& p) {
    detail::validate_coefficient("rolling::Viscous", p.coefficient);
  }

  template <int D, class A>
  GRAIN_INLINE static void torque(const ContactGeometry<D>& g, const PairProperties& pair,
                                  const NormalResult& n, const Params& p, History<D>&, double,
                                  A& ti, A& tj) {
    if (!(g.overlap > 0.0)) return;
    const double c =
        detail::coefficient(p.coefficient, pair) * g.r_eff * g.r_eff * std::max(n.force, 0.0);
    detail::apply<A>(A(-c * detail::rolling_omega(g)), ti, tj);
  }
};

} // namespace grain::rolling
