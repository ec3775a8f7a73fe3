// Thermal verification (verification reference, section 4): lumped relaxation of two particles,
// a particle on an isothermal wall (static and thermo-mechanical), a 1D chain between a hot and a
// cold wall (steady profile and slowest mode), the effective conductivity of a simple-cubic
// lattice, and conservation of heat in an insulated thermo-mechanical packing.
//
// Conductances are Batchelor-O'Brien, H = 4 k* a, with the Hertz contact radius a = sqrt(R* delta)
// (area::None) unless stated; the lumped model C_i dT_i/dt = sum_j H_ij (T_j - T_i) then holds
// exactly for the simulation, and forward Euler gives dT_n = dT_0 (1 - dt/tau)^n.

#include "../approx.hpp"
#include "../errors.hpp"
#include "../support/materials.hpp"
#include <doctest/doctest.h>
#include <grain/grain.hpp>
#include <grain/models/conduction/batchelor_obrien.hpp>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <tuple>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

using namespace grain;

namespace {

using Thermal =
    Interaction<normal::Hertz<>, tangent::None, rolling::None, conduction::BatchelorOBrien>;
using ThermalGeo = Interaction<normal::Hertz<>, tangent::None, rolling::None,
                               conduction::BatchelorOBrien, area::Geometric>;
using Sim3 = Simulation<Sphere, search::CellList, Thermal>;
using Sim3Geo = Simulation<Sphere, search::AllPairs, ThermalGeo>;
using Sim2 = Simulation<Disk, search::CellList, Thermal>;

using grain::test::glass;

/// Two identical particles R = 0.01 m overlapping by 1e-4 m at 300 K and 400 K (section 4.1).
template <class Sim>
Sim two_particles(double dt) {
  typename Sim::Params p;
  p.analysis = Analysis::thermal;
  p.time_step = dt;
  Sim sim(p);
  const auto m = sim.add_material(glass());
  using V = Vec<Sim::dimension>;
  V x1 = V::Zero();
  x1[0] = 0.02 - 1e-4;
  sim.add_particle({.position = V::Zero(), .radius = 0.01, .material = m, .temperature = 300});
  sim.add_particle({.position = x1, .radius = 0.01, .material = m, .temperature = 400});
  sim.initialize();
  return sim;
}

double temperature_of(const auto& sim, std::int64_t id) {
  return sim.particles().temperature[sim.index_of(id)];
}

} // namespace

TEST_CASE("4.1 two particles relax with constant conductance (exact for forward Euler)") {
  // C = rho 4/3 pi R^3 c = 8.37758 J/K; Hertz radius a = sqrt(R* delta) = 7.07107e-4 m,
  // H = 2 k a = 1.41421e-3 W/K, tau = C1 C2/(H (C1 + C2)) = 2961.9 s (reference, computed).
  const double C = 2500 * 4.0 / 3.0 * std::numbers::pi * 1e-6 * 800;
  CHECK(C == grain::test::approx(8.37758).epsilon(1e-6));
  const double H = 2.0 * 1.0 * std::sqrt(0.005 * 1e-4);
  const double tau = C / (2.0 * H);
  CHECK(tau == grain::test::approx(2961.9).epsilon(2e-5));

  for (double dt : {10.0, 100.0, 500.0}) {
    auto sim = two_particles<Sim3>(dt);
    const double e0 = sim.thermal_energy();
    const long n = static_cast<long>(std::lround(tau / dt));
    sim.steps(n);
    const double dT = temperature_of(sim, 1) - temperature_of(sim, 0);
    // class A: forward Euler's own recursion, to round-off
    CHECK(dT == grain::test::approx(100.0 * std::pow(1.0 - dt / tau, double(n))).epsilon(1e-11));
    // invariant C1 T1 + C2 T2, to round-off
    CHECK(std::abs(sim.thermal_energy() - e0) <= 1e-13 * e0);
  }
  // class B: against the exponential; the global error falls in proportion to dt
  auto error = [&](double dt) {
    auto sim = two_particles<Sim3>(dt);
    const long n = static_cast<long>(std::lround(tau / dt));
    sim.steps(n);
    const double t = double(n) * dt;
    return std::abs(temperature_of(sim, 0) - (350.0 - 50.0 * std::exp(-t / tau)));
  };
  const double e1 = error(tau / 100), e2 = error(tau / 200);
  CHECK(e1 / e2 == grain::test::approx(2.0).epsilon(0.02));
  CHECK(e2 < 0.05); // K, at dt = tau/200
  {
    // at t = tau: T1 = 350 - 50/e = 331.606 K (reference), with dt = tau/1000
    auto sim = two_particles<Sim3>(tau / 1000);
    sim.steps(1000);
    CHECK(temperature_of(sim, 0) == grain::test::approx(331.606).epsilon(1e-4));
  }
  {
    // geometric (lens) radius a = 9.98749e-4 m: H = 1.99750e-3 W/K, tau = 2097.0 s (reference)
    auto sim = two_particles<Sim3Geo>(1.0);
    sim.steps(2097);
    const double dT = temperature_of(sim, 1) - temperature_of(sim, 0);
    const double tau_geo = C / (2.0 * 2.0 * 9.98749e-4);
    CHECK(tau_geo == grain::test::approx(2097.0).epsilon(1e-4));
    CHECK(dT == grain::test::approx(100.0 * std::pow(1.0 - 1.0 / tau_geo, 2097.0)).epsilon(1e-5));
  }
  {
    // 2D disks, same geometry: the same conductance (no length factor), C = rho pi R^2 L c
    auto sim = two_particles<Sim2>(10.0);
    const double C2 = 2500 * std::numbers::pi * 1e-4 * 1.0 * 800;
    const double tau2 = C2 / (2.0 * H);
    sim.steps(100);
    const double dT = temperature_of(sim, 1) - temperature_of(sim, 0);
    CHECK(dT == grain::test::approx(100.0 * std::pow(1.0 - 10.0 / tau2, 100.0)).epsilon(1e-11));
  }
}

