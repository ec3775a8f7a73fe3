// Dissipated energy (SimulationParams::track_dissipation): the energy the contacts and the
// global damping take from the bodies, checked against energy balances with closed forms.
//
// - A damped normal impact of a sphere on a plane, no gravity, no friction: the dissipated
//   energy is the kinetic energy lost, m (v_in^2 - v_out^2)/2, and v_out = e v_in.
// - A head-on impact of two unequal spheres: m* (v_in^2 - v_out^2)/2 of the relative motion.
// - A free sphere under global damping c: m (v0^2 - v^2)/2 with v = v0 exp(-c t / m).
// - A sphere thrown sliding on a plane with friction: once it rolls (v = 5/7 v0) friction has
//   taken 2/7 of the kinetic energy m v0^2 / 2.
// - A settling packing under gravity with Hertz-Mindlin contacts and rolling resistance: the
//   total kinetic + potential + elastic + dissipated energy stays that of the start.

#include "../approx.hpp"
#include <doctest/doctest.h>
#include <grain/grain.hpp>

#include <cmath>
#include <numbers>

using namespace grain;
using grain::test::approx;

namespace {

constexpr double pi = std::numbers::pi;

Material soft() {
  return {.name = "soft",
          .density = 2500,
          .young = 1e7,
          .poisson = 0.25,
          .restitution = 0.5,
          .friction = 0.0};
}

template <class Sim>
typename Sim::Params tracked(double dt, Vec3 gravity = Vec3::Zero()) {
  typename Sim::Params p;
  p.time_step = dt;
  p.gravity = gravity;
  p.track_dissipation = true;
  return p;
}

} // namespace

TEST_CASE("dissipation: a damped impact on a plane dissipates the kinetic energy it loses") {
  using Sim = Simulation<Sphere, search::CellList, presets::LinearCoulomb>;
  Sim sim(tracked<Sim>(1e-6));
  const auto m = sim.add_material(soft());
  sim.add_wall(walls::Plane{{0, 0, 0}, {0, 0, 1}}, {.material = m});
  const double R = 0.01, v = 1.0;
  sim.add_particle(
      {.position = {0, 0, R + 1e-4}, .radius = R, .material = m, .velocity = {0, 0, -v}});
  CHECK(std::isnan(Sim().dissipated_energy())); // not tracked unless asked
  sim.run(0.01);
  const double mass = 2500 * 4.0 / 3.0 * pi * R * R * R;
  const double vout = sim.particles().velocity[0].z();
  REQUIRE(sim.contact_counts().second == 0);    // the impact is over
  CHECK(vout == approx(0.5 * v).epsilon(2e-3)); // restitution 0.5 (linear spring-dashpot)
  // the work sum of a contact that starts and ends at zero force is second order
  CHECK(sim.dissipated_energy() == approx(0.5 * mass * (v * v - vout * vout)).epsilon(1e-4));
}

TEST_CASE("dissipation: a head-on impact of unequal spheres") {
  using Sim = Simulation<Sphere, search::CellList, Interaction<normal::Hertz<>>>;
  Sim sim(tracked<Sim>(5e-7));
  const auto m = sim.add_material(soft());
  const double R1 = 0.01, R2 = 0.006, v1 = 0.6, v2 = -0.4;
  sim.add_particle({.position = {0, 0, 0}, .radius = R1, .material = m, .velocity = {v1, 0, 0}});
  sim.add_particle(
      {.position = {R1 + R2 + 1e-4, 0, 0}, .radius = R2, .material = m, .velocity = {v2, 0, 0}});
  sim.run(0.005);
  REQUIRE(sim.contact_counts().first == 0);
  const double m1 = 2500 * 4.0 / 3.0 * pi * R1 * R1 * R1, m2 = 2500 * 4.0 / 3.0 * pi * R2 * R2 * R2;
  const double ms = m1 * m2 / (m1 + m2);
  const auto& p = sim.particles();
  const double u = p.velocity[sim.index_of(1)].x() - p.velocity[sim.index_of(0)].x();
  const double lost = 0.5 * ms * ((v1 - v2) * (v1 - v2) - u * u);
  REQUIRE(lost > 0.5 * 0.5 * ms * (v1 - v2) * (v1 - v2)); // most of it: restitution 0.5
  CHECK(sim.dissipated_energy() == approx(lost).epsilon(1e-4));
  // momentum is untouched, so the loss is all of the kinetic energy lost
  const double ke0 = 0.5 * m1 * v1 * v1 + 0.5 * m2 * v2 * v2;
  CHECK(sim.dissipated_energy() == approx(ke0 - sim.kinetic_energy()).epsilon(1e-4));
}

