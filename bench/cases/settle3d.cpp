// settle3d benchmark case: spheres on a simple cubic lattice settle in a closed box of 6 planes
// (Hertz-Mindlin, e = 0.5, mu = 0.5). Same set-up, step counts and end-of-run figures as the
// LIGGGHTS and LAMMPS inputs of the case (docs/performance.md).
//
// Usage: case_settle3d [NX NY NZ NWARM NRUN [periodic]]  (default 25 25 16 1000 4000, N = 10,000)
// `periodic`: x and y periodic instead of the 4 side planes (the cost of periodic boundaries).
// Prints "key value" lines: the size, the figures after the NWARM untimed steps (warm_*), the
// particle-steps per second of the NRUN timed steps and the figures after the last step. Threads:
// OMP_NUM_THREADS. Exits with status 1 if a particle has left the box, 2 on a bad command line.
// Built a second time as case_settle3d_by_id (GRAIN_CASE_SUMS_BY_ID): the contact loads summed per
// particle in ascending partner id (grain::sums<grain::by_id>, docs/sums.md), walled only.
#include "run_case.hpp"

int main(int argc, char** argv) {
  using namespace grain;
  std::vector<long> a = {25, 25, 16, 1000, 4000};
  const bool periodic = argc == 7 && std::string(argv[6]) == "periodic";
  if (!bench::parse_arguments(periodic ? 6 : argc, argv, a, {1, 1, 1, 0, 1})) {
    std::fprintf(stderr, "usage: case_settle3d [NX NY NZ NWARM NRUN [periodic]]  (NX, NY, NZ, "
                         "NRUN >= 1; NWARM >= 0)\n");
    return 2;
  }
  const int nx = static_cast<int>(a[0]), ny = static_cast<int>(a[1]), nz = static_cast<int>(a[2]);
#ifdef GRAIN_CASE_SUMS_BY_ID
  if (periodic) {
    std::fprintf(stderr, "case_settle3d_by_id: walled only\n");
    return 2;
  }
  auto sim = bench::make_settle3d<search::CellList, sums<by_id>>(nx, ny, nz);
#else
  auto sim = bench::make_settle3d(nx, ny, nz, periodic);
#endif
  const double s = 1.02 * bench::case_diameter;
#ifdef GRAIN_CASE_SUMS_BY_ID
  std::printf("case settle3d by_id\n");
#else
  std::printf("case settle3d%s\n", periodic ? " periodic" : "");
#endif
  std::printf("size %d %d %d\n", nx, ny, nz);
  // periodic: a particle may lie up to half a skin outside the box between list builds
  const double margin = periodic ? 0.1 * bench::case_diameter : 0.0;
  return bench::run_case(sim, Vec3(-margin, -margin, 0.0),
                         Vec3(nx * s + margin, ny * s + margin, nz * s), a[3], a[4]);
}
