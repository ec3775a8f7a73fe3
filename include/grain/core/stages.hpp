#pragma once
/// \file stages.hpp
/// User stages and per-particle fields of a `Simulation`, chosen at compile time.
///
/// A *stage* is a plain struct with one or more hook member functions, each taking the
/// simulation by reference. `Simulation<Shape, Search, Contact, grain::stages<S1, S2>>` holds one
/// object of each stage type and calls its hooks at fixed points of every step, in list order:
///
/// - `initialize(sim)`: at the end of every `Simulation::initialize()` (neighbour list built,
///   time step fixed, initial forces known), before the first step and after a change of the
///   set-up between runs (not after io::load_checkpoint: a stage's state comes from the
///   checkpoint);
/// - `begin_step(sim)`: at the start of a step, time t;
/// - `before_search(sim)`: after the drift (velocity Verlet: positions at t + dt, velocities at
///   t + dt/2) and the wall motion, before the neighbour search; a stage may move particles and
///   walls here, the search sees the new positions (moving simulations only);
/// - `after_forces(sim)`: every force, torque and heat rate of the step is summed (contacts,
///   walls, gravity, damping, prescribed loads); a stage may read them (e.g. `wall_force(w)`)
///   and add its own before the final kick. It also runs after the initial force evaluation of
///   `initialize()` (velocity Verlet), so that the first half kick feels the stage's loads;
/// - `end_of_step(sim)`: after the integration, the time update and the lifecycle (time t + dt).
///
/// A hook a stage does not define costs nothing: the calls are resolved at compile time, with no
/// virtual dispatch. `sim.stage<S>()` returns the stage object (to set its parameters before a
/// run or read its results after one).
///
/// A *field* is per-particle data that a stage or a program needs and the library does not:
/// `grain::fields<F...>` as a simulation option, or `using fields = grain::fields<F...>;` inside a
/// stage, attaches one `std::vector<F>` per field type, kept in the particle order (re-sorted,
/// appended and removed with the particles, saved in checkpoints). `sim.field<F>()[i]` is the
/// value of particle i (current index); new particles get `F{}`. A simulation pays for no field
/// it does not name. The thermal state (temperature, heat rate, heat capacity) is the built-in
/// example: it exists only when the contact conducts heat.

#include <cstdint>
#include <tuple>
#include <type_traits>
#include <vector>

namespace grain {

/// The user stages of a simulation, in the order their hooks run (a Simulation option).
template <class... S>
struct stages {};

/// Per-particle fields (a Simulation option, or a stage's `fields` member type).
template <class... F>
struct fields {};

/// Per-particle field of rigid aggregates (the clump stage, clumps/clumps.hpp): the clump and
/// member index of a particle, -1 for a single particle. A simulation that has this field never
/// puts two members of the same clump into its neighbour list: they do not touch each other.
struct ClumpMember {
  std::int32_t clump = -1;
  std::int32_t member = -1;
};

namespace detail {

template <class T>
struct is_stages : std::false_type {};
template <class... S>
struct is_stages<stages<S...>> : std::true_type {};

template <class T>
struct is_fields : std::false_type {};
template <class... F>
struct is_fields<fields<F...>> : std::true_type {};

/// True if the stage S has at least one hook callable with a Sim&.
template <class S, class Sim>
concept stage_for = requires(S& s, Sim& sim) {
  s.initialize(sim);
}
|| requires(S& s, Sim& sim) { s.begin_step(sim); }
|| requires(S& s, Sim& sim) { s.before_search(sim); }
|| requires(S& s, Sim& sim) { s.after_forces(sim); }
|| requires(S& s, Sim& sim) { s.end_of_step(sim); };

template <class S, class Sim>
concept moves_in_stage = requires(S& s, Sim& sim) {
  s.before_search(sim);
};

/// A stage's own field list (`fields<>` if it has none).
template <class S>
struct stage_fields {
  using type = fields<>;
};
template <class S>
requires requires { typename S::fields; }
struct stage_fields<S> {
  using type = typename S::fields;
  static_assert(is_fields<type>::value,
                "grain::stages: a stage's member type `fields` must be grain::fields<F...>");
};

/// Appends the field types of B that A does not have yet.
template <class A, class B>
struct merge_fields;
template <class... A>
struct merge_fields<fields<A...>, fields<>> {
  using type = fields<A...>;
};
template <class... A, class F, class... B>
struct merge_fields<fields<A...>, fields<F, B...>> {
  using type = typename merge_fields<
      std::conditional_t<(std::is_same_v<A, F> || ...), fields<A...>, fields<A..., F>>,
      fields<B...>>::type;
};

/// The field list of a simulation: its `fields<...>` options, then each stage's fields.
template <class Acc, class... Ts>
struct collect_fields {
  using type = Acc;
};
template <class Acc, class T, class... Ts>
struct collect_fields<Acc, T, Ts...> {
  using type = typename collect_fields<typename merge_fields<Acc, T>::type, Ts...>::type;
};

template <class StageList, class FieldOptions>
struct all_fields;
template <class... S, class... FO>
struct all_fields<stages<S...>, fields<FO...>> {
  using type =
      typename collect_fields<fields<>, fields<FO...>, typename stage_fields<S>::type...>::type;
};

/// std::tuple<S...> of a stage list; std::tuple<std::vector<F>...> of a field list.
template <class L>
struct stage_tuple;
template <class... S>
struct stage_tuple<stages<S...>> {
  using type = std::tuple<S...>;
};
template <class L>
struct field_tuple;
template <class... F>
struct field_tuple<fields<F...>> {
  using type = std::tuple<std::vector<F>...>;
  template <class T>
  static constexpr bool contains = (std::is_same_v<T, F> || ...);
};

/// Concatenation of the `fields<...>` options.
template <class... Options>
struct field_options {
  using type = fields<>;
};
template <class T, class... Options>
struct field_options<T, Options...> {
  using type = typename field_options<Options...>::type;
};
template <class... F, class... Options>
struct field_options<fields<F...>, Options...> {
  using type = typename merge_fields<fields<F...>, typename field_options<Options...>::type>::type;
};

} // namespace detail
} // namespace grain
