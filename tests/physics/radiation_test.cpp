// Thermal radiation of particles with their local environment (radiation::ZhouYuZulli).
//
// Closed forms: a particle of capacity C, emissivity eps and surface A in an environment held at
// T_L exchanges C dT/dt = sigma eps A (T_L^4 - T^4), so that
//   t(T) = C / (sigma eps A) (G(T) - G(T0)),  G(T) = (ln|(T + a)/(T - a)| + 2 atan(T/a)) / (4 a^3),
// with a = T_L (dG/dT = 1/(a^4 - T^4)); its steady temperature is T_L.
// - a particle alone sees the fluid: T_L = T_f;
// - a particle among k neighbours held at T_n within 1.5 diameters (and others held hotter just
//   beyond) sees T_L = phi T_f + (1 - phi) T_n, phi = 1 - k V_p / (V_Omega - V_p): in 3D six
//   neighbours, phi = 1 - 6/26; in 2D four, phi = 1 - 4/8.

#include "../approx.hpp"
#include "../support/materials.hpp"
#include <doctest/doctest.h>
#include <grain/grain.hpp>

#include <cmath>
#include <numbers>
#include <vector>

using namespace grain;
using grain::test::approx;

namespace {

using Thermal =
    Interaction<normal::Hertz<>, tangent::None, rolling::None, conduction::BatchelorOBrien>;
using Sim3 = Simulation<Sphere, search::CellList, Thermal, radiation::ZhouYuZulli>;
using Sim2 = Simulation<Disk, search::CellList, Thermal, radiation::ZhouYuZulli>;

constexpr double pi = std::numbers::pi;
constexpr double sigma = 5.670374419e-8;

double G(double T, double a) {
  return (std::log(std::abs((T + a) / (T - a))) + 2.0 * std::atan(T / a)) / (4.0 * a * a * a);
}

Material radiating(double emissivity) {
  Material m = grain::test::glass();
  m.emissivity = emissivity;
  return m;
}

template <class Sim>
typename Sim::Params thermal_params(double dt, double t_fluid) {
  typename Sim::Params prm;
  prm.analysis = Analysis::thermal;
  prm.time_step = dt;
  prm.fluid.temperature = t_fluid;
  return prm;
}

/// A particle at the origin with k neighbours at 2.5 R along the axes held at T_n, and particles
/// held at 2000 K on the diagonals at 3.5 R (beyond the domain of 3 R); returns the id of the
/// particle at the origin.
template <class Sim>
std::int64_t surround(Sim& sim, std::uint32_t m, double R, double t_n) {
  constexpr int D = Sim::dimension;
  using V = Vec<D>;
  const auto centre =
      sim.add_particle({.position = V::Zero(), .radius = R, .material = m, .temperature = 300.0});
  std::vector<std::int64_t> near, far;
  for (int k = 0; k < D; ++k)
    for (const double s : {-1.0, 1.0}) {
      V x = V::Zero();
      x[k] = 2.5 * R * s;
      near.push_back(sim.add_particle({.position = x, .radius = R, .material = m}));
    }
  for (int c = 0; c < (1 << D); ++c) {
    V x;
    for (int k = 0; k < D; ++k)
      x[k] = ((c >> k) & 1 ? 1.0 : -1.0) * 3.5 * R / std::sqrt(double(D));
    far.push_back(sim.add_particle({.position = x, .radius = R, .material = m}));
  }
  sim.add_group("near", near);
  sim.add_group("far", far);
  sim.fix_temperature("near", t_n);
  sim.fix_temperature("far", 2000.0);
  return centre;
}

} // namespace

TEST_CASE("radiation: a particle alone cools to the fluid as sigma eps A (T_f^4 - T^4)") {
  const double R = 0.005, eps = 0.8, Tf = 300.0, T0 = 1000.0, T1 = 600.0;
  const Material mat = radiating(eps);
  const double C = mat.density * 4.0 / 3.0 * pi * R * R * R * mat.heat_capacity;
  const double A = 4.0 * pi * R * R;
  const double t1 = C / (sigma * eps * A) * (G(T1, Tf) - G(T0, Tf));
  REQUIRE(t1 > 0.0);
  Sim3 sim(thermal_params<Sim3>(t1 / 20000.0, Tf));
  const auto m = sim.add_material(mat);
  sim.add_particle({.position = {0, 0, 0}, .radius = R, .material = m, .temperature = T0});
  sim.run(t1);
  // forward Euler over 2e4 steps: below 0.06 K
  CHECK(sim.particles().temperature[0] == approx(T1).epsilon(1e-4));
}

