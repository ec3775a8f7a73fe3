// Variable properties (tables of temperature, time or speed) and result statistics.
//
// Each case has a closed form:
// - conductivity k(T): the steady middle temperature of a three-particle chain between two held
//   temperatures solves k*(k(T1), k(Tm)) (T1 - Tm) = k*(k(Tm), k(T3)) (Tm - T3) (equal contact
//   radii; Batchelor-O'Brien H = 4 k* a, k* = k1 k2/(k1 + k2));
// - heat capacity c(T) = c0 + b T under a constant heat rate Q: m (c0 (T - T0) + b (T^2 - T0^2)/2)
//   = Q t;
// - Young's modulus E(t) switched before an elastic Hertz impact on a plane: the maximum overlap
//   (15 m v^2 / (16 E* sqrt(R)))^(2/5) of the new modulus, and the same motion as a material
//   with that modulus;
// - radius R(t) of a particle resting on a plane: mass rho 4/3 pi R^3, inertia 0.4 m R^2, and the
//   static Hertz overlap (3 m g / (4 E* sqrt(R)))^(2/3) of the grown particle;
// - friction mu(t) of a block sliding on a plane (rotation restrained): dv/dt = -mu(t) g.
// - friction of a wall that follows the wall's temperature, heated as a ramp: the block slides
//   with dv/dt = -g (mu_p + mu_w(T_w(t)))/2, integrated in closed form;
// - conductivity of a wall that follows its temperature: the heat rate of a resting particle is
//   that of a wall material with the table's value, 4 k* a (T_w - T), k* = k_p k_w/(k_p + k_w).
// - statistics of known velocities: counts, totals, means, extremes; free particles only.

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
using ThermalSim = Simulation<Sphere, search::CellList, Thermal>;
using HertzSim = Simulation<Sphere, search::CellList, Interaction<normal::Hertz<>, tangent::None>>;
using FrictionSim = Simulation<Sphere, search::CellList, presets::LinearCoulomb>;

constexpr double pi = std::numbers::pi;

/// Glass (grain::test::glass), elastic and without friction.
Material glass() {
  Material m = grain::test::glass();
  m.restitution = 1.0;
  m.friction = 0.0;
  return m;
}

} // namespace

TEST_CASE("variable property: a temperature-dependent conductivity sets the steady chain "
          "temperature") {
  // k(T) = 1 + 2 (T - 300)/100 W/(m K) between 300 and 400 K
  auto k = [](double T) { return 1.0 + 2.0 * (T - 300.0) / 100.0; };
  auto keff = [](double a, double b) { return a * b / (a + b); };
  const double T1 = 400.0, T3 = 300.0;
  // closed form: bisection on the heat balance of the middle particle
  double lo = T3, hi = T1;
  for (int it = 0; it < 200; ++it) {
    const double tm = 0.5 * (lo + hi);
    const double r = keff(k(T1), k(tm)) * (T1 - tm) - keff(k(tm), k(T3)) * (tm - T3);
    (r > 0 ? lo : hi) = tm;
  }
  const double expected = 0.5 * (lo + hi);
  REQUIRE(std::abs(expected - 350.0) > 5.0); // the variable conductivity matters

  ThermalSim::Params prm;
  prm.analysis = Analysis::thermal;
  ThermalSim sim(prm);
  const auto m = sim.add_material(glass());
  const double R = 0.01, pitch = 2 * R - 1e-4; // equal overlaps: equal contact radii
  const auto a =
      sim.add_particle({.position = {0, 0, 0}, .radius = R, .material = m, .temperature = T1});
  const auto b =
      sim.add_particle({.position = {pitch, 0, 0}, .radius = R, .material = m, .temperature = 320});
  const auto c = sim.add_particle(
      {.position = {2 * pitch, 0, 0}, .radius = R, .material = m, .temperature = T3});
  sim.add_group("hot", {a});
  sim.add_group("cold", {c});
  sim.fix_temperature("hot", T1);
  sim.fix_temperature("cold", T3);
  sim.add_variable_property(
      {"all", Property::conductivity, Variable::temperature, Table({{300.0, 1.0}, {400.0, 3.0}})});
  sim.initialize();
  // the slowest time constant C / (2 H) is some 1e3 dt: run 40 of them
  const double H = 4.0 * keff(1.0, 1.0) * std::sqrt(0.5 * R * 1e-4);
  const double C = glass().density * 4.0 / 3.0 * pi * R * R * R * glass().heat_capacity;
  sim.run(40.0 * C / (2.0 * H));
  const double tm = sim.particles().temperature[sim.index_of(b)];
  // forward Euler's steady state is the exact one; 1e-9 K covers the residual transient
  CHECK(tm == approx(expected).epsilon(1e-9));
  CHECK(sim.particles().temperature[sim.index_of(a)] == T1);
}

