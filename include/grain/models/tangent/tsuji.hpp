#pragma once
/// \file tsuji.hpp
/// Nonlinear spring-dashpot-slider of Tsuji, Tanaka & Ishida (Powder Technol. 71 (1992) 239),
/// in the seed program's form, with a vector history.
///
///   K_t = sqrt(2 R*) E* sqrt(delta) / ((2 - nu)(1 + nu))                        [N/m]
///   F_t = -K_t xi - eta_t v_t,  |F_t| <= mu |F_n|                                   [N]
///
/// E* [Pa] effective Young's modulus, R* [m] effective radius, delta [m] normal overlap, nu the
/// mean Poisson ratio of the pair. For two particles of one material K_t is
/// 1/(2 sqrt(2) (1 - nu^2)) times Mindlin's 8 G* a (0.39 at nu = 0.3). xi [m] is the elongation
/// vector in the tangent plane, rotated with the contact and truncated at the Coulomb limit
/// (stick_slip.hpp); sticking against mu_s, sliding at mu_d.
///
/// - eta_t [N s/m]: `damping` if >= 0, else the normal model's damping coefficient eta_n =
///   dF_n/d(delta rate) (Tsuji's choice: the tangential dashpot equals the normal one).
///
/// Defaults: damping -1 (normal damping coefficient).

#include <cmath>
#include <grain/models/tangent/stick_slip.hpp>

namespace grain::tangent {

struct Tsuji {
  static constexpr Slot slot = Slot::tangent;
  static constexpr const char* name = "Tsuji";

  struct Params {
    double damping = -1.0; ///< eta_t [N s/m]; < 0 = the normal damping coefficient
  };
  template <int D>
  using History = detail::SpringHistory<D>;

  static void validate(const Params& p) {
    grain::detail::require(std::isfinite(p.damping), "tangent::Tsuji", "damping", p.damping,
                           "[0, inf), or < 0 for the normal damping coefficient");
  }

  template <int D>
  static void reverse(History<D>& h) {
    detail::negate<D>(h.spring);
  }

  /// K_t [N/m].
  template <int D>
  static double stiffness(const ContactGeometry<D>& g, const PairProperties& pair) {
    const double nu = pair.poisson_avg;
    return std::sqrt(2.0 * g.r_eff) * pair.young_eff * std::sqrt(std::max(g.overlap, 0.0)) /
           ((2.0 - nu) * (1.0 + nu));
  }

  template <int D>
  GRAIN_INLINE static TangentResult<D> force(const ContactGeometry<D>& g,
                                             const PairProperties& pair, const NormalResult& n,
                                             const Params& p, History<D>& h, double dt) {
    const double eta = p.damping >= 0.0 ? p.damping : std::max(n.damping, 0.0);
    return detail::spring_step<D>(g, pair, n.force,
                                  detail::LinearSpring{stiffness<D>(g, pair), eta}, h.spring,
                                  &h.sliding, dt);
  }
};

} // namespace grain::tangent