TEST_CASE("radiation: neighbours within 1.5 diameters and the fluid make the local environment") {
  const double R = 0.001, eps = 1.0, Tf = 300.0, Tn = 800.0;
  const Material mat = radiating(eps);
  SUBCASE("spheres") {
    const double phi = 1.0 - 6.0 / 26.0, TL = phi * Tf + (1.0 - phi) * Tn;
    const double C = mat.density * 4.0 / 3.0 * pi * R * R * R * mat.heat_capacity;
    const double A = 4.0 * pi * R * R;
    const double t1 = C / (sigma * eps * A) * (G(400.0, TL) - G(300.0, TL));
    Sim3 sim(thermal_params<Sim3>(t1 / 20000.0, Tf));
    const auto m = sim.add_material(mat);
    const auto c = surround(sim, m, R, Tn);
    sim.run(t1);
    CHECK(sim.particles().temperature[sim.index_of(c)] == approx(400.0).epsilon(1e-4));
    // steady: the environment's temperature (time constant C / (4 sigma eps A T_L^3) = 40 s)
    sim.run(1500.0);
    CHECK(sim.particles().temperature[sim.index_of(c)] == approx(TL).epsilon(1e-9));
  }
  SUBCASE("disks") {
    const double phi = 1.0 - 4.0 / 8.0, TL = phi * Tf + (1.0 - phi) * Tn;
    const double L = Disk{}.thickness; // length of the disks
    const double C = mat.density * pi * R * R * L * mat.heat_capacity;
    const double A = 2.0 * pi * R * L;
    const double t1 = C / (sigma * eps * A) * (G(500.0, TL) - G(300.0, TL));
    Sim2 sim(thermal_params<Sim2>(t1 / 20000.0, Tf));
    const auto m = sim.add_material(mat);
    const auto c = surround(sim, m, R, Tn);
    sim.run(t1);
    CHECK(sim.particles().temperature[sim.index_of(c)] == approx(500.0).epsilon(1e-4));
    sim.run(1500.0);
    CHECK(sim.particles().temperature[sim.index_of(c)] == approx(TL).epsilon(1e-9));
  }
}

TEST_CASE("radiation: a particle passing by is seen exactly while inside the domain") {
  // B (held at 1000 K) flies past A at 2.5 R without touching it: A's domain (3 R) holds B while
  // |x_B| <= sqrt(9 - 6.25) R, that is for 2 sqrt(2.75) R / v; A gains heat only then, with
  // T_L = phi T_f + (1 - phi) 1000 K, phi = 1 - 1/26. The neighbour list is rebuilt many times
  // on the way (skin 0.2 R).
  using Sim = Sim3;
  const double R = 0.001, eps = 1.0, Tf = 300.0, v = 1.0;
  Material mat = radiating(eps);
  mat.young = 1e7;
  Sim::Params prm;
  prm.time_step = 1e-6;
  prm.fluid.temperature = Tf;
  Sim sim(prm);
  const auto m = sim.add_material(mat);
  const auto a =
      sim.add_particle({.position = {0, 0, 0}, .radius = R, .material = m, .temperature = Tf});
  const auto b = sim.add_particle({.position = {-10 * R, 2.5 * R, 0},
                                   .radius = R,
                                   .material = m,
                                   .velocity = {v, 0, 0},
                                   .temperature = 1000.0});
  sim.add_group("hot", {b});
  sim.fix_temperature("hot", 1000.0);
  sim.run(20 * R / v);
  const double phi = 1.0 - 1.0 / 26.0, TL = phi * Tf + (1.0 - phi) * 1000.0;
  const double C = mat.density * 4.0 / 3.0 * pi * R * R * R * mat.heat_capacity;
  const double inside = 2.0 * std::sqrt(2.75) * R / v;
  // G(T) - G(Tf) = sigma eps A t / C, solved for T by bisection
  const double target = sigma * eps * 4.0 * pi * R * R * inside / C;
  double lo = Tf, hi = TL;
  for (int it = 0; it < 200; ++it) {
    const double t = 0.5 * (lo + hi);
    (G(t, TL) - G(Tf, TL) < target ? lo : hi) = t;
  }
  const double expected = 0.5 * (lo + hi) - Tf;
  REQUIRE(expected > 5e-4);
  // one step in 3300 of the time inside: 3e-4 of the rise at most
  CHECK(sim.particles().temperature[sim.index_of(a)] - Tf == approx(expected).epsilon(5e-4));
  CHECK(sim.counters().rebuilds > 50);
}

TEST_CASE("radiation: bad emissivities and domains are named") {
  Material bad = radiating(1.5);
  Sim3 sim;
  CHECK_THROWS_WITH_AS(sim.add_material(bad), doctest::Contains("emissivity = 1.5 is invalid"),
                       InputError);
  Sim3::Params prm;
  prm.radiation.domain = 0.4;
  CHECK_THROWS_WITH_AS(Sim3{prm}, doctest::Contains("domain = 0.4 is invalid"), InputError);
  Sim3 dark;
  const auto m = dark.add_material(radiating(0.0));
  dark.add_particle({.position = {0, 0, 0}, .radius = 0.01, .material = m});
  CHECK_THROWS_WITH_AS(dark.initialize(), doctest::Contains("every material has emissivity = 0"),
                       InputError);
}