TEST_CASE("variable property: a temperature-dependent heat capacity under a constant heat rate") {
  ThermalSim::Params prm;
  prm.analysis = Analysis::thermal;
  prm.time_step = 0.01;
  ThermalSim sim(prm);
  const auto m = sim.add_material(glass());
  const double R = 0.005, T0 = 300.0, Q = 2.0;
  sim.add_particle({.position = {0, 0, 0}, .radius = R, .material = m, .temperature = T0});
  // c(T) = 800 + 2 (T - 300) J/(kg K)
  sim.add_variable_property({"all", Property::heat_capacity, Variable::temperature,
                             Table({{300.0, 800.0}, {800.0, 1800.0}})});
  sim.prescribe_heat_rate("all", Q);
  const double t = 200.0;
  sim.run(t);
  const double mass = glass().density * 4.0 / 3.0 * pi * R * R * R;
  // m (800 (T - T0) + (T - T0)^2) = Q t
  const double u = Q * t / mass;
  const double expected = T0 + (-800.0 + std::sqrt(800.0 * 800.0 + 4.0 * u)) / 2.0;
  REQUIRE(expected - T0 > 50.0);
  // forward Euler with the capacity lagging one step: first order, dt Q/(m c) ~ 1e-2 K per step
  CHECK(sim.particles().temperature[0] == approx(expected).epsilon(1e-4));
  CHECK(sim.particles().heat_capacity[0] ==
        approx(mass * (800.0 + 2.0 * (sim.particles().temperature[0] - 300.0))).epsilon(1e-4));
}

TEST_CASE("variable property: Young's modulus switched in time gives the new Hertz impact") {
  const double E0 = 1e7, E1 = 4e7, R = 0.01, v = 0.5, gap = 0.002;
  auto run = [&](bool variable, double& dmax) {
    HertzSim::Params prm;
    prm.time_step = 2e-6;
    HertzSim sim(prm);
    Material mp = glass();
    mp.young = variable ? E0 : E1;
    const auto m = sim.add_material(mp);
    Material mw = glass();
    mw.young = 1e6 * E1;
    const auto w = sim.add_material(mw);
    sim.add_wall(walls::Plane{{0, 0, 0}, {0, 0, 1}}, {.material = w});
    sim.add_particle(
        {.position = {0, 0, R + gap}, .radius = R, .material = m, .velocity = {0, 0, -v}});
    if (variable) // E0 until t = 1 ms, then E1 (impact at gap / v = 4 ms)
      sim.add_variable_property(
          {"all", Property::young, Variable::time, Table({{0.0, E0}, {1e-3, E0}, {1.001e-3, E1}})});
    dmax = 0.0;
    for (int k = 0; k < 8000; ++k) {
      sim.step();
      dmax = std::max(dmax, R - sim.particles().position[0].z());
    }
    return sim.particles().velocity[0].z();
  };
  double d_var = 0, d_ref = 0;
  const double v_var = run(true, d_var), v_ref = run(false, d_ref);
  const double nu = glass().poisson;
  const double Es = 1.0 / ((1 - nu * nu) / E1 + (1 - nu * nu) / (1e6 * E1));
  const double mass = glass().density * 4.0 / 3.0 * pi * R * R * R;
  const double expected = std::pow(15.0 * mass * v * v / (16.0 * Es * std::sqrt(R)), 0.4);
  // sampled peak at dt = t_c / ~100: within 1e-3
  CHECK(d_var == approx(expected).epsilon(1e-3));
  // the same motion as a particle made of the new material (per-contact mixing = material mixing)
  CHECK(d_var == approx(d_ref).epsilon(1e-12));
  CHECK(v_var == approx(v_ref).epsilon(1e-12));
  CHECK(v_var == approx(v).epsilon(1e-3)); // elastic rebound
}