TEST_CASE("4.2 particle on an isothermal wall") {
  // Static: T(t) = T_w + (T0 - T_w) exp(-H t / C), H = 4 k* a with k* = k_p k_w/(k_p + k_w).
  Sim3::Params p;
  p.analysis = Analysis::thermal;
  p.time_step = 5.0;
  Sim3 sim(p);
  const auto m = sim.add_material(glass());
  Material wall_mat = glass();
  wall_mat.name = "copper";
  wall_mat.conductivity = 3.0;
  const auto w = sim.add_material(wall_mat);
  sim.add_wall(walls::Plane{{0, 0, 0}, {0, 0, 1}},
               {.name = "hot plate", .material = w, .temperature = TimeFunction(400.0)});
  sim.add_particle(
      {.position = {0, 0, 0.01 - 1e-4}, .radius = 0.01, .material = m, .temperature = 300});
  sim.initialize();
  const double C = 2500 * 4.0 / 3.0 * std::numbers::pi * 1e-6 * 800;
  const double H = 4.0 * (1.0 * 3.0 / 4.0) * std::sqrt(0.01 * 1e-4);
  const double rate = H / C;
  sim.steps(400);
  const double t = 2000.0;
  // class A: forward Euler recursion; class B: the exponential within dt/tau
  CHECK(temperature_of(sim, 0) ==
        grain::test::approx(400.0 - 100.0 * std::pow(1.0 - 5.0 * rate, 400.0)).epsilon(1e-11));
  CHECK(temperature_of(sim, 0) ==
        grain::test::approx(400.0 - 100.0 * std::exp(-rate * t)).epsilon(1e-4));
  {
    // 2D: a disk on a segment at 400 K (same overlap; C = rho pi R^2 L c with L = 1 m)
    Sim2::Params p2;
    p2.analysis = Analysis::thermal;
    p2.time_step = 5.0;
    Sim2 s2(p2);
    const auto m2 = s2.add_material(glass());
    const auto w2 = s2.add_material(wall_mat);
    s2.add_wall(walls::Segment{{-1, 0}, {1, 0}}, {.material = w2, .temperature = 400.0});
    s2.add_particle(
        {.position = {0, 0.01 - 1e-4}, .radius = 0.01, .material = m2, .temperature = 300});
    s2.steps(400);
    const double C2 = 2500 * std::numbers::pi * 1e-4 * 800;
    CHECK(temperature_of(s2, 0) ==
          grain::test::approx(400.0 - 100.0 * std::pow(1.0 - 5.0 * H / C2, 400.0)).epsilon(1e-11));
  }
}

TEST_CASE("4.2 thermo-mechanical: a steel sphere resting on a wall conducts through its Hertz "
          "contact") {
  // Steel sphere R = 5 mm, rho = 7800, E = 200 GPa, nu = 0.3 on a rigid wall (E* = E/(1 - nu^2)
  // when the wall's material is much stiffer) under gravity: static Hertz radius
  // a_H = (3 m g R / (4 E*))^(1/3) = 8.81e-6 m; with k_p = k_w = 16 W/(m K):
  // H = 4 (k/2) a_H = 2.82e-4 W/K (reference, computed). The sphere is dropped from rest
  // touching the wall, settles under strong damping, and the measured heat rate gives H.
  Sim3::Params p;
  p.gravity = {0, 0, -9.81};
  Sim3 sim(p);
  const auto steel = sim.add_material({.name = "steel",
                                       .density = 7800,
                                       .young = 200e9,
                                       .poisson = 0.3,
                                       .restitution = 0.05,
                                       .conductivity = 16,
                                       .heat_capacity = 500});
  const auto rigid = sim.add_material({.name = "rigid steel",
                                       .density = 7800,
                                       .young = 200e15,
                                       .poisson = 0.3,
                                       .restitution = 0.05,
                                       .conductivity = 16,
                                       .heat_capacity = 500});
  sim.add_wall(walls::Plane{{0, 0, 0}, {0, 0, 1}}, {.material = rigid, .temperature = 310.0});
  sim.add_particle(
      {.position = {0, 0, 0.005}, .radius = 0.005, .material = steel, .temperature = 300});
  sim.initialize();
  sim.run(2e-3);
  const auto& q = sim.particles();
  const double m = q.mass[0];
  const double estar = 200e9 / (1 - 0.09);
  const double aH = std::cbrt(3.0 * m * 9.81 * 0.005 / (4.0 * estar));
  CHECK(aH == grain::test::approx(8.81e-6).epsilon(1e-3));
  const double H = q.heat_rate[0] / (310.0 - q.temperature[0]);
  // tolerance: the remaining vibration of the settled sphere changes the overlap by < 0.1 %
  CHECK(H == grain::test::approx(4.0 * 8.0 * aH).epsilon(2e-3));
  CHECK(H == grain::test::approx(2.82e-4).epsilon(2e-3));
  // tau = C/H = m c / H = 7.24e3 s (reference)
  CHECK(m * 500 / H == grain::test::approx(7.24e3).epsilon(2e-3));
}

