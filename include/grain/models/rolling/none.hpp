#pragma once
/// \file none.hpp
/// No rolling resistance: the only contact torque is that of the tangential force.

#include <grain/models/concepts.hpp>

namespace grain::rolling {

struct None {
  static constexpr Slot slot = Slot::rolling;
  static constexpr const char* name = "none";
  struct Params {};
  template <int D>
  struct History {};
  static void validate(const Params&) {}
  template <int D, class A>
  GRAIN_INLINE static void torque(const ContactGeometry<D>&, const PairProperties&,
                                  const NormalResult&, const Params&, History<D>&, double, A&, A&) {
  }
};

} // namespace grain::rolling
