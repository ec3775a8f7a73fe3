#pragma once
/// \file none.hpp
/// No tangential force (frictionless contacts).

#include <grain/models/concepts.hpp>

namespace grain::tangent {

struct None {
  static constexpr Slot slot = Slot::tangent;
  static constexpr const char* name = "none";
  struct Params {};
  template <int D>
  struct History {};
  static void validate(const Params&) {}
  template <int D>
  GRAIN_INLINE static TangentResult<D> force(const ContactGeometry<D>&, const PairProperties&,
                                             const NormalResult&, const Params&, History<D>&,
                                             double) {
    return {};
  }
};

} // namespace grain::tangent