TEST_CASE("4.4 chain of 10 spheres between a hot and a cold wall: steady profile and slowest "
          "mode") {
  // Equal conductances between neighbours and to the walls (H_w = H): the wall overlaps are half
  // the pair overlaps, so sqrt(R delta_w) = sqrt(R/2 delta) and k* is k/2 on both. Steady state
  // T_i = T_L + (T_R - T_L) i/(N+1); from a uniform start the slowest mode decays with
  // tau_1 = C / (4 H sin^2(pi/(2(N+1)))) = 12.344 C/H for N = 10.
  constexpr int N = 10;
  const double R = 0.005, delta = 2e-5, TL = 273.15, TR = 323.15;
  const double C = 2500 * 4.0 / 3.0 * std::numbers::pi * R * R * R * 800;
  const double H = 4.0 * 0.5 * std::sqrt(R / 2 * delta);
  const double tau1 = C / (4.0 * H * std::pow(std::sin(std::numbers::pi / (2.0 * (N + 1))), 2));
  CHECK(tau1 * H / C == grain::test::approx(12.344).epsilon(1e-4));
  Sim3::Params p;
  p.analysis = Analysis::thermal;
  // stable below 2/lambda_max = 0.510 C/H; the sufficient bound is C/(2H)
  p.time_step = 0.2 * C / H;
  Sim3 sim(p);
  const auto m = sim.add_material(glass());
  const double pitch = 2 * R - delta;
  const double x0 = R - delta / 2;
  sim.add_wall(walls::Plane{{0, 0, 0}, {1, 0, 0}}, {.material = m, .temperature = TL});
  sim.add_wall(walls::Plane{{2 * x0 + (N - 1) * pitch, 0, 0}, {-1, 0, 0}},
               {.material = m, .temperature = TR});
  for (int i = 0; i < N; ++i)
    sim.add_particle({.position = {x0 + i * pitch, 0, 0},
                      .radius = R,
                      .material = m,
                      .temperature = TL,
                      .id = i});
  sim.initialize();
  // lambda_max = 4 (H/C) sin^2(N pi / (2 (N + 1))): the limit 2/lambda_max = 0.5103 C/H (the
  // Lanczos estimate is exact to rounding for 10 particles); the bound C/(2H)
  const double fastest =
      4.0 * H / C * std::pow(std::sin(N * std::numbers::pi / (2.0 * (N + 1))), 2);
  CHECK(sim.conduction_time_step() == grain::test::approx(2.0 / fastest).epsilon(1e-9));
  CHECK(sim.conduction_time_step() * H / C == grain::test::approx(0.51034).epsilon(1e-4));
  CHECK(sim.conduction_bound() == grain::test::approx(C / (2 * H)).epsilon(1e-12));
  // the slowest mode from the late-time decay of the deviation from the steady state
  auto deviation = [&] {
    double s = 0;
    for (int i = 0; i < N; ++i)
      s += std::abs(temperature_of(sim, i) - (TL + (TR - TL) * (i + 1) / (N + 1)));
    return s;
  };
  const long n1 = static_cast<long>(std::lround(3 * tau1 / p.time_step));
  sim.steps(n1);
  const double d1 = deviation();
  sim.steps(n1);
  const double d2 = deviation();
  // forward Euler's discrete decay rate of the mode: ln(1 - dt lambda_1)/dt
  const double lambda1 = 1.0 / tau1;
  const double discrete = -std::log(1.0 - p.time_step * lambda1) / p.time_step;
  const double measured = std::log(d1 / d2) / (double(n1) * p.time_step);
  CHECK(measured == grain::test::approx(discrete).epsilon(1e-3));
  CHECK(measured == grain::test::approx(lambda1).epsilon(0.12)); // dt = 0.2 C/H: 1st-order offset
  sim.steps(40 * n1);
  for (int i = 0; i < N; ++i)
    CHECK(temperature_of(sim, i) ==
          grain::test::approx(TL + (TR - TL) * (i + 1) / (N + 1)).epsilon(1e-10));
}

