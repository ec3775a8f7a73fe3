// Neighbour searches: the cost of building the neighbour list from scratch, and of the per-step
// check that decides whether it must be rebuilt, in particles per second.
//
// `Simulation::rebuild` and `Simulation::update_neighbors` are private, so the benchmarks call
// what they call, in the same order and with the same arguments:
//   build/AllPairs       search::detail::build_all_pairs with no skin (AllPairs rebuilds at
//                        every step; it has no update);
//   build/VerletList     search::detail::build_all_pairs with the skin (the same O(N^2) test);
//   build/CellList       search::detail::cell_order, ParticleArrays::permute and
//                        search::detail::build_cells: a rebuild with the default
//                        `CellList::Params::sort = true` (particles re-sorted by cell);
//   build/CellList_nosort  build_cells alone (`sort = false`);
//   update               the displacement check of update_neighbors (the largest displacement
//                        since the last build against half the skin), which is the same code
//                        for VerletList and CellList.
// The history carry-over of a rebuild (Simulation's, not the search's) is not included.
//
// Particle sets (spheres, no walls): "mono", radius R = 0.5 mm; "ratio10", radii uniform in
// [0.1 R, R] (size ratio 10). Centres are quasi-random (R3 sequence) in a cube filled to a solid
// fraction of 0.6, then sorted by cell once, as a simulation's particles are after their first
// rebuild. Skin 0.1 mm (0.2 R_max, settle3d's and CellList's default); the list holds the
// pairs closer than r_i + r_j + skin. Sizes: AllPairs tiny (500) and 2e3; VerletList tiny and
// 1e4; CellList and update tiny (800), 1e4 and 1e5. The tiny sizes stay below the size at which
// the loops go parallel (1000), so that the smoke test is quick on a busy machine.
//
// Counters: particles_per_s (rate), N, pairs (list entries) and pairs_per_particle.
// Run on one thread: OMP_NUM_THREADS=1 build/bench/bench_search

#include "cases.hpp"
#include <algorithm>
#include <benchmark/benchmark.h>
#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <vector>

