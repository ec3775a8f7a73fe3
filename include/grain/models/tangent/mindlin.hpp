#pragma once
/// \file mindlin.hpp
/// Mindlin no-slip tangential stiffness for Hertz contacts, with a dashpot and a Coulomb slider
/// (Mindlin, J. Appl. Mech. 16 (1949) 259; the "Hertz-Mindlin no-slip" model of Tsuji et al.
/// and of LIGGGHTS' `tangential_history` with `hertz`).
///
///   K_t = 8 G* a,  a = sqrt(R* delta)                                           [N/m]
///   F_t = -K_t xi - eta_t v_t,  |F_t| <= mu |F_n|                                   [N]
///
/// G* [Pa] is the pair's effective shear modulus, 1/G* = (2 - nu1)/G1 + (2 - nu2)/G2, R* [m]
/// the effective radius and delta [m] the normal overlap. xi [m] is the elongation vector in the
/// tangent plane, rotated with the contact and truncated at the Coulomb limit (stick_slip.hpp);
/// sticking is tested against mu_s, sliding carries mu_d |F_n|. Elastic energy 1/2 K_t |xi|^2.
///
/// - eta_t [N s/m]: `damping` if >= 0, else the normal damping scaled by the stiffnesses,
///   eta_t = eta_n sqrt(K_t / K_n) (a sticking contact moves with m*/kappa, so its damping ratio
///   is sqrt(kappa) times the normal one) with K_n the normal model's tangent stiffness (for
///   normal::Hertz<TsujiDamping> this is LIGGGHTS' gamma_t = -2 sqrt(5/6) beta sqrt(S_t m*)).
///
/// Defaults: damping -1 (normal damping ratio).

#include <cmath>
#include <grain/models/tangent/stick_slip.hpp>

namespace grain::tangent {

struct Mindlin {
  static constexpr Slot slot = Slot::tangent;
  static constexpr const char* name = "Mindlin";

  struct Params {
    double damping = -1.0; ///< eta_t [N s/m]; < 0 = the normal model's damping ratio
  };
  template <int D>
  using History = detail::SpringHistory<D>;

  static void validate(const Params& p) {
    grain::detail::require(std::isfinite(p.damping), "tangent::Mindlin", "damping", p.damping,
                           "[0, inf), or < 0 for the normal damping ratio");
  }

  template <int D>
  static void reverse(History<D>& h) {
    detail::negate<D>(h.spring);
  }

  /// K_t = 8 G* sqrt(R* delta) [N/m].
  template <int D>
  static double stiffness(const ContactGeometry<D>& g, const PairProperties& pair) {
    return 8.0 * pair.shear_eff * std::sqrt(g.r_eff * std::max(g.overlap, 0.0));
  }

  template <int D>
  GRAIN_INLINE static TangentResult<D> force(const ContactGeometry<D>& g,
                                             const PairProperties& pair, const NormalResult& n,
                                             const Params& p, History<D>& h, double dt) {
    const double kt = stiffness<D>(g, pair);
    const double eta = p.damping >= 0.0 ? p.damping : detail::normal_ratio_damping(n, kt);
    return detail::spring_step<D>(g, pair, n.force, detail::LinearSpring{kt, eta}, h.spring,
                                  &h.sliding, dt);
  }
};

} // namespace grain::tangent