TEST_CASE("the conduction limit is the eigenvalue limit: a chain runs stably between the bound "
          "C/(2H) and 2/lambda_max, and a step above 2/lambda_max is refused") {
  // The chain of 4.4 (N = 10, H_w = H): forward Euler is stable for dt < 2/lambda_max =
  // 0.5103 C/H. At dt = 0.505 C/H (above the bound C/(2H)) the fastest mode is multiplied by
  // 1 - dt lambda_max = -0.979 per step: it decays, and the chain reaches its steady profile. At
  // dt = 0.515 C/H the factor is -1.018: the run is refused before it starts.
  constexpr int N = 10;
  const double R = 0.005, delta = 2e-5, TL = 273.15, TR = 323.15;
  const double C = 2500 * 4.0 / 3.0 * std::numbers::pi * R * R * R * 800;
  const double H = 4.0 * 0.5 * std::sqrt(R / 2 * delta);
  auto chain = [&](double dt) {
    Sim3::Params p;
    p.analysis = Analysis::thermal;
    p.time_step = dt;
    Sim3 sim(p);
    const auto m = sim.add_material(glass());
    const double pitch = 2 * R - delta;
    const double x0 = R - delta / 2;
    sim.add_wall(walls::Plane{{0, 0, 0}, {1, 0, 0}}, {.material = m, .temperature = TL});
    sim.add_wall(walls::Plane{{2 * x0 + (N - 1) * pitch, 0, 0}, {-1, 0, 0}},
                 {.material = m, .temperature = TR});
    for (int i = 0; i < N; ++i)
      sim.add_particle({.position = {x0 + i * pitch, 0, 0},
                        .radius = R,
                        .material = m,
                        .temperature = i % 2 ? TR : TL, // the fastest mode is excited
                        .id = i});
    return sim;
  };
  auto stable = chain(0.505 * C / H);
  stable.steps(20000);
  for (int i = 0; i < N; ++i)
    CHECK(temperature_of(stable, i) ==
          grain::test::approx(TL + (TR - TL) * (i + 1) / (N + 1)).epsilon(1e-9));
  auto above = chain(0.515 * C / H);
  const auto e = grain::test::error_of([&] { above.initialize(); });
  CHECK(grain::test::has(e, "above the conduction limit"));
  CHECK(grain::test::has(e, "2 / lambda_max"));
  CHECK(above.conduction_time_step() * H / C == grain::test::approx(0.51034).epsilon(1e-4));
}

TEST_CASE("4.5 simple-cubic lattice between a hot and a cold wall: k_e = H/(2R)") {
  // 4 x 4 x 10 spheres at spacing 2R - delta, walls on the short faces, adiabatic sides; at steady
  // state the heat flux per unit area over the gradient between interior layers is H/(2R - delta)
  // (the lattice pitch replaces 2R for overlapping spheres).
  const double R = 0.005, delta = 2e-5, pitch = 2 * R - delta;
  const int nx = 4, ny = 4, nz = 10;
  Sim3::Params p;
  p.analysis = Analysis::thermal;
  const double C = 2500 * 4.0 / 3.0 * std::numbers::pi * R * R * R * 800;
  const double H = 4.0 * 0.5 * std::sqrt(R / 2 * delta);
  p.time_step = 0.1 * C / H; // sufficient bound C/(6H) for the 6 contacts of an interior sphere
  Sim3 sim(p);
  const auto m = sim.add_material(glass());
  const double z0 = R - delta / 2;
  sim.add_wall(walls::Plane{{0, 0, 0}, {0, 0, 1}}, {.material = m, .temperature = 350.0});
  sim.add_wall(walls::Plane{{0, 0, 2 * z0 + (nz - 1) * pitch}, {0, 0, -1}},
               {.material = m, .temperature = 300.0});
  std::int64_t id = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        sim.add_particle({.position = {i * pitch, j * pitch, z0 + k * pitch},
                          .radius = R,
                          .material = m,
                          .temperature = 300.0,
                          .id = id++});
  sim.steps(12000);
  auto layer_mean = [&](int k) {
    double s = 0;
    for (int q = 0; q < nx * ny; ++q)
      s += temperature_of(sim, k * nx * ny + q);
    return s / (nx * ny);
  };
  // flux through the contacts between layers 4 and 5, per unit area
  double flux = 0;
  for (int q = 0; q < nx * ny; ++q)
    flux += H * (temperature_of(sim, 4 * nx * ny + q) - temperature_of(sim, 5 * nx * ny + q));
  flux /= nx * ny * pitch * pitch;
  const double gradient = (layer_mean(3) - layer_mean(6)) / (3 * pitch);
  CHECK(flux / gradient == grain::test::approx(H / pitch).epsilon(1e-6));
}

TEST_CASE("heat is conserved to round-off in an insulated thermo-mechanical packing, and is "
          "bit-identical for 1 and 2 threads") {
  // 2D: 400 disks with random temperatures fall into an insulated box and settle while
  // conducting; the heat content sum m c T is constant to round-off.
  auto run = [](int threads) {
#ifdef _OPENMP
    omp_set_num_threads(threads);
#else
    (void)threads;
#endif
    using Sim = Simulation<Disk, search::CellList,
                           Interaction<normal::Hertz<>, tangent::SpringDashpotSlider, rolling::None,
                                       conduction::BatchelorOBrien>>;
    Sim::Params p;
    p.gravity = {0, -9.81};
    Sim sim(p);
    const auto m = sim.add_material({.name = "soft glass",
                                     .density = 2500,
                                     .young = 1e7,
                                     .poisson = 0.25,
                                     .restitution = 0.3,
                                     .friction = 0.4,
                                     .conductivity = 1.0,
                                     .heat_capacity = 800});
    sim.add_wall(walls::Segment{{0, 0}, {0.23, 0}}, {.material = m});
    sim.add_wall(walls::Segment{{0, 0}, {0, 0.8}}, {.material = m});
    sim.add_wall(walls::Segment{{0.23, 0}, {0.23, 0.8}}, {.material = m});
    for (int k = 0; k < 1200; ++k) {
      const double x = 0.01 + 0.011 * (k % 20), y = 0.01 + 0.011 * (k / 20);
      sim.add_particle({.position = {x, y},
                        .radius = 0.004 + 0.0005 * ((k * 7) % 3),
                        .material = m,
                        .temperature = 300.0 + double((k * 37) % 101)});
    }
    const double e0 = sim.thermal_energy();
    sim.run(0.2);
    const double e1 = sim.thermal_energy();
    CHECK(std::abs(e1 - e0) <= 1e-13 * e0);
    CHECK(sim.contact_counts().first > 500);
    CHECK(sim.particles().temperature[sim.index_of(0)] != 300.0);
    return sim.particles().temperature;
  };
#ifdef _OPENMP
  const int saved = omp_get_max_threads();
#endif
  const auto a = run(1);
  const auto b = run(2);
#ifdef _OPENMP
  omp_set_num_threads(saved);
#endif
  CHECK(a == b);
}

