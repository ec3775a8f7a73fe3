#pragma once
/// \file none.hpp
/// No contact-area correction: conduction models use the contact radius as simulated.

#include <grain/models/concepts.hpp>

namespace grain::area {

struct None {
  static constexpr Slot slot = Slot::area;
  static constexpr const char* name = "none";
  struct Params {};
  template <int D>
  struct History {};
  static void validate(const Params&) {}
};

} // namespace grain::area