TEST_CASE("dissipation: global damping takes the kinetic energy of a free sphere") {
  using Sim = Simulation<Sphere, search::CellList, presets::LinearCoulomb>;
  auto prm = tracked<Sim>(1e-4);
  prm.damping_translational = 2e-3; // N s/m
  Sim sim(prm);
  const auto m = sim.add_material(soft());
  const double R = 0.01, v0 = 1.0;
  sim.add_particle({.position = {0, 0, 0}, .radius = R, .material = m, .velocity = {v0, 0, 0}});
  sim.run(1.0);
  const double mass = 2500 * 4.0 / 3.0 * pi * R * R * R;
  const double v = v0 * std::exp(-2e-3 * 1.0 / mass);
  // velocity Verlet with a velocity-dependent force: second order, (c dt/m)^2 ~ 1e-5
  CHECK(sim.dissipated_energy() == approx(0.5 * mass * (v0 * v0 - v * v)).epsilon(1e-4));
}

TEST_CASE("dissipation: friction takes 2/7 of the energy of a sphere that starts to roll") {
  using Sim = Simulation<Sphere, search::CellList, presets::LinearCoulomb>;
  const double g = 9.81;
  auto prm = tracked<Sim>(2e-6, Vec3(0, 0, -g));
  prm.max_start_overlap = 0.1; // the pile starts 0.06 R into a wall
  Sim sim(prm);
  Material mat = soft();
  mat.friction = 0.3;
  mat.restitution = 0.2;
  const auto m = sim.add_material(mat);
  sim.add_wall(walls::Plane{{0, 0, 0}, {0, 0, 1}}, {.material = m});
  const double R = 0.005, v0 = 0.5;
  sim.add_particle({.position = {0, 0, R}, .radius = R, .material = m});
  sim.run(0.05); // settle on the plane
  const double settle = sim.dissipated_energy();
  sim.particles().velocity[0] = Vec3(v0, 0, 0);
  const double mass = sim.particles().mass[0];
  sim.run(v0 / (3.5 * 0.3 * g) + 0.1); // rolling after 2 v0 / (7 mu g)
  const auto& p = sim.particles();
  CHECK(p.velocity[0].x() == approx(5.0 / 7.0 * v0).epsilon(5e-3));
  // the tangential spring stores and returns a little: 1 %
  CHECK(sim.dissipated_energy() - settle == approx(2.0 / 7.0 * 0.5 * mass * v0 * v0).epsilon(1e-2));
}

TEST_CASE("dissipation: a settling packing conserves kinetic + potential + elastic + dissipated "
          "energy") {
  using Sim = Simulation<Sphere, search::CellList, presets::HertzMindlinRolling>;
  const double g = 9.81;
  auto prm = tracked<Sim>(2e-6, Vec3(0, 0, -g));
  prm.max_start_overlap = 0.1; // the pile starts 0.06 R into a wall
  Sim sim(prm);
  Material mat = soft();
  mat.friction = 0.5;
  mat.rolling_friction = 0.05;
  const auto m = sim.add_material(mat);
  sim.add_wall(walls::Plane{{0, 0, 0}, {0, 0, 1}}, {.material = m});
  sim.add_wall(walls::Plane{{0, 0, 0}, {1, 0, 0}}, {.material = m});
  sim.add_wall(walls::Plane{{0.05, 0, 0}, {-1, 0, 0}}, {.material = m});
  sim.add_wall(walls::Plane{{0, 0, 0}, {0, 1, 0}}, {.material = m});
  sim.add_wall(walls::Plane{{0, 0.05, 0}, {0, -1, 0}}, {.material = m});
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k)
        sim.add_particle(
            {.position = {0.006 + 0.0121 * i + 0.001 * k, 0.006 + 0.0121 * j, 0.006 + 0.0121 * k},
             .radius = 0.005,
             .material = m,
             .velocity = {0.1 * (j - 1.5), 0.05 * (i - 1.5), 0}});
  sim.initialize();
  const double e0 = sim.kinetic_energy() + sim.potential_energy() + sim.elastic_energy();
  double worst = 0.0;
  for (int k = 0; k < 10; ++k) {
    sim.run(0.02);
    const double e = sim.kinetic_energy() + sim.potential_energy() + sim.elastic_energy() +
                     sim.dissipated_energy();
    worst = std::max(worst, std::abs(e - e0));
  }
  const double drop = sim.dissipated_energy();
  REQUIRE(drop > 0.2 * std::abs(e0)); // much of the energy was dissipated
  MESSAGE("energy balance: worst |E - E0| = " << worst << " J of " << drop << " J dissipated");
  CHECK(worst <= 2e-4 * drop); // second-order work sums: measured 1.6e-5
}