TEST_CASE("variable property: a growing particle on a plane takes the new mass and overlap") {
  HertzSim::Params prm;
  prm.time_step = 1e-6;
  prm.gravity = Vec3(0, 0, -9.81);
  prm.damping_translational = 0.05; // settles within the run
  HertzSim sim(prm);
  Material mp = glass();
  mp.young = 1e7;
  mp.restitution = 0.3; // damped: at rest long before the end
  const auto m = sim.add_material(mp);
  const auto w = sim.add_material(mp);
  sim.add_wall(walls::Plane{{0, 0, 0}, {0, 0, 1}}, {.material = w});
  const double R0 = 0.004, R1 = 0.005;
  sim.add_particle({.position = {0, 0, R0}, .radius = R0, .material = m});
  sim.add_variable_property(
      {"all", Property::radius, Variable::time, Table({{0.0, R0}, {0.05, R1}}), 10});
  sim.run(0.3);
  const auto& p = sim.particles();
  const double mass = mp.density * 4.0 / 3.0 * pi * R1 * R1 * R1;
  CHECK(p.radius[0] == R1);
  CHECK(p.mass[0] == approx(mass).epsilon(1e-12));
  CHECK(p.inertia[0] == approx(0.4 * mass * R1 * R1).epsilon(1e-12));
  const double Es = 1.0 / (2.0 * (1 - mp.poisson * mp.poisson) / mp.young);
  const double delta = std::pow(3.0 * mass * 9.81 / (4.0 * Es * std::sqrt(R1)), 2.0 / 3.0);
  // at rest: the overlap of the static Hertz balance within 1e-3 (residual oscillation)
  CHECK(R1 - p.position[0].z() == approx(delta).epsilon(1e-3));
}

TEST_CASE("variable property: friction changing in time decelerates a sliding block as mu(t) g") {
  FrictionSim::Params prm;
  prm.time_step = 2e-6;
  prm.gravity = Vec3(0, 0, -9.81);
  FrictionSim sim(prm);
  Material mp = glass();
  mp.young = 1e7;
  mp.restitution = 0.3;
  mp.friction = 0.2;
  const auto m = sim.add_material(mp);
  sim.add_wall(walls::Plane{{0, 0, 0}, {0, 0, 1}}, {.material = m});
  const double R = 0.005, g = 9.81;
  const double delta =
      std::pow(3.0 * mp.density * 4.0 / 3.0 * pi * R * R * R * g /
                   (4.0 * mp.young / (2.0 * (1 - mp.poisson * mp.poisson)) * std::sqrt(R)),
               2.0 / 3.0);
  sim.add_particle(
      {.position = {0, 0, R - delta}, .radius = R, .material = m, .velocity = {1.0, 0, 0}});
  sim.restrain("all", {}, {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)}); // a block: no rolling
  // mu = 0.2 until 0.1 s, then 0.4 (both the particle's and the wall's: the pair mean)
  sim.add_variable_property(
      {"all", Property::friction, Variable::time, Table({{0.0, 0.2}, {0.1, 0.2}, {0.1001, 0.4}})});
  sim.run(0.1);
  const double v1 = sim.particles().velocity[0].x();
  sim.run(0.1);
  const double v2 = sim.particles().velocity[0].x();
  // mean friction of the pair: (0.2 + 0.2)/2, then (0.4 + 0.2)/2 (the wall keeps its material)
  CHECK(1.0 - v1 == approx(0.2 * g * 0.1).epsilon(2e-2));
  CHECK(v1 - v2 == approx(0.3 * g * 0.1).epsilon(2e-2));
  CHECK(std::abs(sim.particles().omega[0].norm()) <= 1e-12);
}

