#pragma once
/// \file spring.hpp
/// Linear tangential spring without slider (elastic, no friction limit).
///
///   F_t = -k_t xi                                                                  [N]
///
/// xi [m] is the elongation vector in the tangent plane, accumulated from the tangential
/// relative velocity at the contact point and rotated with the contact (see stick_slip.hpp).
/// Elastic energy 1/2 k_t |xi|^2 [J]. Without a slider the contact never slides: use it for
/// no-slip (mu -> infinity) tests such as the tangential rebound of an impact (Maw, Barber &
/// Fawcett, Wear 38 (1976) 101).
///
/// - k_t [N/m]: `stiffness` if > 0, else `stiffness_ratio` x the normal model's tangent
///   stiffness; the default ratio (1 - nu)/(1 - nu/2) (Mindlin, J. Appl. Mech. 16 (1949) 259)
///   gives 8 G* a for a Hertz contact of equal materials.
///
/// Defaults: stiffness 0 (derived), stiffness_ratio 0 (Mindlin ratio).

#include <grain/models/tangent/stick_slip.hpp>

namespace grain::tangent {

struct Spring {
  static constexpr Slot slot = Slot::tangent;
  static constexpr const char* name = "spring";

  struct Params {
    double stiffness = 0.0;       ///< k_t [N/m]; 0 = stiffness_ratio x normal stiffness
    double stiffness_ratio = 0.0; ///< k_t/k_n; 0 = (1 - nu)/(1 - nu/2)
  };
  template <int D>
  using History = detail::ElasticHistory<D>;

  /// The Mindlin stiffness ratio of the pair worked out once (see Interaction::resolve).
  static Params resolve(Params p, const PairProperties& pair) {
    return detail::resolve_stiffness_ratio(p, pair);
  }
  static void validate(const Params& p) {
    grain::detail::require_non_negative("tangent::Spring", "stiffness", p.stiffness);
    grain::detail::require_non_negative("tangent::Spring", "stiffness_ratio", p.stiffness_ratio);
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
    return detail::spring_step<D>(g, pair, n.force, law, h.spring, nullptr, dt);
  }
};

} // namespace grain::tangent
