#pragma once
/// \file periodic_stage.hpp
/// `grain::periodic<S>`: a user stage run on a period, like the periodic engines of Woo/Yade
/// (by steps, by simulated time or by wall-clock time), instead of at every step.
///
/// S is a plain struct with `template <class Sim> void run(Sim& sim)` (and, if it needs one, an
/// `initialize(sim)` hook, called at every `Simulation::initialize()`). Put `periodic<S>` in the
/// simulation's `stages<...>` option and set its periods before the run:
///
/// ```cpp
/// using Sim = Simulation<Sphere, search::CellList, Contact, stages<periodic<Report>>>;
/// auto& report = sim.stage<periodic<Report>>();
/// report.every_time = 0.01;     // [s] of simulated time
/// report.every_wall = 60.0;     // [s] of wall-clock time, whichever comes first
/// report.stage.file = "out.txt"; // the wrapped stage's own settings
/// ```
///
/// `run` is called at the end of a step (after the integration, the time update and the
/// lifecycle, the `end_of_step` point of stages.hpp) when any of the periods that are set has
/// elapsed since the last run:
///
/// - `every_steps` = n > 0: at steps k0 + n, k0 + 2n, ... (k0: the step of the last
///   `initialize()`);
/// - `every_time` = T > 0 [s]: at the first step at or after t0 + T, t0 + 2T, ... (t0: the time
///   of the last `initialize()`; a step that passes several instants runs S once, and the next
///   instant is the first one after it);
/// - `every_wall` = W > 0 [s]: when W seconds of wall-clock time have passed since the last run
///   (or since `initialize()`).
///
/// A run of S for any reason restarts the wall-clock period only; the step and time grids stay
/// fixed. `at_start = true` also runs S at the end of `initialize()`; `max_runs` >= 0 stops after
/// that many runs (-1: no limit). `runs()` counts the runs. A `periodic<S>` with no period set
/// is refused when the run starts (InputError), as is a negative or non-finite period.
/// A periodic stage costs a few comparisons per step between its runs. Checkpoints keep its
/// schedule (see `serialize`).

#include <grain/core/error.hpp>

#include <chrono>
#include <cmath>
#include <limits>

namespace grain {

template <class S>
struct periodic {
  S stage{};             ///< the wrapped stage (its own settings and results)
  long every_steps = 0;  ///< period in steps (0: not used)
  double every_time = 0; ///< period in simulated time [s] (0: not used)
  double every_wall = 0; ///< period in wall-clock time [s] (0: not used)
  long max_runs = -1;    ///< the most runs (-1: no limit)
  bool at_start = false; ///< also run at the end of Simulation::initialize()

  /// The number of runs of S so far.
  long runs() const { return runs_; }

  template <class Sim>
  void initialize(Sim& sim) {
    const char* obj = "periodic stage";
    detail::require(every_steps >= 0, obj, "every_steps", static_cast<double>(every_steps),
                    "[0, inf) steps (0: not used)");
    detail::require(std::isfinite(every_time) && every_time >= 0.0, obj, "every_time", every_time,
                    "[0, inf) s (0: not used)");
    detail::require(std::isfinite(every_wall) && every_wall >= 0.0, obj, "every_wall", every_wall,
                    "[0, inf) s (0: not used)");
    detail::require(every_steps > 0 || every_time > 0.0 || every_wall > 0.0, obj, "periods", 0.0,
                    "at least one of every_steps, every_time, every_wall > 0");
    detail::require(max_runs >= -1, obj, "max_runs", static_cast<double>(max_runs),
                    "-1 (no limit) or [0, inf)");
    if constexpr (requires { stage.initialize(sim); }) stage.initialize(sim);
    next_step_ =
        every_steps > 0 ? sim.step_count() + every_steps : std::numeric_limits<long>::max();
    t0_ = sim.time();
    k_time_ = 1;
    last_wall_ = std::chrono::steady_clock::now();
    if (at_start) fire(sim);
  }

  template <class Sim>
  void end_of_step(Sim& sim) {
    bool due = false;
    if (sim.step_count() >= next_step_) {
      due = true;
      while (next_step_ <= sim.step_count())
        next_step_ += every_steps;
    }
    if (every_time > 0.0) {
      // instants t0 + k T; rounding of a time that lands on an instant is forgiven
      const double tol = 1e-9 * every_time;
      if (sim.time() >= t0_ + static_cast<double>(k_time_) * every_time - tol) {
        due = true;
        while (sim.time() >= t0_ + static_cast<double>(k_time_) * every_time - tol)
          ++k_time_;
      }
    }
    if (!due && every_wall > 0.0 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - last_wall_).count() >=
            every_wall)
      due = true;
    if (due) fire(sim);
  }

  /// Checkpoints keep the schedule (runs, the next step and time instants) and the wrapped
  /// stage's state if it has a `serialize`; the wall-clock period restarts on a restart.
  template <class Archive>
  void serialize(Archive& ar) {
    ar(runs_, next_step_, t0_, k_time_);
    if constexpr (requires { stage.serialize(ar); }) stage.serialize(ar);
  }

private:
  template <class Sim>
  void fire(Sim& sim) {
    if (max_runs >= 0 && runs_ >= max_runs) return;
    stage.run(sim);
    ++runs_;
    last_wall_ = std::chrono::steady_clock::now();
  }

  long runs_ = 0;
  long next_step_ = std::numeric_limits<long>::max();
  double t0_ = 0.0;
  long k_time_ = 1;
  std::chrono::steady_clock::time_point last_wall_{};
};

} // namespace grain
