#pragma once
// What the case programs share: the command line, the timed run and the "key value" report.
#include "../cases.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace grain::bench {

/// Reads the command-line integers of a case program into `values` (left unchanged when there are
/// no arguments). All must be >= `min[k]`. Returns false on a bad command line.
inline bool parse_arguments(int argc, char** argv, std::vector<long>& values,
                            const std::vector<long>& min) {
  if (argc == 1) return true;
  if (static_cast<std::size_t>(argc - 1) != values.size()) return false;
  for (std::size_t k = 0; k < values.size(); ++k) {
    const char* s = argv[k + 1];
    char* rest = nullptr;
    const long v = std::strtol(s, &rest, 10);
    if (rest == s || *rest != '\0' || v < min[k] || v > 100000000L) return false;
    values[k] = v;
  }
  return true;
}

inline void print_figures(const char* prefix, const Figures& f) {
  std::printf("%scontacts %zu\n", prefix, f.contacts);
  std::printf("%ske %.17g\n", prefix, f.kinetic);
  std::printf("%srke %.17g\n", prefix, f.rotational);
  std::printf("%smean_height %.17g\n", prefix, f.mean_height);
}

/// Prints nothing more (the default of run_case's `extra`).
struct NoExtra {
  template <class Sim>
  void operator()(const Sim&, const char*) const {}
};

/// Runs `nwarm` untimed and `nrun` timed steps and prints the report; `extra(sim, prefix)` prints
/// case-specific figures after the warm-up ("warm_") and at the end (""). Returns the exit status
/// (1 if a particle has left the box `lo`..`hi` or is not finite).
template <class Sim, class Extra = NoExtra>
int run_case(Sim& sim, const Vec<Sim::D>& lo, const Vec<Sim::D>& hi, long nwarm, long nrun,
             Extra extra = {}) {
  int threads = 1;
#ifdef _OPENMP
  threads = omp_get_max_threads();
#endif
  std::printf("N %zu\n", sim.size());
  std::printf("nwarm %ld\n", nwarm);
  std::printf("nrun %ld\n", nrun);
  std::printf("threads %d\n", threads);
  sim.initialize();
  std::printf("time_step %.17g\n", sim.time_step());
  sim.steps(nwarm);
  print_figures("warm_", figures(sim, lo, hi));
  extra(sim, "warm_");
  const long rebuilds0 = sim.counters().rebuilds;
  const auto t0 = std::chrono::steady_clock::now();
  sim.steps(nrun);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const Figures f = figures(sim, lo, hi);
  std::printf("steps %ld\n", sim.step_count());
  std::printf("run_seconds %.6f\n", seconds);
  std::printf("particle_steps_per_s %.6g\n",
              static_cast<double>(sim.size()) * static_cast<double>(nrun) / seconds);
  std::printf("neighbor_rebuilds %ld\n", sim.counters().rebuilds - rebuilds0);
  std::printf("list_pairs %zu\n", sim.neighbor_list().partners.size());
  print_figures("", f);
  extra(sim, "");
  std::printf("particles_outside %zu\n", f.outside);
  return f.outside == 0 ? 0 : 1;
}

} // namespace grain::bench
