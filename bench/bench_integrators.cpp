// Time integrators: whole steps of a simulation of free particles (no contacts), so that what is
// timed is the integration and the per-particle work every step does around it, in
// particle-steps per second.
//
// The particles are settle3d's spheres (d = 1 mm, Hertz-Mindlin contact, cell list with skin
// 0.1 d, dt = 2.5e-6 s) on a cubic lattice of spacing 3 d, so that no pair is ever within reach
// of the search, with no walls and no gravity. Velocities (amplitude 1e-3 m/s) and angular
// velocities (amplitude 100 rad/s) are quasi-random; particles move 2.5e-9 m per step, so the
// neighbour list is never rebuilt while timing (checked). A step is then: the integrator's
// half-kick and drift before the forces (VelocityVerlet only), the displacement check of the
// neighbour list, the force pass (force arrays reset, predicted velocities for VelocityVerlet,
// empty contact rows, body forces) and the integrator's update after the forces. Translation and
// rotation (angular velocity and orientation quaternion) are both integrated.
//
// "spinning" particles rotate; "still" ones have omega = 0, for which the orientation update
// (an axis-angle quaternion product and a normalisation per particle) is skipped: the difference
// is the cost of integrating orientations.
//
// Sizes: tiny (9 x 9 x 9, below the size at which the loops go parallel, so that the smoke test
// is quick on a busy machine) and N1e5 (50 x 50 x 40). Counters: particle_steps_per_s, N.
// Run on one thread: OMP_NUM_THREADS=1 build/bench/bench_integrators

#include "cases.hpp"
#include <benchmark/benchmark.h>
#include <string>

namespace {

using namespace grain;

/// Free spheres on a lattice of spacing 3 d with the integrator I.
template <class I>
Simulation<Sphere, search::CellList, bench::Settle3dContact, I> free_particles(int nx, int ny,
                                                                               int nz, bool spin) {
  const double d = bench::case_diameter, a = 3.0 * d, v0 = 1e-3, w0 = spin ? 100.0 : 0.0;
  Simulation<Sphere, search::CellList, bench::Settle3dContact, I> sim(
      {.time_step = bench::case_time_step, .search = {.skin = 0.1 * d}});
  const auto m = sim.add_material(bench::case_material());
  auto u = [](long n, double alpha) { return 2.0 * bench::rseq(n, alpha) - 1.0; };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const long n = i + static_cast<long>(nx) * (j + static_cast<long>(ny) * k);
        sim.add_particle({.position = Vec3((i + 0.5) * a, (j + 0.5) * a, (k + 0.5) * a),
                          .radius = 0.5 * d,
                          .material = m,
                          .velocity = v0 * Vec3(u(n, 0.8191725133961645), u(n, 0.6710436067037893),
                                                u(n, 0.5497004779019703)),
                          .omega = w0 * Vec3(u(n, 0.5497004779019703), u(n, 0.8191725133961645),
                                             u(n, 0.6710436067037893))});
      }
  return sim;
}

template <class I>
void free_steps(benchmark::State& state, int nx, int ny, int nz, bool spin) {
  auto sim = free_particles<I>(nx, ny, nz, spin);
  sim.initialize();
  if (!sim.neighbor_list().partners.empty()) {
    state.SkipWithError("the particles are not free: the neighbour list holds pairs");
    return;
  }
  const long rebuilds = sim.counters().rebuilds;
  long steps = 0;
  for (auto _ : state) {
    sim.step();
    ++steps;
  }
  if (sim.counters().rebuilds != rebuilds)
    state.SkipWithError("the neighbour list was rebuilt while timing");
  state.counters["particle_steps_per_s"] = benchmark::Counter(
      static_cast<double>(sim.size()) * static_cast<double>(steps), benchmark::Counter::kIsRate);
  state.counters["N"] = static_cast<double>(sim.size());
}

template <class I>
void register_integrator(const std::string& name) {
  struct Size {
    const char* name;
    int nx, ny, nz;
  };
  for (const bool spin : {true, false})
    for (const Size z : {Size{"tiny", 9, 9, 9}, Size{"N1e5", 50, 50, 40}}) {
      const std::string full = "free_step/" + name + (spin ? "/spinning/" : "/still/") + z.name;
      benchmark::RegisterBenchmark(full.c_str(), [z, spin](benchmark::State& st) {
        free_steps<I>(st, z.nx, z.ny, z.nz, spin);
      })->Unit(benchmark::kMillisecond);
    }
}

} // namespace

int main(int argc, char** argv) {
  register_integrator<integrate::ForwardEuler>("ForwardEuler");
  register_integrator<integrate::SymplecticEuler>("SymplecticEuler");
  register_integrator<integrate::Taylor2>("Taylor2");
  register_integrator<integrate::VelocityVerlet>("VelocityVerlet");
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
