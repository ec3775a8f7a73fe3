#pragma once
/// \file none.hpp
/// No heat conduction: a purely mechanical simulation (particles carry no thermal arrays).

#include <grain/models/concepts.hpp>

namespace grain::conduction {

struct None {
  static constexpr Slot slot = Slot::conduction;
  static constexpr const char* name = "none";
  static constexpr bool thermal = false;
  struct Params {};
  template <int D>
  struct History {};
  static void validate(const Params&) {}
};

} // namespace grain::conduction
