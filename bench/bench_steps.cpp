// Whole simulation steps of the benchmark cases; reports particle-steps per second.
#include "cases.hpp"
#include <benchmark/benchmark.h>

static void settle3d(benchmark::State& state, int nx, int ny, int nz, int warm) {
  auto sim = grain::bench::make_settle3d(nx, ny, nz);
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

BENCHMARK_CAPTURE(settle3d, tiny, 10, 10, 10, 10)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(settle3d, N1e4, 25, 25, 16, 1000)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK_CAPTURE(settle3d, N1e5, 50, 50, 40, 1000)->Unit(benchmark::kMillisecond)->MinTime(4.0);

BENCHMARK_MAIN();