TEST_CASE("thermal input errors name the object, the value and the valid range") {
  {
    // a time step above the conduction limit of two particles, C/H = 2 tau = 5923.8 s (exact)
    auto make = [] { return two_particles<Sim3>(5930.0); };
    CHECK(two_particles<Sim3>(5920.0).conduction_time_step() ==
          grain::test::approx(2 * 2961.9).epsilon(2e-5));
    CHECK_THROWS_WITH_AS(make(), doctest::Contains("conduction limit"), InputError);
    // exactly at the limit, C/H: the difference would flip sign each step without decaying
    const double limit = two_particles<Sim3>(5920.0).conduction_time_step();
    CHECK_THROWS_WITH_AS(two_particles<Sim3>(limit), doctest::Contains("at the conduction limit"),
                         InputError);
  }
  {
    Sim3::Params p;
    p.analysis = Analysis::thermal;
    Sim3 sim(p);
    Material m = glass();
    m.heat_capacity = 0;
    const auto k = sim.add_material(m);
    sim.add_particle({.position = {0, 0, 0}, .radius = 0.01, .material = k});
    CHECK_THROWS_WITH_AS(sim.initialize(), doctest::Contains("heat_capacity = 0"), InputError);
  }
  {
    Sim3 sim;
    const auto k = sim.add_material(glass());
    CHECK_THROWS_WITH_AS(
        sim.add_particle({.position = {0, 0, 0}, .radius = 0.01, .material = k, .temperature = -1}),
        doctest::Contains("temperature = -1"), InputError);
  }
  {
    using Mech = Simulation<Sphere, search::CellList, Interaction<normal::Hertz<>>>;
    Mech::Params p;
    p.analysis = Analysis::thermal;
    CHECK_THROWS_WITH_AS(Mech{p}, doctest::Contains("conduction model"), InputError);
    Mech sim;
    const auto k = sim.add_material(glass());
    CHECK_THROWS_WITH_AS(
        sim.add_particle(
            {.position = {0, 0, 0}, .radius = 0.01, .material = k, .temperature = 300}),
        doctest::Contains("no conduction model"), InputError);
    static_assert(!Mech::thermal);
    static_assert(!HasTemperature<Mech::Particles>);
  }
  {
    // the thermal time scale has units of time: R^2 rho c / k
    auto sim = two_particles<Sim3>(1.0);
    CHECK(sim.thermal_time_step() == grain::test::approx(1e-4 * 2500 * 800 / 1.0).epsilon(1e-12));
  }
}

TEST_CASE("heat from dissipation: a sphere sliding to rolling heats by half the energy it loses") {
  // A sphere launched without spin on an insulated plane slides until v = 5/7 v0, losing 2/7 of
  // its kinetic energy to friction (plus the little the normal damping takes while it settles).
  // With dissipation_heating = 1 half of every dissipated joule heats the sphere (the plane
  // takes the other half): m c dT = (E_mech(0) - E_mech(t))/2, E_mech = kinetic + potential +
  // elastic. Tolerance 1 %: the heat integrates the dissipated power with the step's velocities,
  // the energy balance follows the integrator (first order in dt).
  using Sim = Simulation<
      Sphere, search::AllPairs,
      Interaction<normal::Hertz<>, tangent::Slider, rolling::None, conduction::BatchelorOBrien>>;
  Sim::Params p;
  p.gravity = {0, 0, -9.81};
  p.dissipation_heating = 1.0;
  Sim sim(p);
  const auto m = sim.add_material({.name = "steel",
                                   .density = 7800,
                                   .young = 2e9,
                                   .poisson = 0.3,
                                   .restitution = 0.5,
                                   .friction = 0.3,
                                   .conductivity = 40,
                                   .heat_capacity = 500});
  sim.add_wall(walls::Plane{{0, 0, 0}, {0, 0, 1}}, {.material = m});
  sim.add_particle({.position = {0, 0, 0.005},
                    .radius = 0.005,
                    .material = m,
                    .velocity = {1.0, 0, 0},
                    .temperature = 300});
  sim.initialize();
  auto mech = [&] { return sim.kinetic_energy() + sim.potential_energy() + sim.elastic_energy(); };
  const double e0 = mech();
  const double slip_time = 2.0 * 1.0 / (7.0 * 0.3 * 9.81);
  sim.run(1.5 * slip_time);
  const auto& q = sim.particles();
  const double heat = q.heat_capacity[0] * (q.temperature[0] - 300.0);
  const double lost = e0 - mech();
  CHECK(q.velocity[0].x() == grain::test::approx(5.0 / 7.0).epsilon(2e-3));
  CHECK(lost == grain::test::approx(2.0 / 7.0 * 0.5 * q.mass[0]).epsilon(0.02));
  CHECK(heat == grain::test::approx(0.5 * lost).epsilon(0.01));
}

