// Input checks of conditions, the lifecycle and variable properties: the message names the
// object, the value and the valid range, and a run never continues with an invalid value.

#include "../support/materials.hpp"
#include <doctest/doctest.h>
#include <grain/grain.hpp>
#include <grain/models/conduction/batchelor_obrien.hpp>

#include <cmath>

using namespace grain;

namespace {

using Thermal =
    Interaction<normal::Hertz<>, tangent::None, rolling::None, conduction::BatchelorOBrien>;
using ThermalSim = Simulation<Sphere, search::CellList, Thermal>;
using MechSim = Simulation<Sphere, search::CellList, presets::HertzMindlin>;

/// Glass with E = 1e7 Pa.
Material glass() { return grain::test::glass(1e7); }

} // namespace

TEST_CASE("input checks: negative damping and negative fixed temperatures are rejected") {
  MechSim sim;
  sim.add_material(glass());
  sim.add_particle({.position = {0, 0, 0}, .radius = 0.01});
  CHECK_THROWS_WITH_AS(sim.set_damping(-1.0), doctest::Contains("translational = -1"), InputError);
  CHECK_THROWS_WITH_AS(sim.set_damping(0.0, TimeFunction::table({{0.0, 1.0}, {1.0, -2.0}})),
                       doctest::Contains("rotational = -2"), InputError);
  CHECK_THROWS_WITH_AS(sim.set_mass_damping(Vec3(0, -5, 0)),
                       doctest::Contains("linear component = -5"), InputError);
  // a ramp that turns negative during the run stops it at that time
  MechSim::Params prm;
  prm.time_step = 1e-4;
  MechSim ramp(prm);
  ramp.add_material(glass());
  ramp.add_particle({.position = {0, 0, 0}, .radius = 0.01});
  ramp.set_damping(TimeFunction::linear(1e-3, -1e-2));
  CHECK_NOTHROW(ramp.run(0.05));
  CHECK_THROWS_WITH_AS(ramp.run(0.1), doctest::Contains("set_damping: damping = "), InputError);

  ThermalSim th;
  th.add_material(glass());
  th.add_particle({.position = {0, 0, 0}, .radius = 0.01});
  CHECK_THROWS_WITH_AS(th.fix_temperature("all", -5.0), doctest::Contains("temperature = -5"),
                       InputError);
}

TEST_CASE("input checks: ids are never reused, destruction times lie ahead") {
  MechSim::Params prm;
  prm.time_step = 1e-4;
  MechSim sim(prm);
  sim.add_material(glass());
  sim.add_particle({.position = {0, 0, 0}, .radius = 0.01, .id = 7});
  sim.add_particle({.position = {1, 0, 0}, .radius = 0.01, .destruction_time = 0.01, .id = 8});
  sim.run(0.02);
  REQUIRE(sim.removed_ids().size() == 1);
  CHECK_THROWS_WITH_AS(sim.add_particle({.position = {2, 0, 0}, .radius = 0.01, .id = 8}),
                       doctest::Contains("id = 8 is invalid"), InputError);
  CHECK_THROWS_WITH_AS(sim.add_particle({.position = {2, 0, 0}, .radius = 0.01, .id = 7}),
                       doctest::Contains("id = 7 is invalid"), InputError);
  CHECK_THROWS_WITH_AS(
      sim.add_particle({.position = {2, 0, 0}, .radius = 0.01, .destruction_time = 0.015}),
      doctest::Contains("destruction_time = 0.015 is invalid; valid range: (current time"),
      InputError);
}

TEST_CASE("input checks: a variable conductivity bounds the time step and cannot destabilise "
          "the run") {
  // two touching spheres in a thermal analysis; the conductivity rises a thousandfold in time
  auto make = [](double dt) {
    ThermalSim::Params prm;
    prm.analysis = Analysis::thermal;
    prm.time_step = dt;
    ThermalSim sim(prm);
    sim.add_material(glass());
    sim.add_particle({.position = {0, 0, 0}, .radius = 0.01, .temperature = 400});
    sim.add_particle({.position = {0.0199, 0, 0}, .radius = 0.01, .temperature = 300});
    sim.add_variable_property(
        {"all", Property::conductivity, Variable::time, Table({{0.0, 1.0}, {10.0, 1000.0}})});
    return sim;
  };
  // the automatic step follows the largest table value: R^2 rho c / k_max
  ThermalSim automatic = make(0.0);
  automatic.initialize();
  const double tau = 0.01 * 0.01 * 2500 * 800 / 1000.0;
  CHECK(automatic.thermal_time_step() == doctest::Approx(tau).epsilon(1e-12));
  CHECK(automatic.time_step() <= 0.1 * tau * (1 + 1e-12));
  // relaxation time C / (2 H) = 2.96 s once k = 1000 W/(m K): at rest at the mean after 100 s
  automatic.run(100.0);
  CHECK(automatic.particles().temperature[0] == doctest::Approx(350.0).epsilon(1e-9));
  // a given step that the rising conductivity makes unstable stops the run with the reason
  ThermalSim given = make(20.0);
  CHECK_THROWS_WITH_AS(given.run(200.0), doctest::Contains("above the conduction limit"),
                       InputError);
  for (double T : given.particles().temperature)
    CHECK(std::isfinite(T));
}