TEST_CASE("variable property of a wall: friction follows the wall's temperature") {
  using Sim = Simulation<Sphere, search::CellList,
                         Interaction<normal::LinearSpringDashpot, tangent::SpringDashpotSlider,
                                     rolling::None, conduction::BatchelorOBrien>>;
  Sim::Params prm;
  prm.time_step = 2e-6;
  prm.gravity = Vec3(0, 0, -9.81);
  Sim sim(prm);
  Material mp = glass();
  mp.young = 1e7;
  mp.restitution = 0.3;
  mp.friction = 0.2;
  const auto m = sim.add_material(mp);
  // the wall heats from 300 K at 2000 K/s; its friction goes from 0.2 at 300 K to 0.6 at 700 K
  const auto floor = sim.add_wall(
      walls::Plane{{0, 0, 0}, {0, 0, 1}},
      {.material = m, .temperature = TimeFunction::table({{0.0, 300.0}, {1.0, 2300.0}})});
  sim.add_wall_variable_property(floor, {"all", Property::friction, Variable::temperature,
                                         Table({{300.0, 0.2}, {700.0, 0.6}})});
  const double R = 0.005, g = 9.81;
  const double delta =
      std::pow(3.0 * mp.density * 4.0 / 3.0 * pi * R * R * R * g /
                   (4.0 * mp.young / (2.0 * (1 - mp.poisson * mp.poisson)) * std::sqrt(R)),
               2.0 / 3.0);
  sim.add_particle({.position = {0, 0, R - delta},
                    .radius = R,
                    .material = m,
                    .velocity = {1.0, 0, 0},
                    .temperature = 300.0});
  sim.restrain("all", {}, {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)}); // a block: no rolling
  // pair friction (0.2 + 0.2 + 0.001 (2000 t))/2 = 0.2 + t: v = 1 - g (0.2 t + t^2/2)
  for (const double t : {0.1, 0.2}) {
    sim.run(t - sim.time());
    CHECK(1.0 - sim.particles().velocity[0].x() ==
          approx(g * (0.2 * t + 0.5 * t * t)).epsilon(5e-3));
  }
  CHECK(sim.wall_material(floor).friction == approx(0.6).epsilon(1e-3));
  CHECK(sim.material_of(0).friction == 0.2); // the particle keeps its own
}

TEST_CASE("variable property of a wall: conductivity follows the wall's temperature") {
  // a particle at 300 K resting on a wall whose temperature rises from 300 K to 500 K in 1 s,
  // conductivity k_w(T) = 1 + 4 (T - 300)/200 W/(m K); the particle keeps k_p = 1
  auto heat_rate = [](bool variable, double t_end) {
    ThermalSim::Params prm;
    prm.analysis = Analysis::thermal;
    prm.time_step = 1e-3;
    ThermalSim sim(prm);
    const auto m = sim.add_material(glass());
    Material wall = glass();
    // the constant material has the table's value at the wall temperature of t_end
    if (!variable) wall.conductivity = 1.0 + 4.0 * (200.0 * t_end) / 200.0;
    const auto mw = sim.add_material(wall);
    const auto w = sim.add_wall(
        walls::Plane{{0, 0, 0}, {0, 0, 1}},
        {.material = mw, .temperature = TimeFunction::table({{0.0, 300.0}, {1.0, 500.0}})});
    if (variable)
      sim.add_wall_variable_property(std::vector<std::size_t>{w},
                                     {"all", Property::conductivity, Variable::temperature,
                                      Table({{300.0, 1.0}, {500.0, 5.0}})});
    const auto id = sim.add_particle(
        {.position = {0, 0, 0.01 - 1e-4}, .radius = 0.01, .material = m, .temperature = 300.0});
    sim.add_group("held", {id});
    sim.fix_temperature("held", 300.0);
    sim.run(t_end);
    double q = 0.0;
    sim.for_each_contact(
        [&](std::size_t, std::size_t, bool, const auto&, const auto&, double rate) { q += rate; });
    return q;
  };
  for (const double t : {0.25, 0.5}) {
    const double kw = 1.0 + 4.0 * (200.0 * t) / 200.0, keff = kw / (1.0 + kw);
    const double a = std::sqrt(0.01 * 1e-4); // contact radius of the overlap with a plane
    const double q = heat_rate(true, t);
    CHECK(q == approx(heat_rate(false, t)).epsilon(1e-12));
    CHECK(q == approx(4.0 * keff * a * 200.0 * t).epsilon(1e-9));
  }
}

