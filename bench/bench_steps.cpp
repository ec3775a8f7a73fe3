// Whole simulation steps of the benchmark cases; reports particle-steps per second. settle3d and
// thermal3d (the same mechanics plus heat conduction) side by side give the cost of conduction.
#include "cases.hpp"
#include <benchmark/benchmark.h>

template <class Sim>
static void run_steps(benchmark::State& state, Sim& sim, int warm) {
  sim.steps(warm);
  long steps = 0;
  for (auto _ : state) {
    sim.step();
    ++steps;
  }
  state.counters["particle_steps_per_s"] = benchmark::Counter(
      static_cast<double>(sim.size()) * static_cast<double>(steps), benchmark::Counter::kIsRate);
  state.counters["N"] = static_cast<double>(sim.size());
  const auto [pp, pw] = sim.contact_counts();
  state.counters["contacts"] = static_cast<double>(pp);
}

static void settle3d(benchmark::State& state, int nx, int ny, int nz, int warm) {
  auto sim = grain::bench::make_settle3d(nx, ny, nz);
  run_steps(state, sim, warm);
}

static void thermal3d(benchmark::State& state, int nx, int ny, int nz, int warm) {
  auto sim = grain::bench::make_thermal3d(nx, ny, nz);
  run_steps(state, sim, warm);
}

BENCHMARK_CAPTURE(settle3d, tiny, 10, 10, 10, 10)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(thermal3d, tiny, 10, 10, 10, 10)->Unit(benchmark::kMillisecond);
// A fixed number of steps, so that settle3d and thermal3d time the same motion; three repetitions
// (compare the medians: the machine is noisy).
BENCHMARK_CAPTURE(settle3d, N1e4, 25, 25, 16, 1000)
    ->Unit(benchmark::kMillisecond)->Iterations(2000)->Repetitions(3);
BENCHMARK_CAPTURE(thermal3d, N1e4, 25, 25, 16, 1000)
    ->Unit(benchmark::kMillisecond)->Iterations(2000)->Repetitions(3);
BENCHMARK_CAPTURE(settle3d, N1e5, 50, 50, 40, 1000)
    ->Unit(benchmark::kMillisecond)->Iterations(400)->Repetitions(3);
BENCHMARK_CAPTURE(thermal3d, N1e5, 50, 50, 40, 1000)
    ->Unit(benchmark::kMillisecond)->Iterations(400)->Repetitions(3);

BENCHMARK_MAIN();
