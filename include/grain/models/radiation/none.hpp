#pragma once
/// \file none.hpp
/// No thermal radiation: particles exchange heat only by conduction, convection and the
/// prescribed heat conditions.

#include <grain/models/concepts.hpp>

namespace grain::radiation {

struct None {
  static constexpr Slot slot = Slot::radiation;
  static constexpr const char* name = "none";
  static constexpr bool active = false;
  struct Params {};
  static void validate(const Params&) {}
};

} // namespace grain::radiation
