// Input checks of conditions, the lifecycle and variable properties: the message names the
// object, the value and the valid range, and a run never continues with an invalid value.

#include <doctest/doctest.h>
#include <grain/grain.hpp>
#include <grain/models/conduction/batchelor_obrien.hpp>

#include <cmath>

using namespace grain;

namespace {

using Thermal = Interaction<normal::Hertz<>, tangent::None, rolling::None,
                            conduction::BatchelorOBrien>;
using ThermalSim = Simulation<Sphere, search::CellList, Thermal>;
using MechSim = Simulation<Sphere, search::CellList, presets::HertzMindlin>;

Material glass() {
  return {.name = "glass", .density = 2500, .young = 1e7, .poisson = 0.25, .conductivity = 1.0,
          .heat_capacity = 800};
}

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
    sim.add_variable_property({"all", Property::conductivity, Variable::time,
                               Table({{0.0, 1.0}, {10.0, 1000.0}})});
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
  for (double T : given.particles().temperature) CHECK(std::isfinite(T));
}