namespace {

using namespace grain;

constexpr double radius = 0.5e-3;     ///< R = r_max [m]
constexpr double skin = 0.2 * radius; ///< [m]
constexpr double solid_fraction = 0.6;

using Sim = Simulation<Sphere, search::CellList, bench::Settle3dContact>;

/// A particle set held by a simulation (built with the public API, never initialised).
struct ParticleSet {
  Sim sim;
  double r_max = 0.0; ///< largest radius (sets the cell size, as in Simulation)
  const ParticleArrays<3>& particles() const { return sim.particles(); }
};

/// N spheres; `ratio10` gives radii R (0.1 + 0.9 u), u uniform in [0, 1) (R-sequence).
ParticleSet make_set(long n, bool ratio10) {
  ParticleSet s{Sim({.time_step = bench::case_time_step, .search = {.skin = skin}})};
  const auto m = s.sim.add_material(bench::case_material());
  std::vector<double> r(static_cast<std::size_t>(n));
  double volume = 0.0;
  for (long k = 0; k < n; ++k) {
    r[k] = ratio10 ? radius * (0.1 + 0.9 * bench::rseq(k, 0.7236067977499790)) : radius;
    volume += 4.0 / 3.0 * std::numbers::pi * r[k] * r[k] * r[k];
    s.r_max = std::max(s.r_max, r[k]);
  }
  const double side = std::cbrt(volume / solid_fraction);
  // R3 sequence: alpha_d = 1/g^d, g = 1.2207440846 the root of g^4 = g + 1 (as settle3d)
  for (long k = 0; k < n; ++k)
    s.sim.add_particle({.position = side * Vec3(bench::rseq(k, 0.8191725133961645),
                                                bench::rseq(k, 0.6710436067037893),
                                                bench::rseq(k, 0.5497004779019703)),
                        .radius = r[k],
                        .material = m});
  // sorted by cell once, as after a simulation's first rebuild
  auto& p = s.sim.particles();
  p.permute(search::detail::cell_order(p, 2.0 * s.r_max + skin));
  return s;
}

/// Each particle set is built once per process.
ParticleSet& particle_set(long n, bool ratio10) {
  static std::map<std::pair<long, bool>, ParticleSet> sets;
  auto it = sets.find({n, ratio10});
  if (it == sets.end()) it = sets.emplace(std::pair{n, ratio10}, make_set(n, ratio10)).first;
  return it->second;
}

void set_counters(benchmark::State& state, std::size_t n, const NeighborList& list) {
  state.counters["particles_per_s"] =
      benchmark::Counter(static_cast<double>(n) * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate);
  state.counters["N"] = static_cast<double>(n);
  state.counters["pairs"] = static_cast<double>(list.partners.size());
  state.counters["pairs_per_particle"] =
      static_cast<double>(list.partners.size()) / static_cast<double>(n);
}

enum class Kind { all_pairs, verlet, cells, cells_nosort };

/// A rebuild of the list from scratch.
void build(benchmark::State& state, Kind kind, long n, bool ratio10) {
  ParticleSet& s = particle_set(n, ratio10);
  // the set is sorted by cell again at every CellList build: work on a copy
  ParticleArrays<3> p = s.particles();
  const std::vector<Wall<3>> walls;
  NeighborList list;
  for (auto _ : state) {
    switch (kind) {
    case Kind::all_pairs:
      search::detail::build_all_pairs(p, walls, 0.0, list);
      break;
    case Kind::verlet:
      search::detail::build_all_pairs(p, walls, skin, list);
      break;
    case Kind::cells:
      p.permute(search::detail::cell_order(p, 2.0 * s.r_max + skin));
      search::detail::build_cells(p, walls, skin, s.r_max, list);
      break;
    case Kind::cells_nosort:
      search::detail::build_cells(p, walls, skin, s.r_max, list);
      break;
    }
    benchmark::DoNotOptimize(list.partners.data());
    benchmark::ClobberMemory();
  }
  set_counters(state, p.size(), list);
}

/// The per-step check of Simulation::update_neighbors: the largest displacement since the last
/// build, against half the skin (no rebuild is due: every particle moved 1e-3 of the skin).
void update(benchmark::State& state, long n, bool ratio10) {
  const ParticleSet& s = particle_set(n, ratio10);
  const std::vector<Vec3> snapshot = s.particles().position;
  std::vector<Vec3> x = snapshot;
  for (std::size_t i = 0; i < x.size(); ++i)
    x[i] += 1e-3 * skin * Vec3(bench::rseq(static_cast<long>(i), 0.618), 0.5, -0.25);
  const long nl = static_cast<long>(x.size());
  NeighborList list;
  search::detail::build_cells(s.particles(), {}, skin, s.r_max, list);
  long rebuilds = 0;
  for (auto _ : state) {
    double d2 = 0.0;
#pragma omp parallel for reduction(max : d2) schedule(static) if (nl >= Sim::parallel_threshold)
    for (long i = 0; i < nl; ++i)
      d2 = std::max(d2, (x[i] - snapshot[i]).squaredNorm());
    rebuilds += 2.0 * std::sqrt(d2) >= skin;
    benchmark::DoNotOptimize(rebuilds);
  }
  if (rebuilds != 0) state.SkipWithError("the displacement check asked for a rebuild");
  set_counters(state, x.size(), list);
}

void register_all() {
  struct Sizes {
    Kind kind;
    const char* name;
    std::vector<std::pair<const char*, long>> sizes;
  };
  const Sizes builds[] = {
      {Kind::all_pairs, "AllPairs", {{"tiny", 500}, {"N2e3", 2000}}},
      {Kind::verlet, "VerletList", {{"tiny", 500}, {"N1e4", 10000}}},
      {Kind::cells, "CellList", {{"tiny", 800}, {"N1e4", 10000}, {"N1e5", 100000}}},
      {Kind::cells_nosort, "CellList_nosort", {{"tiny", 800}, {"N1e4", 10000}, {"N1e5", 100000}}},
  };
  for (const bool ratio10 : {false, true}) {
    const std::string set = ratio10 ? "ratio10" : "mono";
    for (const auto& b : builds)
      for (const auto& [size, n] : b.sizes)
        benchmark::RegisterBenchmark(
            ("build/" + std::string(b.name) + "/" + set + "/" + size).c_str(),
            [kind = b.kind, n = n, ratio10](benchmark::State& st) { build(st, kind, n, ratio10); })
            ->Unit(benchmark::kMillisecond);
    for (const auto& [size, n] : std::vector<std::pair<const char*, long>>{
             {"tiny", 800}, {"N1e4", 10000}, {"N1e5", 100000}})
      benchmark::RegisterBenchmark(
          ("update/" + set + "/" + size).c_str(),
          [n = n, ratio10](benchmark::State& st) { update(st, n, ratio10); })
          ->Unit(benchmark::kMicrosecond);
  }
}

} // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
