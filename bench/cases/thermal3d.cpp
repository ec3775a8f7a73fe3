// thermal3d benchmark case: settle3d plus heat conduction between particles (LIGGGHTS
// fix heat/gran/conduction, k = 1 W/(m K), c = 840 J/(kg K)), half of the lattice columns at 400 K,
// the others at 300 K, adiabatic walls. Same set-up, step counts and end-of-run figures as the
// LIGGGHTS input of the case (docs/performance.md), plus dT_hot = <T>_hot - 400 K and
// dT_cold = <T>_cold - 300 K over the initial groups.
//
// Usage: case_thermal3d [NX NY NZ NWARM NRUN]      (default 25 25 16 1000 4000, N = 10,000)
// Output as case_settle3d, with dT_hot, dT_cold (and warm_dT_hot, warm_dT_cold) added.
#include "run_case.hpp"

int main(int argc, char** argv) {
  using namespace grain;
  std::vector<long> a = {25, 25, 16, 1000, 4000};
  if (!bench::parse_arguments(argc, argv, a, {1, 1, 1, 0, 1})) {
    std::fprintf(stderr,
                 "usage: case_thermal3d [NX NY NZ NWARM NRUN]  (NX, NY, NRUN >= 1; NWARM >= 0)\n");
    return 2;
  }
  const int nx = static_cast<int>(a[0]), ny = static_cast<int>(a[1]), nz = static_cast<int>(a[2]);
  auto sim = bench::make_thermal3d(nx, ny, nz);
  const double s = 1.02 * bench::case_diameter;
  std::printf("case thermal3d\n");
  std::printf("size %d %d %d\n", nx, ny, nz);
  auto temperatures = [nx](const auto& sm, const char* prefix) {
    const auto& p = sm.particles();
    double hot = 0, cold = 0;
    std::size_t nh = 0, nc = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.id[i] % nx < nx / 2) {
        hot += p.temperature[i];
        ++nh;
      } else {
        cold += p.temperature[i];
        ++nc;
      }
    }
    std::printf("%sdT_hot %.17g\n", prefix, nh ? hot / double(nh) - 400.0 : 0.0);
    std::printf("%sdT_cold %.17g\n", prefix, nc ? cold / double(nc) - 300.0 : 0.0);
  };
  return bench::run_case(sim, Vec3::Zero(), Vec3(nx * s, ny * s, nz * s), a[3], a[4], temperatures);
}