TEST_CASE("variable property of a wall: bad properties, walls and variables are named") {
  ThermalSim sim;
  const auto m = sim.add_material(glass());
  const auto cold = sim.add_wall(walls::Plane{{0, 0, 0}, {0, 0, 1}}, {.material = m});
  const VariableProperty grow{"all", Property::radius, Variable::time,
                              Table({{0.0, 0.01}, {1.0, 0.02}})};
  CHECK_THROWS_WITH_AS(sim.add_wall_variable_property(cold, grow),
                       doctest::Contains("property = radius is invalid for a wall"), InputError);
  const VariableProperty stiff{"all", Property::young, Variable::temperature,
                               Table({{300.0, 1e7}, {400.0, 2e7}})};
  CHECK_THROWS_WITH_AS(sim.add_wall_variable_property(cold, stiff),
                       doctest::Contains("variable = temperature is invalid for wall 0"),
                       InputError);
  CHECK_THROWS_WITH_AS(sim.add_wall_variable_property(3, stiff),
                       doctest::Contains("wall = 3 is invalid; valid range: [0, 1)"), InputError);
}

TEST_CASE("variable property: bad tables and variables are named") {
  ThermalSim sim;
  sim.add_material(glass());
  CHECK_THROWS_WITH_AS(sim.add_variable_property({"all", Property::radius, Variable::time,
                                                  Table({{0.0, 0.01}, {1.0, -0.01}}, "growth")}),
                       doctest::Contains("Table 'growth' y[1] = -0.01 is invalid for radius"),
                       InputError);
  CHECK_THROWS_WITH_AS(sim.add_variable_property({"all", Property::young, Variable::time,
                                                  Table({{0.0, 1e7}, {1.0, 2e7}}), 0}),
                       doctest::Contains("every = 0"), InputError);
  CHECK_THROWS_WITH_AS(sim.add_variable_property({"nowhere", Property::young, Variable::time,
                                                  Table({{0.0, 1e7}, {1.0, 2e7}})}),
                       doctest::Contains("group = 'nowhere'"), InputError);
  HertzSim mech;
  mech.add_material(glass());
  CHECK_THROWS_WITH_AS(mech.add_variable_property({"all", Property::young, Variable::temperature,
                                                   Table({{0.0, 1e7}, {1.0, 2e7}})}),
                       doctest::Contains("variable = temperature is invalid"), InputError);
}

TEST_CASE("variable property: the time step is checked against the stiffest table value") {
  HertzSim::Params prm;
  HertzSim probe;
  const auto pm = probe.add_material(glass());
  (void)pm;
  probe.add_particle({.position = {0, 0, 0}, .radius = 0.01});
  probe.initialize();
  const double critical_soft = probe.critical_time_step();
  prm.time_step = 0.9 * critical_soft; // stable for the material's modulus
  HertzSim sim(prm);
  sim.add_material(glass());
  sim.add_particle({.position = {0, 0, 0}, .radius = 0.01});
  sim.add_variable_property(
      {"all", Property::young, Variable::time, Table({{0.0, 7e10}, {1.0, 7e12}})});
  CHECK_THROWS_WITH_AS(sim.initialize(), doctest::Contains("above the stable limit"), InputError);
}