TEST_CASE("the seed's resting_single model: direct + surrounding-layer conduction to a wall and "
          "convection (verification 4.11)") {
  // Sphere R = 1 m centred 0.99 m above a wall at 400 K (with material), k = 1000, rho = 30,
  // c = 20, T = 300 K; fluid k_f = 10 at 250 K, at rest (Nu = 2). Batchelor-O'Brien with the
  // geometric contact radius a = sqrt(1 - 0.99^2) = 0.141067 m: H = 4 (k/2) a = 282.13 W/K
  // (reference 282.1); surrounding layer 0.4 R to the wall (grain counts the disc near the axis
  // where the gap is held at S, so 1081.58 W/K instead of the seed's 1019.37, see
  // docs/models/conduction_indirect.md); convection h S = (2 k_f / 2R) 4 pi R^2 = 125.66 W/K
  // (reference 125.7). Checked: the initial heat rate (class A, 1e-12) and the lumped steady
  // temperature (H_w T_w + h S T_f)/(H_w + h S) (class A after convergence, 1e-9).
  using Contact =
      Interaction<normal::Hertz<>, tangent::None, rolling::None,
                  conduction::Combined<conduction::BatchelorOBrien, conduction::SurroundingLayer>,
                  area::Geometric>;
  using Sim = Simulation<Sphere, search::AllPairs, Contact, convection::RanzMarshall>;
  Sim::Params p;
  p.analysis = Analysis::thermal;
  p.fluid = {.temperature = 250,
             .density = 1.2,
             .viscosity = 1.8e-5,
             .conductivity = 10,
             .heat_capacity = 1000};
  p.time_step = 1e-3; // tau = C / sum H = 1.69 s
  Sim sim(p);
  const auto m = sim.add_material({.name = "resting_single",
                                   .density = 30,
                                   .young = 1e6,
                                   .conductivity = 1000,
                                   .heat_capacity = 20});
  sim.add_wall(walls::Plane{{0, 0, 0}, {0, 0, 1}}, {.material = m, .temperature = 400.0});
  sim.add_particle({.position = {0, 0, 0.99}, .radius = 1.0, .material = m, .temperature = 300});
  sim.initialize();
  const double a = std::sqrt(1 - 0.99 * 0.99);
  const double h_bob = 4 * 500 * a;
  CHECK(h_bob == grain::test::approx(282.1).epsilon(2e-4));
  const double h_layer = conduction::SurroundingLayer::wall(1.0, 0.99, a, 10.0, {});
  CHECK(h_layer == grain::test::approx(1081.58).epsilon(1e-5));
  const double hs = 2 * 10.0 / 2.0 * 4 * std::numbers::pi;
  sim.step();
  const auto& q = sim.particles();
  CHECK(q.heat_rate[0] == grain::test::approx((h_bob + h_layer) * 100 - hs * 50).epsilon(1e-12));
  sim.run(60.0); // 35 tau
  const double steady = ((h_bob + h_layer) * 400 + hs * 250) / (h_bob + h_layer + hs);
  CHECK(q.temperature[0] == grain::test::approx(steady).epsilon(1e-9));
}

TEST_CASE("a wall material without conductivity insulates for an indirect model too") {
  // the set-up of the resting_single case (verification 4.11) without convection: direct
  // (Batchelor-O'Brien) + surrounding-layer conduction from a wall at 400 K into a sphere at
  // 300 K. With the wall's material at k = 1000 W/(m K) the heat rate is (H_BOB + H_layer)
  // 100 K (1e-12); with a wall material of zero conductivity no heat crosses the wall (exactly 0),
  // although the surrounding layer itself does not involve the wall's conductivity.
  using Contact =
      Interaction<normal::Hertz<>, tangent::None, rolling::None,
                  conduction::Combined<conduction::BatchelorOBrien, conduction::SurroundingLayer>,
                  area::Geometric>;
  using Sim = Simulation<Sphere, search::AllPairs, Contact>;
  auto heat_rate = [](double wall_conductivity) {
    Sim::Params p;
    p.analysis = Analysis::thermal;
    p.fluid = {.temperature = 250,
               .density = 1.2,
               .viscosity = 1.8e-5,
               .conductivity = 10,
               .heat_capacity = 1000};
    p.time_step = 1e-3;
    Sim sim(p);
    const auto m = sim.add_material({.name = "resting_single",
                                     .density = 30,
                                     .young = 1e6,
                                     .conductivity = 1000,
                                     .heat_capacity = 20});
    const auto w = sim.add_material({.name = "wall",
                                     .density = 30,
                                     .young = 1e6,
                                     .conductivity = wall_conductivity,
                                     .heat_capacity = 20});
    sim.add_wall(walls::Plane{{0, 0, 0}, {0, 0, 1}}, {.material = w, .temperature = 400.0});
    sim.add_particle({.position = {0, 0, 0.99}, .radius = 1.0, .material = m, .temperature = 300});
    sim.step();
    return sim.particles().heat_rate[0];
  };
  const double a = std::sqrt(1 - 0.99 * 0.99);
  const double h_layer = conduction::SurroundingLayer::wall(1.0, 0.99, a, 10.0, {});
  CHECK(heat_rate(1000.0) == grain::test::approx((4 * 500 * a + h_layer) * 100).epsilon(1e-12));
  CHECK(heat_rate(0.0) == 0.0);
}

