#pragma once
/// \file di_renzo_di_maio.hpp
/// Nonlinear spring-(dashpot-)slider of Di Renzo & Di Maio (Chem. Eng. Sci. 60 (2005) 1303,
/// "An improved integral non-linear model for the contact of particles in distinct element
/// simulations"), with a vector history.
///
///   K_t = 16/3 G* sqrt(R* delta)                                               [N/m]
///   F_t = -K_t xi - eta_t v_t,  |F_t| <= mu |F_n|                                   [N]
///
/// K_t is 2/3 of Mindlin's no-slip stiffness 8 G* a (a = sqrt(R* delta)), a stiffness that does
/// not depend on the tangential load history. G* [Pa] effective shear modulus, R* [m] effective
/// radius, delta [m] normal overlap. xi [m] is the elongation vector in the tangent plane, rotated
/// with the contact and truncated at the Coulomb limit (stick_slip.hpp); sticking against mu_s,
/// sliding at mu_d.
///
/// - eta_t [N s/m]: `damping`; the original model has no viscous part (default 0).

#include <cmath>
#include <grain/models/tangent/stick_slip.hpp>

namespace grain::tangent {

struct DiRenzoDiMaio {
  static constexpr Slot slot = Slot::tangent;
  static constexpr const char* name = "Di Renzo-Di Maio";

  struct Params {
    double damping = 0.0; ///< eta_t [N s/m]
  };
  template <int D>
  using History = detail::SpringHistory<D>;

  static void validate(const Params& p) {
    grain::detail::require_non_negative("tangent::DiRenzoDiMaio", "damping", p.damping);
  }

  template <int D>
  static void reverse(History<D>& h) {
    detail::negate<D>(h.spring);
  }

  /// K_t = 16/3 G* sqrt(R* delta) [N/m].
  template <int D>
  static double stiffness(const ContactGeometry<D>& g, const PairProperties& pair) {
    return 16.0 / 3.0 * pair.shear_eff * std::sqrt(g.r_eff * std::max(g.overlap, 0.0));
  }

  template <int D>
  GRAIN_INLINE static TangentResult<D> force(const ContactGeometry<D>& g,
                                             const PairProperties& pair, const NormalResult& n,
                                             const Params& p, History<D>& h, double dt) {
    return detail::spring_step<D>(g, pair, n.force,
                                  detail::LinearSpring{stiffness<D>(g, pair), p.damping}, h.spring,
                                  &h.sliding, dt);
  }
};

} // namespace grain::tangent