namespace {

/// A load gone wrong: from `at` seconds on, the particle with id `id` receives a NaN force
/// (as a user stage or a broken table would give it), or a NaN heat flow if `heat`.
struct NanLoad {
  std::int64_t id = 0;
  double at = 0.0;
  bool heat = false;
  template <class Sim>
  void after_forces(Sim& sim) {
    if (sim.time() < at) return;
    auto& p = sim.particles();
    for (std::size_t i = 0; i < p.size(); ++i)
      if (p.id[i] == id) {
        if constexpr (requires { p.heat_rate; })
          if (heat) {
            p.heat_rate[i] = std::nan("");
            continue;
          }
        p.force[i].x() = std::nan("");
      }
  }
};

/// Spheres falling onto a floor, one of them (id 7) given a NaN load after 0.01 s.
template <class Sim>
Sim falling_with_nan_load(bool heat) {
  typename Sim::Params prm;
  prm.time_step = 2e-5;
  prm.gravity = Vec3(0, 0, -9.81);
  Sim sim(prm);
  sim.add_material(glass());
  for (int k = 0; k < 8; ++k)
    sim.add_particle({.position = {0.03 * k, 0, 0.05},
                      .radius = 0.01,
                      .temperature = heat ? 300.0 : std::nan(""),
                      .id = 3 + k});
  sim.add_wall(walls::Plane{Vec3::Zero(), Vec3::UnitZ()});
  // a NaN particle is not one that left the box: it must not be removed quietly
  sim.set_bounding_box(regions::Box<3>{Vec3(-1, -1, -1), Vec3(1, 1, 1)});
  sim.template stage<NanLoad>() = NanLoad{.id = 7, .at = 0.01, .heat = heat};
  return sim;
}

} // namespace

TEST_CASE_TEMPLATE("numerical checks: a position or temperature that is no longer finite stops "
                   "the run, naming the particle",
                   Integrator, integrate::VelocityVerlet, integrate::VelocityVerletHalfStep,
                   integrate::SymplecticEuler) {
  // Without the check a NaN particle drops out of the displacement maximum, keeps no contact and
  // is never reported (or is removed as having left the bounding box). With it, the next step
  // stops with NumericalError. The Verlet integrators take the pass over the particles that
  // measures the displacements; symplectic Euler drifts after the forces and is measured by the
  // neighbour update.
  using Sim =
      Simulation<Sphere, search::CellList, presets::HertzMindlin, Integrator, stages<NanLoad>>;
  auto sim = falling_with_nan_load<Sim>(false);
  CHECK_THROWS_WITH_AS(sim.run(0.05), doctest::Contains("particle 7 has position = (nan"),
                       NumericalError);
  // the step after the load: t = 0.01 s reached at step 500
  CHECK(sim.step_count() <= 502);
  for (std::size_t i = 0; i < sim.particles().size(); ++i)
    if (sim.particles().id[i] != 7) CHECK(sim.particles().position[i].allFinite());

  // a temperature is checked where it is integrated
  using ThermalFall = Simulation<Sphere, search::CellList, Thermal, Integrator, stages<NanLoad>>;
  auto hot = falling_with_nan_load<ThermalFall>(true);
  CHECK_THROWS_WITH_AS(hot.run(0.05), doctest::Contains("particle 7 has temperature = nan K"),
                       NumericalError);
}

TEST_CASE("numerical checks: a temperature that is no longer finite stops a thermal analysis") {
  // particles at rest, no neighbour-list rebuild after the first: the check is in the update
  using Sim = Simulation<Sphere, search::CellList, Thermal, stages<NanLoad>>;
  Sim::Params prm;
  prm.analysis = Analysis::thermal;
  prm.time_step = 1e-3;
  Sim sim(prm);
  sim.add_material(glass());
  for (int k = 0; k < 4; ++k)
    sim.add_particle(
        {.position = {0.0199 * k, 0, 0}, .radius = 0.01, .temperature = 300.0 + k, .id = 20 + k});
  sim.stage<NanLoad>() = NanLoad{.id = 22, .at = 0.5, .heat = true};
  CHECK_THROWS_WITH_AS(sim.run(2.0), doctest::Contains("particle 22 has temperature = nan K"),
                       NumericalError);
  CHECK(sim.time() < 0.51);
}

TEST_CASE("input: two particles at the same centre are refused before the run") {
  // their contact has no normal: the run would otherwise end in NaN positions
  MechSim sim({.time_step = 1e-6});
  sim.add_material(glass());
  sim.add_particle({.position = Vec3(0.01, 0, 0), .radius = 1e-3, .id = 4});
  sim.add_particle({.position = Vec3(0.01, 0, 0), .radius = 2e-3, .id = 9});
  std::string what;
  try {
    sim.initialize();
  } catch (const InputError& e) {
    what = e.what();
  }
  CHECK(what.find("particles 4 and 9 have the same centre (0.01, 0, 0) m") != std::string::npos);
  CHECK(what.find("distinct centres") != std::string::npos);
}
