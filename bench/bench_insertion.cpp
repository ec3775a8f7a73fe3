// One try of an insertion (detail::Insertions::place) with N spheres present: the pass over the
// positions that builds the cell grid around the region, and the placement of the one sphere
// due. N spheres of radius 1 mm lie at random in a cube sized for a solid fraction of 0.3; the
// insertion's box lies on top of it, one particle due per try (a number rate of 1e5 /s at tries
// 1e-5 s apart). N = 1e5 and 1e6 (and a tiny 1e3 for the smoke test), on one thread.
//
// Counters: particles (present), time_per_particle (the time of a try per particle present).
// Run: build/bench/bench_insertion

#include <grain/setup/insertion.hpp>

#include <benchmark/benchmark.h>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

namespace {

using namespace grain;

void insertion_try(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const double r = 1e-3;
  const double side = std::cbrt(double(n) * 4.0 / 3.0 * std::numbers::pi * r * r * r / 0.3);
  generate::Random rng(1);
  std::vector<Vec3> x(n);
  for (auto& p : x)
    p = Vec3(rng.uniform(0, side), rng.uniform(0, side), rng.uniform(0, side));
  const std::vector<double> radius(n, r);
  detail::Insertions<3> ins;
  ins.add({.region = regions::Box<3>{{0, 0, side + 0.01}, {side, side, side + 0.02}},
           .size = generate::Constant{r},
           .number_rate = 1e5},
          "bench", 0.0, 2500.0, false);
  std::vector<Group> groups;
  std::int64_t next_id = static_cast<std::int64_t>(n);
  const auto volume = [](double q) { return 4.0 / 3.0 * std::numbers::pi * q * q * q; };
  std::vector<ParticleSpec<3>> born;
  long tries = 0;
  for (auto _ : state) {
    born.clear();
    ++tries;
    const auto placed =
        ins.place(double(tries) * 1e-5, x, radius, nullptr, born, r, volume, 0.0, next_id, groups);
    benchmark::DoNotOptimize(placed);
  }
  state.counters["particles"] = double(n);
  state.counters["time_per_particle"] = benchmark::Counter(
      double(n), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

} // namespace

BENCHMARK(insertion_try)
    ->Name("insertion/try/tiny")
    ->Arg(1000)
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();
BENCHMARK(insertion_try)
    ->Name("insertion/try")
    ->Arg(100000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

BENCHMARK_MAIN();
