// The cell-size methods as Simulation options: the Voronoi conduction models receive the fluid-cell
// radius of each pair from a power diagram (VoronoiDiagram) or from porosities (GlobalPorosity,
// LocalPorosity), in 2D and 3D.
#include <doctest/doctest.h>
#include <grain/grain.hpp>
#include <grain/thermal/voronoi.hpp>

#include "../approx.hpp"
#include "../support/materials.hpp"

#include <cmath>
#include <map>
#include <numbers>
#include <utility>

using namespace grain;

namespace {

using grain::test::glass;

/// Conductances by particle-id pair of a thermal analysis of an n x n (x n) lattice, pitch s.
template <class Sim>
std::map<std::pair<std::int64_t, std::int64_t>, double> lattice(Sim& sim, int n, double R,
                                                                double s) {
  const auto m = sim.add_material(glass());
  std::int64_t id = 0;
  using V = Vec<Sim::dimension>;
  for (int k = 0; k < (Sim::dimension == 3 ? n : 1); ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        V x = V::Zero();
        x[0] = i * s;
        x[1] = j * s;
        if constexpr (Sim::dimension == 3) x[2] = k * s;
        sim.add_particle({.position = x, .radius = R, .material = m, .id = id++});
      }
  sim.initialize();
  std::map<std::pair<std::int64_t, std::int64_t>, double> h;
  const auto& p = sim.particles();
  sim.for_each_conductance([&](std::size_t i, std::size_t j, bool wall, double H) {
    if (!wall) h[{std::min(p.id[i], p.id[j]), std::max(p.id[i], p.id[j])}] = H;
  });
  return h;
}

} // namespace

TEST_CASE("Voronoi A with the power diagram of a square lattice: r_ij = s/2 for every nearest "
          "pair") {
  using Contact = Interaction<normal::Hertz<>, tangent::None, rolling::None, conduction::VoronoiA>;
  using Sim = Simulation<Disk, search::CellList, Contact, cells::VoronoiDiagram>;
  Sim::Params p;
  p.analysis = Analysis::thermal;
  p.fluid.conductivity = 0.026;
  p.time_step = 1.0;
  Sim sim(p);
  const double R = 1e-3, delta = 2e-7, s = 2 * R - delta;
  const auto h = lattice(sim, 5, R, s);
  // a = sqrt(R* delta) (area::None), d = 2 sqrt(R^2 - a^2) (the distance consistent with a);
  // k* = 0.5. Interior edges have length s (r = s/2); the faces between two particles on the
  // boundary are clipped at the margin R beyond the outermost centres: r = (s/2 + R)/2.
  const double a = std::sqrt(0.5 * R * delta);
  const double d = 2 * std::sqrt(R * R - a * a);
  const int n = 5;
  CHECK(h.size() == 2 * n * (n - 1)); // diagonals are not Voronoi neighbours
  int boundary = 0;
  for (const auto& [k, H] : h) {
    const int ia = int(k.first % n), ja = int(k.first / n), ib = int(k.second % n),
              jb = int(k.second / n);
    const bool edge =
        (ja == jb && (ja == 0 || ja == n - 1)) || (ia == ib && (ia == 0 || ia == n - 1));
    boundary += edge;
    const double rij = edge ? 0.5 * (s / 2 + R) : s / 2;
    CHECK(H == grain::test::approx(conduction::VoronoiA::mono(R, d, a, rij, 0.5, 0.026, {}))
                   .epsilon(1e-9));
  }
  CHECK(boundary == 4 * (n - 1));
}

TEST_CASE("Voronoi B with global and local porosity cell sizes in 3D") {
  using Contact = Interaction<normal::Hertz<>, tangent::None, rolling::None, conduction::VoronoiB>;
  const double R = 1e-3, delta = 2e-7, s = 2 * R - delta;
  const double a = std::sqrt(0.5 * R * delta);
  {
    // estimated global porosity of a simple-cubic block of whole cells: 1 - pi/6 ... of the
    // hull of the centres; r_ij = 0.56 R (1 - phi)^(-1/3) for every touching pair
    using Sim = Simulation<Sphere, search::CellList, Contact, cells::HullGlobalPorosity>;
    Sim::Params p;
    p.analysis = Analysis::thermal;
    p.fluid.conductivity = 0.026;
    p.time_step = 1.0;
    Sim sim(p);
    const auto h = lattice(sim, 4, R, s);
    std::vector<Vec3> x;
    std::vector<double> r;
    for (std::size_t i = 0; i < sim.size(); ++i) {
      x.push_back(sim.particles().position[i]);
      r.push_back(R);
    }
    const double phi = cells::global_porosity(std::span<const Vec3>(x), std::span<const double>(r));
    const double rij = cells::cell_radius_from_porosity(R, phi);
    const double d = 2 * std::sqrt(R * R - a * a);
    const double expected = conduction::VoronoiB::mono(R, d, a, rij, 0.5, 0.026, {});
    CHECK(h.size() == 3 * 4 * 4 * 3);
    for (const auto& [k, H] : h)
      CHECK(H == grain::test::approx(expected).epsilon(1e-9));
  }
  {
    // local porosity: every pair conducts, with r_ij from the mean of the two local porosities
    using Sim = Simulation<Sphere, search::CellList, Contact, cells::HullLocalPorosity>;
    Sim::Params p;
    p.analysis = Analysis::thermal;
    p.fluid.conductivity = 0.026;
    p.time_step = 1.0;
    Sim sim(p);
    const auto h = lattice(sim, 3, R, s);
    CHECK(h.size() == 3 * 3 * 3 * 2);
    for (const auto& [k, H] : h)
      CHECK(H > 0.0);
  }
}
