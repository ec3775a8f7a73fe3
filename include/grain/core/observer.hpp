#pragma once
/// \file observer.hpp
/// Observers of a run (io::every, io::summary, ...): callables invoked after each step with the
/// simulated system; an observer may also have `start(system)` and `finish(system)` members,
/// called before the first and after the last step of a run.

namespace grain::detail {

/// Calls `o.start(s)` if the observer has it.
template <class O, class S>
void start_observer(O& o, S& s) {
  if constexpr (requires { o.start(s); }) o.start(s);
}

/// Calls `o.finish(s)` if the observer has it.
template <class O, class S>
void finish_observer(O& o, S& s) {
  if constexpr (requires { o.finish(s); }) o.finish(s);
}

/// Calls `s.check_state()` if the simulated system has it (Simulation::check_state: throws
/// NumericalError for a state gone wrong).
template <class S>
void check_state(const S& s) {
  if constexpr (requires { s.check_state(); }) s.check_state();
}

} // namespace grain::detail
