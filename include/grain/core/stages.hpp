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

#include <concepts>
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

/// How the simulation's core treats a particle by the value of one of its fields: the way an
/// extension above the core (clumps, a rigid-body system) tells it what the core must know,
/// without the core naming the extension. Specialise it for a field type F with either or both
/// of these static members (a field without a specialisation changes nothing):
/// - `static bool driven(const F& f)`: true if a particle whose inverse mass is 0 is moved by
///   its contact forces through the extension (a clump member, a particle of a rigid body), so
///   it is not a fixed particle: its contacts use its own mass, not an infinite one;
/// - `static bool excluded(const F& a, const F& b)`: true if two particles never act on each
///   other (members of one rigid aggregate): their pair is left out of the neighbour list.
template <class F>
struct field_traits {};

namespace detail {

template <class F>
concept driving_field = requires(const F& f) {
  { field_traits<F>::driven(f) } -> std::convertible_to<bool>;
};
template <class F>
concept excluding_field = requires(const F& a) {
  { field_traits<F>::excluded(a, a) } -> std::convertible_to<bool>;
};
/// field_traits<F>::driven(f), or false if F does not say.
template <class F>
bool field_driven(const F& f) {
  if constexpr (driving_field<F>)
    return field_traits<F>::driven(f);
  else
    return ((void)f, false);
}
/// field_traits<F>::excluded(a, b), or false if F does not say.
template <class F>
bool field_excludes(const F& a, const F& b) {
  if constexpr (excluding_field<F>)
    return field_traits<F>::excluded(a, b);
  else
    return ((void)a, (void)b, false);
}

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