TEST_CASE("a density table that lowers the conduction limit below the time step stops the run") {
  // section 4.1's pair (C = 8.37758 J/K, H = 1.41421e-3 W/K: limit C / H = 5924 s) at dt = 3000 s;
  // the density falls to 250 kg/m^3 after t = 3001 s, so C and the limit fall tenfold (592 s).
  // Forward Euler would then multiply the temperature difference by 1 - 2 dt H / C = -9.1 per
  // step; the update that lowers the density raises InputError instead.
  auto sim = two_particles<Sim3>(3000.0);
  sim.add_variable_property({"all", Property::density, Variable::time,
                             Table({{0.0, 2500.0}, {3001.0, 2500.0}, {3002.0, 250.0}})});
  const auto e = grain::test::error_of([&] { sim.steps(4); });
  CHECK(grain::test::has(e, "above the conduction limit"));
  CHECK(grain::test::has(e, "density"));
  CHECK(sim.time() == 6000.0); // stopped at the update of t = 6000 s
}

TEST_CASE("indirect conduction in a simulation: gaps within the cutoff conduct, with the "
          "Voronoi cell radius of the chosen cell-size method") {
  // Surrounding layer across a 10 um gap between two R = 1 mm spheres (k_f = 0.026): H =
  // 2.98279e-4 W/K (verification 4.6); forward Euler relaxation exact to round-off.
  {
    using Contact =
        Interaction<normal::Hertz<>, tangent::None, rolling::None, conduction::SurroundingLayer>;
    using Sim = Simulation<Sphere, search::CellList, Contact>;
    static_assert(Contact::indirect);
    Sim::Params p;
    p.analysis = Analysis::thermal;
    p.fluid.conductivity = 0.026;
    p.time_step = 1.0;
    Sim sim(p);
    const auto m = sim.add_material(glass());
    sim.add_particle({.position = {0, 0, 0}, .radius = 1e-3, .material = m, .temperature = 300});
    sim.add_particle(
        {.position = {2e-3 + 1e-5, 0, 0}, .radius = 1e-3, .material = m, .temperature = 400});
    sim.initialize();
    const double C = 2500 * 4.0 / 3.0 * std::numbers::pi * 1e-9 * 800;
    const double H = 2.98279e-4;
    sim.steps(100);
    const double dT = temperature_of(sim, 1) - temperature_of(sim, 0);
    CHECK(dT == grain::test::approx(100 * std::pow(1 - 2 * H / C, 100.0)).epsilon(1e-5));
    CHECK(sim.conduction_time_step() == grain::test::approx(C / H).epsilon(5e-6));
  }
  // Voronoi B with the global porosity given (0.4): r_ij = 0.56 R (0.6)^(-1/3) = 0.6640 R; at a
  // Hertz contact radius a = 10 um (overlap 2 a^2 / R) H = 1.63679e-4 W/K (verification 4.7).
  {
    using Contact =
        Interaction<normal::Hertz<>, tangent::None, rolling::None, conduction::VoronoiB>;
    using Sim = Simulation<Sphere, search::CellList, Contact, cells::GlobalPorosity>;
    Sim::Params p;
    p.analysis = Analysis::thermal;
    p.fluid.conductivity = 0.026;
    p.cells.porosity = 0.4;
    p.time_step = 1.0;
    Sim sim(p);
    const auto m = sim.add_material(glass());
    const double a = 1e-5, delta = 2 * a * a / 1e-3;
    sim.add_particle({.position = {0, 0, 0}, .radius = 1e-3, .material = m, .temperature = 300});
    sim.add_particle(
        {.position = {2e-3 - delta, 0, 0}, .radius = 1e-3, .material = m, .temperature = 400});
    sim.initialize();
    double H = 0;
    sim.for_each_conductance([&](std::size_t, std::size_t, bool, double h) { H += h; });
    CHECK(H == grain::test::approx(1.63679e-4).epsilon(5e-6));
  }
}

TEST_CASE("a neighbour distance per particle: small particles drop the partners only large ones "
          "reach, with the same results") {
  // Spheres of 1 mm on a lattice of pitch 3.2 mm (gaps 1.2 mm) under a layer of 3 mm spheres
  // (gaps 1 mm, 0.8 mm to the small ones), moving at up to 0.5 m/s, with surrounding-layer
  // conduction (cutoff 0.4 x the larger radius). The search reaches skin + 1.2 mm for every pair
  // (skin 0.2 x 3 mm); per particle, a pair of small spheres is listed only within
  // skin + 0.4 mm, and no pair closer than its conduction cutoff is ever missing: positions and
  // temperatures are the same bits.
  using Contact =
      Interaction<normal::Hertz<>, tangent::None, rolling::None, conduction::SurroundingLayer>;
  using Sim = Simulation<Sphere, search::CellList, Contact>;
  auto run = [](bool per_particle) {
    Sim::Params p;
    p.fluid.conductivity = 0.026;
    p.time_step = 1e-6;
    p.neighbour_distance_per_particle = per_particle;
    Sim sim(p);
    const auto m = sim.add_material(glass(1e7));
    std::uint64_t seed = 12345;
    auto uniform = [&] { // in [-1, 1)
      seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
      return static_cast<double>(seed >> 11) * 0x1.0p-52 - 1.0;
    };
    auto add = [&](const Vec3& x, double r) {
      sim.add_particle({.position = x,
                        .radius = r,
                        .material = m,
                        .velocity = 0.5 * Vec3(uniform(), uniform(), uniform()),
                        .temperature = 350.0 + 50.0 * uniform()});
    };
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j)
        for (int k = 0; k < 4; ++k)
          add(Vec3(i, j, k) * 3.2e-3, 1e-3);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        add(Vec3(7e-3 * i, 7e-3 * j, 3 * 3.2e-3 + 4.8e-3), 3e-3);
    sim.steps(3000);
    std::vector<double> state;
    for (std::size_t i = 0; i < sim.size(); ++i) {
      state.push_back(sim.particles().temperature[i]);
      for (int d = 0; d < 3; ++d)
        state.push_back(sim.particles().position[i][d]);
    }
    return std::tuple{state, sim.neighbor_list().partners.size(), sim.counters().rebuilds};
  };
  const auto [on, listed_on, rebuilds_on] = run(true);
  const auto [off, listed_off, rebuilds_off] = run(false);
  CHECK(rebuilds_on == rebuilds_off);
  CHECK(rebuilds_on > 3);
  CHECK(on == off);
  CHECK(10 * listed_on < 6 * listed_off); // 184 against 340
  MESSAGE("pairs listed: " << listed_on << " per particle, " << listed_off << " for all");
}

