// pack2d benchmark case: disks on a square lattice rearrange and compact under gravity in a box
// of 4 walls (linear spring-dashpot, e = 0.5, mu = 0.5). Same set-up, step counts and end-of-run
// figures as the LIGGGHTS and LAMMPS inputs of the case (docs/performance.md).
//
// Usage: case_pack2d [NX NY NWARM NRUN [PER_CONTACT]]   (default 125 80 1000 4000 0, N = 10,000)
// PER_CONTACT = 1 computes the contact coefficients in every contact from the Hertz-equivalent
// formula (as LIGGGHTS does) instead of once per pair type (as LAMMPS' input gives them); the
// values, and so the results, are the same.
// Prints "key value" lines: the contact coefficients of disk-disk and disk-wall contacts, the
// size, the figures after the NWARM untimed steps (warm_*), the particle-steps per second of the
// NRUN timed steps and the figures after the last step (rke with the 0.4 m r^2 prefactor of the
// peers' compute erotate/sphere). Threads: OMP_NUM_THREADS. Exits with status 1 if a particle has
// left the box, 2 on a bad command line.
#include "run_case.hpp"

namespace {

/// Prints k_n, eta_n, k_t, eta_t [N/m, N s/m] of a contact between materials a and b of
/// effective radius r and mass m, with the parameters the simulation uses for that pair.
template <class Sim>
void print_coefficients(const Sim& sim, const char* which, std::size_t a, std::size_t b, double r,
                        double m) {
  using namespace grain;
  using Normal = normal::LinearSpringDashpot;
  const auto& pair = sim.pair_properties(a, b);
  const auto& c = sim.contact_params(a, b);
  const double kn = Normal::stiffness(pair, c.normal, r, m);
  const double gn = Normal::damping(pair, c.normal, kn, m);
  ContactGeometry<2> g;
  g.r_eff = r;
  g.m_eff = m;
  const auto t =
      tangent::SpringDashpotSlider::spring<2>(g, pair, NormalResult{0.0, kn, gn, 0.0}, c.tangent);
  std::printf("kn_%s %.10g\ngn_%s %.10g\nkt_%s %.10g\ngt_%s %.10g\n", which, kn, which, gn, which,
              t.k, which, t.eta);
}

} // namespace

int main(int argc, char** argv) {
  using namespace grain;
  std::vector<long> a = {125, 80, 1000, 4000, 0};
  if (argc != 1 && argc != 5 && argc != 6) a.clear(); // wrong count: refused below
  if (argc == 5) a.pop_back();
  if (a.empty() || !bench::parse_arguments(argc, argv, a, {1, 1, 0, 1, 0}) ||
      (a.size() == 5 && a[4] > 1)) {
    std::fprintf(stderr, "usage: case_pack2d [NX NY NWARM NRUN [PER_CONTACT]]  (NX, NY, NRUN >= 1; "
                         "NWARM >= 0; PER_CONTACT 0 or 1)\n");
    return 2;
  }
  const int nx = static_cast<int>(a[0]), ny = static_cast<int>(a[1]);
  const bool per_contact = a.size() == 5 && a[4] == 1;
  auto sim = bench::make_pack2d(nx, ny, per_contact);
  const double s = 1.001 * bench::case_diameter, r = 0.5 * bench::case_diameter;
  const double m = sim.particles().mass[0];
  std::printf("case pack2d\n");
  std::printf("size %d %d\n", nx, ny);
  std::printf("mass %.10g\ninertia %.10g\n", m, sim.particles().inertia[0]);
  print_coefficients(sim, "pair", 0, 0, 0.5 * r, 0.5 * m);
  print_coefficients(sim, "wall", 0, 1, r, m);
  std::printf("coefficients %s\n", per_contact ? "per_contact" : "per_pair_type");
  return bench::run_case(sim, Vec2::Zero(), Vec2(nx * s, ny * s), a[2], a[3]);
}
