// Whole simulation steps of the benchmark cases (settle3d, thermal3d and pack2d at N = 1e4 and
// 1e5, settle3d and thermal3d at 1e6: the sizes of docs/performance.md, warm-up steps first);
// reports particle-steps per second. settle3d and thermal3d (the same mechanics plus heat
// conduction) side by side give the cost of conduction; settle3d and settle3d_periodic_xy (x and
// y periodic instead of the 4 side planes) the cost of periodic boundaries.
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

static void settle3d_periodic_xy(benchmark::State& state, int nx, int ny, int nz, int warm) {
  auto sim = grain::bench::make_settle3d(nx, ny, nz, true);
  run_steps(state, sim, warm);
}

static void thermal3d(benchmark::State& state, int nx, int ny, int nz, int warm) {
  auto sim = grain::bench::make_thermal3d(nx, ny, nz);
  run_steps(state, sim, warm);
}

static void pack2d(benchmark::State& state, int nx, int ny, int warm) {
  auto sim = grain::bench::make_pack2d(nx, ny);
  run_steps(state, sim, warm);
}

BENCHMARK_CAPTURE(settle3d, tiny, 10, 10, 10, 10)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(settle3d_periodic_xy, tiny, 10, 10, 10, 10)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(thermal3d, tiny, 10, 10, 10, 10)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(pack2d, tiny, 20, 20, 10)->Unit(benchmark::kMillisecond);
// A fixed number of steps, so that settle3d and thermal3d time the same motion; three repetitions
// (compare the medians: the machine is noisy).
BENCHMARK_CAPTURE(settle3d, N1e4, 25, 25, 16, 1000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2000)
    ->Repetitions(3);
BENCHMARK_CAPTURE(settle3d_periodic_xy, N1e4, 25, 25, 16, 1000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2000)
    ->Repetitions(3);
BENCHMARK_CAPTURE(thermal3d, N1e4, 25, 25, 16, 1000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2000)
    ->Repetitions(3);
BENCHMARK_CAPTURE(settle3d, N1e5, 50, 50, 40, 1000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(400)
    ->Repetitions(3);
BENCHMARK_CAPTURE(settle3d_periodic_xy, N1e5, 50, 50, 40, 1000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(400)
    ->Repetitions(3);
BENCHMARK_CAPTURE(thermal3d, N1e5, 50, 50, 40, 1000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(400)
    ->Repetitions(3);
BENCHMARK_CAPTURE(pack2d, N1e4, 125, 80, 1000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2000)
    ->Repetitions(3);
BENCHMARK_CAPTURE(pack2d, N1e5, 400, 250, 1000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(400)
    ->Repetitions(3);
// the case definition's N = 1e6 (100 x 100 x 100, 200 warm-up steps); a few seconds per repetition
BENCHMARK_CAPTURE(settle3d, N1e6, 100, 100, 100, 200)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(100)
    ->Repetitions(3);
BENCHMARK_CAPTURE(thermal3d, N1e6, 100, 100, 100, 200)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(100)
    ->Repetitions(3);

BENCHMARK_MAIN();
