// settle3d benchmark case: spheres on a simple cubic lattice settle in a closed box of 6 planes
// (Hertz-Mindlin, e = 0.5, mu = 0.5). Same set-up, step counts and end-of-run figures as the
// LIGGGHTS and LAMMPS inputs of the case (docs/performance.md).
//
// Usage: case_settle3d [NX NY NZ NWARM NRUN]      (default 25 25 16 1000 4000, N = 10,000)
// Prints "key value" lines: the size, the figures after the NWARM untimed steps (warm_*), the
// particle-steps per second of the NRUN timed steps and the figures after the last step. Threads:
// OMP_NUM_THREADS. Exits with status 1 if a particle has left the box, 2 on a bad command line.
#include "run_case.hpp"

int main(int argc, char** argv) {
  using namespace grain;
  std::vector<long> a = {25, 25, 16, 1000, 4000};
  if (!bench::parse_arguments(argc, argv, a, {1, 1, 1, 0, 1})) {
    std::fprintf(
        stderr,
        "usage: case_settle3d [NX NY NZ NWARM NRUN]  (NX, NY, NZ, NRUN >= 1; NWARM >= 0)\n");
    return 2;
  }
  const int nx = static_cast<int>(a[0]), ny = static_cast<int>(a[1]), nz = static_cast<int>(a[2]);
  auto sim = bench::make_settle3d(nx, ny, nz);
  const double s = 1.02 * bench::case_diameter;
  std::printf("case settle3d\n");
  std::printf("size %d %d %d\n", nx, ny, nz);
  return bench::run_case(sim, Vec3::Zero(), Vec3(nx * s, ny * s, nz * s), a[3], a[4]);
}
