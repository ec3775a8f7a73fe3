#pragma once
// The benchmark cases of docs/performance.md, built with grain's public API.
#include <grain/grain.hpp>
#include <cmath>

namespace grain::bench {

/// u(n, alpha) = frac(0.5 + n alpha): the R-sequence used for deterministic initial velocities.
inline double rseq(long n, double alpha) {
  const double x = 0.5 + static_cast<double>(n) * alpha;
  return x - std::floor(x);
}

using Settle3dContact = Interaction<normal::Hertz<>, tangent::SpringDashpotSlider>;
template <class Search = search::CellList>
using Settle3d = Simulation<Sphere, Search, Settle3dContact, integrate::VelocityVerlet>;

/// settle3d: spheres d = 1 mm on a simple cubic lattice (spacing 1.02 d) in a box of 6 planes,
/// Hertz-Mindlin with e = 0.5, mu = 0.5, E = 1e7 Pa, nu = 0.3, dt = 2.5e-6 s, gravity -z.
template <class Search = search::CellList>
Settle3d<Search> make_settle3d(int nx, int ny, int nz) {
  const double d = 1e-3, r = 0.5 * d, a = 1.02 * d, v0 = 0.1;
  Settle3d<Search> sim({.time_step = 2.5e-6, .gravity = Vec3(0, 0, -9.81), .search = {.skin = 0.1 * d}});
  const auto m = sim.add_material({.name = "soft", .density = 2500, .young = 1e7, .poisson = 0.3,
                                   .restitution = 0.5, .friction = 0.5});
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const long n = i + static_cast<long>(nx) * (j + static_cast<long>(ny) * k);
        const Vec3 v(v0 * (2 * rseq(n, 0.8191725133961645) - 1), v0 * (2 * rseq(n, 0.6710436067037893) - 1),
                     v0 * (2 * rseq(n, 0.5497004779019703) - 1));
        sim.add_particle({.position = Vec3((i + 0.5) * a, (j + 0.5) * a, (k + 0.5) * a), .radius = r,
                          .material = m, .velocity = v});
      }
  const Vec3 hi(nx * a, ny * a, nz * a);
  for (int dim = 0; dim < 3; ++dim) {
    sim.add_wall(walls::Plane{Vec3::Zero(), Vec3::Unit(dim)}, {.name = "low", .material = m});
    sim.add_wall(walls::Plane{hi, -Vec3::Unit(dim)}, {.name = "high", .material = m});
  }
  return sim;
}

} // namespace grain::bench
