#pragma once
/// \file slider.hpp
/// Rigid-plastic Coulomb slider: a sliding contact carries the dynamic friction force against
/// its slip velocity.
///
///   F_t = -mu_d |F_n| v_t / |v_t|   (F_t = 0 for v_t = 0)                         [N]
///
/// v_t [m/s] is the tangential relative velocity at the contact point. Without a spring or a
/// dashpot there is no sticking force: a contact whose slip has stopped carries no tangential
/// force, so the static coefficient mu_s has nothing to be compared with and is not used, and
/// a contact that must hold a static tangential load (rolling down an incline) chatters about
/// zero slip with an amplitude of order mu_d |F_n| dt / m*. Use a spring-slider or a
/// spring-dashpot-slider where sticking matters. No history, no parameters (mu_d is the pair's
/// `friction`).
///
/// Unlike the seed program's spring models, only this rigid slider ties the force direction to
/// the slip velocity, which is its definition.

#include <algorithm>
#include <grain/models/tangent/stick_slip.hpp>

namespace grain::tangent {

struct Slider {
  static constexpr Slot slot = Slot::tangent;
  static constexpr const char* name = "slider";

  struct Params {};
  template <int D>
  struct History {};

  static void validate(const Params&) {}

  template <int D>
  GRAIN_INLINE static TangentResult<D> force(const ContactGeometry<D>& g,
                                             const PairProperties& pair, const NormalResult& n,
                                             const Params&, History<D>&, double) {
    TangentResult<D> r;
    if (!(g.overlap > 0.0)) return r;
    const double speed = g.tangential_velocity.norm();
    if (speed > 0.0) {
      r.force = (-pair.friction * std::max(n.force, 0.0) / speed) * g.tangential_velocity;
      r.sliding = true;
    }
    return r;
  }
};

} // namespace grain::tangent
