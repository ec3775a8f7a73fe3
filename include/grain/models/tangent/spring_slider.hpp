#pragma once
/// \file spring_slider.hpp
/// Linear spring with a Coulomb slider (Cundall & Strack, Geotechnique 29 (1979) 47).
///
///   F_t = -k_t xi,  |F_t| <= mu |F_n|                                              [N]
///
/// xi [m] is the elongation vector in the tangent plane, rotated with the contact and truncated
/// at the Coulomb limit (see stick_slip.hpp): sticking is tested against mu_s, a sliding contact
/// carries mu_d |F_n| and its spring holds exactly that force. Elastic energy 1/2 k_t |xi|^2.
///
/// - k_t [N/m]: `stiffness` if > 0, else `stiffness_ratio` x the normal model's tangent
///   stiffness; the default ratio (1 - nu)/(1 - nu/2) gives 8 G* a for a Hertz contact.
/// - mu_s, mu_d: the pair's static and dynamic friction coefficients.
///
/// Defaults: stiffness 0 (derived), stiffness_ratio 0 (Mindlin ratio).

#include <grain/models/tangent/stick_slip.hpp>

namespace grain::tangent {

struct SpringSlider {
  static constexpr Slot slot = Slot::tangent;
  static constexpr const char* name = "spring-slider";

  struct Params {
    double stiffness = 0.0;       ///< k_t [N/m]; 0 = stiffness_ratio x normal stiffness
    double stiffness_ratio = 0.0; ///< k_t/k_n; 0 = (1 - nu)/(1 - nu/2)
  };
  template <int D>
  using History = detail::SpringHistory<D>;

  /// The Mindlin stiffness ratio of the pair worked out once (see Interaction::resolve).
  static Params resolve(Params p, const PairProperties& pair) {
    return detail::resolve_stiffness_ratio(p, pair);
  }
  static void validate(const Params& p) {
    grain::detail::require_non_negative("tangent::SpringSlider", "stiffness", p.stiffness);
    grain::detail::require_non_negative("tangent::SpringSlider", "stiffness_ratio",
                                        p.stiffness_ratio);
  }

  template <int D>
  static void reverse(History<D>& h) {
    detail::negate<D>(h.spring);
  }

  template <int D>
  GRAIN_INLINE static TangentResult<D> force(const ContactGeometry<D>& g,
                                             const PairProperties& pair, const NormalResult& n,
                                             const Params& p, History<D>& h, double dt) {
    const detail::LinearSpring law{
        detail::linear_stiffness(p.stiffness, p.stiffness_ratio, pair, n), 0.0};
    return detail::spring_step<D>(g, pair, n.force, law, h.spring, &h.sliding, dt);
  }
};

} // namespace grain::tangent