TEST_CASE("statistics: counts, totals, means and extremes of known velocities") {
  HertzSim::Params prm;
  prm.time_step = 1e-6;
  HertzSim sim(prm);
  const auto m = sim.add_material(glass());
  const std::vector<double> vx = {0.1, -0.4, 0.25, 0.05};
  std::vector<std::int64_t> ids;
  for (std::size_t k = 0; k < vx.size(); ++k)
    ids.push_back(sim.add_particle({.position = {0.1 * double(k), 0, 0},
                                    .radius = 0.01,
                                    .material = m,
                                    .velocity = {vx[k], 0, 0}}));
  sim.add_particle(
      {.position = {1, 0, 0}, .radius = 0.01, .material = m, .creation_time = 1.0}); // inactive
  sim.add_group("pushed", {ids[1], ids[2]});
  sim.fix_velocity("pushed", Vec3(0.3, 0, 0));
  sim.initialize();
  auto s = io::statistics(sim);
  CHECK(s.particles == 4);
  CHECK(s.free_particles == 2);
  CHECK(s.inactive == 1);
  CHECK(s.removed == 0);
  CHECK(s.speed.count == 4);
  CHECK(s.speed.total == approx(0.1 + 0.4 + 0.25 + 0.05).epsilon(1e-15));
  CHECK(s.speed.mean == approx(0.8 / 4).epsilon(1e-15));
  CHECK(s.velocity[0].min == -0.4);
  CHECK(s.velocity[0].max == 0.25);
  CHECK(s.mass.total == approx(4 * glass().density * 4.0 / 3.0 * pi * 1e-6).epsilon(1e-14));
  const auto f = io::statistics(sim, "all", true); // the two unprescribed ones
  CHECK(f.particles == 2);
  CHECK(f.velocity[0].total == approx(0.1 + 0.05).epsilon(1e-15));
  const auto g = io::statistics(sim, "pushed");
  CHECK(g.particles == 2);
  CHECK(g.free_particles == 0);
  // after a step the pushed ones move at the fixed velocity
  sim.step();
  s = io::statistics(sim, "pushed");
  CHECK(s.velocity[0].min == approx(0.3).epsilon(1e-15));
  CHECK(s.velocity[0].max == approx(0.3).epsilon(1e-15));
  CHECK(std::isnan(io::statistics(sim).temperature.mean)); // a mechanical simulation
}

// The neighbour search is sized by the largest radius present, also when a radius table (here
// of a small particle's group) holds only smaller values: two large spheres (R = 2 mm) that
// overlap by 0.1 mm at the start push each other with the static Hertz force
// F = 4/3 E* sqrt(R/2) delta^3/2 (e = 1: no damping; tolerance 1e-12), and the small one
// (0.2 mm, its radius held by the table) has none.
TEST_CASE("variable property: a radius table of small particles does not hide large ones") {
  HertzSim sim;
  const Material mp = glass();
  const auto m = sim.add_material(mp);
  const double R = 2e-3, delta = 1e-4, r = 2e-4;
  sim.add_particle({.position = {0, 0, 0}, .radius = R, .material = m});
  sim.add_particle({.position = {2 * R - delta, 0, 0}, .radius = R, .material = m});
  const auto s = sim.add_particle({.position = {0.012, 0, 0}, .radius = r, .material = m});
  sim.add_group("small", {s});
  sim.add_variable_property(
      {"small", Property::radius, Variable::time, Table({{0.0, r}, {1.0, r}})});
  sim.initialize();
  const double Es = mp.young / (2.0 * (1 - mp.poisson * mp.poisson));
  const double F = 4.0 / 3.0 * Es * std::sqrt(0.5 * R) * std::pow(delta, 1.5);
  const auto& p = sim.particles();
  CHECK(-p.force[sim.index_of(0)].x() == approx(F).epsilon(1e-12));
  CHECK(p.force[sim.index_of(1)].x() == approx(F).epsilon(1e-12));
  CHECK(p.force[sim.index_of(s)].norm() == 0.0);
}

TEST_CASE("variable property: a particle activated later takes its properties at activation") {
  // density 5000 kg/m^3 by a table of time, updated every 1000 steps; the second particle joins
  // at t = 1.5 ms (step 1500), between two updates. Its mass is that of the table's density from
  // its first step on (exactly: rho 4/3 pi R^3, the same arithmetic as the update).
  HertzSim::Params prm;
  prm.time_step = 1e-6;
  HertzSim sim(prm);
  const auto m = sim.add_material(glass());
  const double R = 0.004, rho = 5000.0;
  sim.add_particle({.position = {0, 0, 0}, .radius = R, .material = m});
  const auto late = sim.add_particle(
      {.position = {0.1, 0, 0}, .radius = R, .material = m, .creation_time = 1.5e-3});
  sim.add_variable_property(
      {"all", Property::density, Variable::time, Table({{0.0, rho}, {1.0, rho}}), 1000});
  sim.run(1.8e-3); // ends between the updates of steps 1000 and 2000
  REQUIRE(sim.is_active(late));
  const double mass = rho * (4.0 / 3.0 * pi * R * R * R);
  CHECK(sim.particles().mass[sim.index_of(late)] == approx(mass).epsilon(1e-14));
  CHECK(sim.particles().mass[sim.index_of(0)] == approx(mass).epsilon(1e-14));
}
