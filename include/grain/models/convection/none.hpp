#pragma once
/// \file none.hpp
/// No convection: particles exchange no heat with the surrounding fluid.

#include <grain/models/concepts.hpp>

namespace grain::convection {

struct None {
  static constexpr Slot slot = Slot::convection;
  static constexpr const char* name = "none";
  static constexpr bool active = false;
  struct Params {};
  static void validate(const Params&) {}
};

} // namespace grain::convection
