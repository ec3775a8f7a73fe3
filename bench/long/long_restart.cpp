// A long run with output and checkpoints, and its restart from a middle checkpoint.
//
// Usage: long_restart OUT NX NY NZ STEPS EVERY [RESTART]
//   Runs settle3d (bench/cases.hpp) on an NX x NY x NZ lattice to step STEPS. Every EVERY steps
//   (and at the start and the end) it writes binary VTK frames (OUT/frames_*), a row of
//   OUT/history.csv and a checkpoint OUT/state_<step>.ckpt. With RESTART (a checkpoint file) the
//   run starts from that checkpoint instead of the initial lattice.
// Prints "key value" lines: the size, the steps, the wall time, the peak and current resident
// memory (VmHWM, VmRSS from /proc/self/status, kB) after the set-up and at the end, and a hash of
// the final positions, velocities and angular velocities (FNV-1a over their bytes in id order).
// Exit status 2 on a bad command line, 1 on an error.
#include "../cases.hpp"

#include <grain/io/checkpoint.hpp>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <numeric>
#include <string>
#include <vector>

namespace {

/// The value [kB] of a "Name:   1234 kB" line of /proc/self/status (-1 if there is none).
long status_kb(const char* name) {
  std::ifstream in("/proc/self/status");
  const std::size_t n = std::strlen(name);
  for (std::string line; std::getline(in, line);)
    if (line.compare(0, n, name) == 0 && line.size() > n && line[n] == ':')
      return std::strtol(line.c_str() + n + 1, nullptr, 10);
  return -1;
}

void print_memory(const char* when) {
  std::printf("%s_vmhwm_kb %ld\n%s_vmrss_kb %ld\n", when, status_kb("VmHWM"), when,
              status_kb("VmRSS"));
  std::fflush(stdout);
}

struct Fnv {
  std::uint64_t h = 1469598103934665603ull;
  void add(const void* p, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    for (std::size_t k = 0; k < n; ++k)
      h = (h ^ b[k]) * 1099511628211ull;
  }
};

/// FNV-1a of position, velocity and omega of every particle, in the order of their ids.
template <class Sim>
std::uint64_t state_hash(const Sim& sim) {
  const auto& p = sim.particles();
  std::vector<std::size_t> order(p.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return p.id[a] < p.id[b]; });
  Fnv f;
  for (const std::size_t i : order) {
    f.add(&p.id[i], sizeof(p.id[i]));
    f.add(p.position[i].data(), 3 * sizeof(double));
    f.add(p.velocity[i].data(), 3 * sizeof(double));
    f.add(p.omega[i].data(), 3 * sizeof(double));
  }
  return f.h;
}

long number(const char* s, long min) {
  char* rest = nullptr;
  const long v = std::strtol(s, &rest, 10);
  if (rest == s || *rest != '\0' || v < min) return -1;
  return v;
}

} // namespace

int main(int argc, char** argv) {
  using namespace grain;
  if (argc != 7 && argc != 8) {
    std::fprintf(stderr, "usage: long_restart OUT NX NY NZ STEPS EVERY [RESTART]\n");
    return 2;
  }
  const std::string out = argv[1];
  const long nx = number(argv[2], 1), ny = number(argv[3], 1), nz = number(argv[4], 1);
  const long total = number(argv[5], 0), every = number(argv[6], 1);
  if (nx < 0 || ny < 0 || nz < 0 || total < 0 || every < 0) {
    std::fprintf(stderr, "long_restart: NX, NY, NZ, EVERY >= 1 and STEPS >= 0 are needed\n");
    return 2;
  }
  try {
    const auto t0 = std::chrono::steady_clock::now();
    auto sim =
        bench::make_settle3d(static_cast<int>(nx), static_cast<int>(ny), static_cast<int>(nz));
    sim.initialize();
    const bool restart = argc == 8;
    if (restart) io::load_checkpoint(sim, argv[7]);
    std::printf("case settle3d\nN %zu\nstart_step %ld\n", sim.size(), sim.step_count());
    print_memory("start");
    const long first = sim.step_count();
    auto checkpoint = [&](const auto& s) {
      char name[32];
      std::snprintf(name, sizeof name, "/state_%07ld.ckpt", s.step_count());
      io::save_checkpoint(s, out + name);
    };
    auto history = io::history(out + "/history.csv");
    history.resume = restart;
    sim.steps(total - first,
              io::every_steps(
                  every,
                  io::vtk(out + "/frames", {.format = io::VtkFormat::binary, .resume = restart}),
                  history, checkpoint));
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("end_step %ld\nsteps_run %ld\nwall_seconds %.1f\n", sim.step_count(),
                sim.step_count() - first, seconds);
    print_memory("end");
    std::printf("state_hash %016llx\n", static_cast<unsigned long long>(state_hash(sim)));
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "long_restart: %s\n", e.what());
    return 1;
  }
}