TEST_CASE("a thermal analysis sees its contacts at rest: the collisional model gives the static "
          "conductance whatever velocities the particles were given") {
  using Contact =
      Interaction<normal::Hertz<>, tangent::None, rolling::None, conduction::Collisional>;
  using Sim = Simulation<Sphere, search::AllPairs, Contact>;
  Sim::Params p;
  p.analysis = Analysis::thermal;
  p.time_step = 1.0;
  Sim sim(p);
  const auto m = sim.add_material(glass());
  sim.add_particle({.position = {0, 0, 0},
                    .radius = 0.01,
                    .material = m,
                    .velocity = {1.0, 0, 0},
                    .temperature = 300});
  sim.add_particle({.position = {0.02 - 1e-4, 0, 0},
                    .radius = 0.01,
                    .material = m,
                    .velocity = {-1.0, 0, 0},
                    .temperature = 400});
  sim.initialize();
  double H = 0;
  sim.for_each_conductance([&](std::size_t, std::size_t, bool, double h) { H += h; });
  // Batchelor-O'Brien with the Hertz radius: 2 k a, a = sqrt(R* delta)
  CHECK(H == grain::test::approx(2.0 * std::sqrt(0.005 * 1e-4)).epsilon(1e-12));
}

TEST_CASE("a wall temperature given as a time function, and convection to a fluid at rest") {
  // A sphere touching a wall whose temperature is a table: 300 K until t = 100 s, then 400 K
  // (ramp over 10 s). The forward-Euler recursion T += dt H (T_w(t_n) - T)/C is replayed in the
  // test and must match to round-off (class A).
  {
    Sim3::Params p;
    p.analysis = Analysis::thermal;
    p.time_step = 5.0;
    Sim3 sim(p);
    const auto m = sim.add_material(glass());
    const TimeFunction tw = TimeFunction::table({{0.0, 300.0}, {100.0, 300.0}, {110.0, 400.0}});
    sim.add_wall(walls::Plane{{0, 0, 0}, {0, 0, 1}}, {.material = m, .temperature = tw});
    sim.add_particle(
        {.position = {0, 0, 0.01 - 1e-4}, .radius = 0.01, .material = m, .temperature = 300});
    sim.initialize();
    const double C = 2500 * 4.0 / 3.0 * std::numbers::pi * 1e-6 * 800;
    const double H = 4.0 * 0.5 * std::sqrt(0.01 * 1e-4);
    double T = 300.0;
    for (int n = 0; n < 200; ++n) {
      T += 5.0 * H * (tw(5.0 * n) - T) / C;
      sim.step();
    }
    CHECK(T > 315.0); // the wall has heated the sphere
    CHECK(temperature_of(sim, 0) == grain::test::approx(T).epsilon(1e-12));
    CHECK(sim.walls()[0].temperature == 400.0);
  }
  // Convection only (insulated wall, no contact): Nu = 2 at rest for both correlations, so
  // h S = (2 k_f / 2R) 4 pi R^2 and T relaxes to T_f with the forward-Euler recursion.
  auto relax = [](auto convection_model) {
    using M = decltype(convection_model);
    using Sim = Simulation<Sphere, search::AllPairs, Thermal, M>;
    typename Sim::Params p;
    p.analysis = Analysis::thermal;
    p.time_step = 10.0;
    p.fluid = {.temperature = 350,
               .density = 1.2,
               .viscosity = 1.8e-5,
               .conductivity = 0.026,
               .heat_capacity = 1000};
    Sim sim(p);
    const auto m = sim.add_material(glass());
    sim.add_particle({.position = {0, 0, 0}, .radius = 0.01, .material = m, .temperature = 300});
    sim.steps(50);
    const double C = 2500 * 4.0 / 3.0 * std::numbers::pi * 1e-6 * 800;
    const double hs = 2.0 * 0.026 / 0.02 * 4.0 * std::numbers::pi * 1e-4;
    CHECK(temperature_of(sim, 0) ==
          grain::test::approx(350.0 - 50.0 * std::pow(1.0 - 10.0 * hs / C, 50.0)).epsilon(1e-12));
  };
  relax(convection::RanzMarshall{});
  relax(convection::Whitaker{});
}
