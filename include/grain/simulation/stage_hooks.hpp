#pragma once
/// \file stage_hooks.hpp
/// Calling the hooks of a simulation's user stages (core/stages.hpp): each hook a stage defines
/// is called with the simulation, in the order of the stage list; a hook a stage does not define
/// costs nothing (resolved at compile time).

#include <grain/core/stages.hpp>

#include <tuple>
#include <type_traits>

namespace grain::detail {

/// The points of a step where stage hooks run.
enum class Hook { initialize, begin_step, before_search, after_forces, end_of_step };

/// True if S is in the stage list L.
template <class S, class L>
inline constexpr bool has_stage_in = false;
template <class S, class... Ss>
inline constexpr bool has_stage_in<S, stages<Ss...>> = (std::is_same_v<S, Ss> || ...);

/// True if the stage list L is empty.
template <class L>
inline constexpr bool no_stages_in = false;
template <class... Ss>
inline constexpr bool no_stages_in<stages<Ss...>> = sizeof...(Ss) == 0;

/// True if a stage of L moves particles or walls between the drift and the search
/// (a `before_search` hook).
template <class L, class Sim>
inline constexpr bool stages_move_in = false;
template <class... Ss, class Sim>
inline constexpr bool stages_move_in<stages<Ss...>, Sim> = (moves_in_stage<Ss, Sim> || ...);

/// Calls hook H of stage s with the simulation, if s has it.
template <Hook H, class S, class Sim>
void call_stage(S& s, Sim& sim) {
  if constexpr (H == Hook::initialize) {
    if constexpr (requires { s.initialize(sim); }) s.initialize(sim);
  } else if constexpr (H == Hook::begin_step) {
    if constexpr (requires { s.begin_step(sim); }) s.begin_step(sim);
  } else if constexpr (H == Hook::before_search) {
    if constexpr (requires { s.before_search(sim); }) s.before_search(sim);
  } else if constexpr (H == Hook::after_forces) {
    if constexpr (requires { s.after_forces(sim); }) s.after_forces(sim);
  } else {
    if constexpr (requires { s.end_of_step(sim); }) s.end_of_step(sim);
  }
}

/// Calls hook H of every stage of the tuple that has it, in order.
template <Hook H, class... S, class Sim>
void call_stages(std::tuple<S...>& all, Sim& sim) {
  static_assert((stage_for<S, Sim> && ...),
                "grain::stages<...>: each stage needs at least one hook taking the simulation "
                "by reference: initialize(sim), begin_step(sim), before_search(sim), "
                "after_forces(sim) or end_of_step(sim)");
  std::apply([&sim](auto&... s) { (call_stage<H>(s, sim), ...); }, all);
}

/// Lets every stage of the tuple that has state to keep across a restart visit it.
template <class... S, class Archive>
void serialize_stages(std::tuple<S...>& all, Archive& ar) {
  std::apply(
      [&ar](auto&... s) {
        (
            [&] {
              if constexpr (requires { s.serialize(ar); }) s.serialize(ar);
            }(),
            ...);
      },
      all);
}

} // namespace grain::detail
