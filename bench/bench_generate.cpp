// Initial packings (generate::fill): random sequential addition of spheres with log-normal radii
// (median R = 0.5 mm, sigma 0.3, truncated to [0.5 R, 2 R]) into a cube, to a solid fraction of
// 0.3, largest first, on one thread. The cube's side is chosen so that the fraction needs about
// N spheres: N = 1e5 and 1e6 (and a tiny 1e3 for the smoke test).
//
// Counters: particles (placed), particles_per_s, attempts_per_particle (trial positions per
// placed sphere) and solid_fraction (reached).
// Run: build/bench/bench_generate

#include <grain/setup/generate.hpp>

#include <benchmark/benchmark.h>
#include <cmath>
#include <numbers>

namespace {

using namespace grain;

constexpr double median = 0.5e-3; ///< [m]
constexpr double sigma = 0.3;     ///< standard deviation of ln r [-]
constexpr double fraction = 0.3;

/// E[r^3] of the truncated log-normal [m^3] by the midpoint rule in ln r.
double mean_cube() {
  const double a = std::log(0.5), b = std::log(2.0);
  const int n = 2000;
  double num = 0.0, den = 0.0;
  for (int k = 0; k < n; ++k) {
    const double t = a + (b - a) * (k + 0.5) / n; // ln(r / median)
    const double w = std::exp(-0.5 * t * t / (sigma * sigma));
    num += w * std::pow(median * std::exp(t), 3);
    den += w;
  }
  return num / den;
}

void fill_lognormal(benchmark::State& state) {
  const auto n = static_cast<double>(state.range(0));
  const double side = std::cbrt(n * 4.0 / 3.0 * std::numbers::pi * mean_cube() / fraction);
  const regions::Box<3> box{Vec3::Zero(), Vec3::Constant(side)};
  const generate::LogNormal dist{median, sigma, 0.5 * median, 2.0 * median};
  generate::Result<3> result;
  for (auto _ : state) {
    result = generate::fill(box, dist, {.solid_fraction = fraction, .seed = 7});
    benchmark::DoNotOptimize(result.particles.data());
  }
  const auto placed = static_cast<double>(result.particles.size());
  state.counters["particles"] = placed;
  state.counters["particles_per_s"] =
      benchmark::Counter(placed, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["attempts_per_particle"] = static_cast<double>(result.attempts) / placed;
  state.counters["solid_fraction"] = result.solid_fraction;
}

} // namespace

BENCHMARK(fill_lognormal)
    ->Name("fill/lognormal/tiny")
    ->Arg(1000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(fill_lognormal)
    ->Name("fill/lognormal")
    ->Arg(100000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->UseRealTime();

BENCHMARK_MAIN();
