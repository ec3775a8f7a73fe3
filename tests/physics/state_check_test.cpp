// A run that goes wrong stops with NumericalError naming the particle, the quantity, the step
// and the stable limits of the start; an overlap at the start is refused with both ids; a
// thermal run whose particles conduct nothing is refused, and one with an insulating material
// warned about.

#include "../errors.hpp"
#include "../support/materials.hpp"
#include <doctest/doctest.h>
#include <grain/bodies.hpp>
#include <grain/grain.hpp>
#include <grain/models/conduction/batchelor_obrien.hpp>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

using namespace grain;
using grain::test::error_of;
using grain::test::has;

namespace {

using MechSim = Simulation<Sphere, search::CellList, presets::HertzMindlin>;
using Thermal =
    Interaction<normal::Hertz<>, tangent::None, rolling::None, conduction::BatchelorOBrien>;
using ThermalSim = Simulation<Sphere, search::CellList, Thermal>;

constexpr double R = 1e-3;

/// A 4 x 4 x 4 lattice of spheres of radius R, 0.1 R apart, at rest (no gravity), ids 0..63,
/// with time step 1e-6 s.
MechSim lattice(double max_start_overlap = 0.05) {
  MechSim::Params p;
  p.time_step = 1e-6;
  p.max_start_overlap = max_start_overlap;
  MechSim sim(p);
  sim.add_material(grain::test::glass(1e7));
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k)
        sim.add_particle({.position = Vec3(i, j, k) * 2.1 * R, .radius = R});
  return sim;
}

std::size_t index_of(const MechSim& sim, std::int64_t id) {
  for (std::size_t i = 0; i < sim.particles().size(); ++i)
    if (sim.particles().id[i] == id) return i;
  return sim.particles().size();
}

} // namespace

TEST_CASE("blow-up: a particle moving more than its radius per step stops the run before the "
          "output of that step, naming it, its speed and the limits of the start") {
  auto sim = lattice();
  long frames = 0;
  auto count = [&](const MechSim&) { ++frames; };
  sim.steps(10, io::every_steps(1, count));
  CHECK(frames == 11); // the start and 10 steps
  // 2000 m/s at dt = 1e-6 s: 2 radii per step (the bound R / dt = 1000 m/s)
  sim.particles().velocity[index_of(sim, 21)] = Vec3(2000.0, 0, 0);
  const auto e = error_of<NumericalError>([&] { sim.steps(5); });
  CHECK(has(e, "particle 21 has speed abs(v) = 2000 m/s"));
  CHECK(has(e, "2 radii per step"));
  CHECK(has(e, "abs(v) <= 1000 m/s"));
  CHECK(has(e, "step 10"));
  CHECK(has(e, "at the start of the run the Rayleigh time"));
  CHECK(sim.step_count() == 10); // the step of the fast particle did not complete
  // a bound of 3 radii per step lets it go (and one of 0 is refused)
  MechSim::Params loose;
  loose.time_step = 1e-6;
  loose.max_step_travel = 3.0;
  MechSim fast(loose);
  fast.add_material(grain::test::glass(1e7));
  fast.add_particle({.position = Vec3::Zero(), .radius = R, .velocity = Vec3(2000.0, 0, 0)});
  CHECK_NOTHROW(fast.steps(5));
  loose.max_step_travel = 0.0;
  CHECK(has(error_of([&] { MechSim bad(loose); }), "max_step_travel = 0 is invalid"));
  // a quantity that is not finite, with output: nothing is written from that state
  auto nan = lattice();
  frames = 0;
  nan.steps(10, io::every_steps(1, count));
  nan.particles().omega[index_of(nan, 5)] = Vec3(0, std::nan(""), 0);
  const auto f = error_of<NumericalError>([&] { nan.steps(5, io::every_steps(1, count)); });
  CHECK(has(f, "particle 5 has angular velocity = (0, nan, 0) rad/s"));
  CHECK(has(f, "valid range: a finite number"));
  CHECK(frames == 11);
}

TEST_CASE("blow-up: the centre of a particle inside another, or behind a plane, stops the run "
          "before the output, naming both") {
  auto sim = lattice();
  sim.add_wall(walls::Plane{{0, 0, -R}, {0, 0, 1}}, {.name = "floor"});
  sim.steps(2);
  auto& x = sim.particles().position;
  // particle 1 (at z = 2.1 R) moved to 0.9 R of particle 0 (still in the neighbour list)
  x[index_of(sim, 1)] = x[index_of(sim, 0)] + Vec3(0, 0, 0.9 * R);
  long frames = 0;
  const auto e = error_of<NumericalError>(
      [&] { sim.steps(1, io::every_steps(1, [&](const MechSim&) { ++frames; })); });
  CHECK(frames == 0);
  CHECK((has(e, "particles 0 and 1 overlap by") || has(e, "particles 1 and 0 overlap by")));
  CHECK(has(e, "beyond the smaller radius 0.001 m"));
  // behind the floor
  auto floor = lattice();
  floor.add_wall(walls::Plane{{0, 0, -R}, {0, 0, 1}}, {.name = "floor"});
  floor.steps(2);
  floor.particles().position[index_of(floor, 0)].z() = -1.2 * R;
  const auto g = error_of<NumericalError>([&] { floor.check_state(); });
  CHECK(has(g, "particle 0 has its centre 0.0002 m behind wall 0 'floor'"));
}

TEST_CASE("overlaps at the start: refused beyond max_start_overlap with both ids, checked for "
          "what was added since the last start") {
  {
    auto sim = lattice();
    // particle 64 overlaps particle 0 by 0.1 R
    sim.add_particle({.position = Vec3(-1.9 * R, 0, 0), .radius = R, .id = 64});
    const auto e = error_of<InputError>([&] { sim.initialize(); });
    CHECK((has(e, "particles 0 and 64 overlap by") || has(e, "particles 64 and 0 overlap by")));
    CHECK(has(e, "0.1 of the smaller radius at the start"));
    CHECK(has(e, "valid range: [0, 0.05]"));
    CHECK(has(e, "max_start_overlap"));
  }
  {
    auto sim = lattice(0.2); // allowed
    sim.add_particle({.position = Vec3(-1.9 * R, 0, 0), .radius = R, .id = 64});
    CHECK_NOTHROW(sim.steps(1));
  }
  {
    auto sim = lattice();
    sim.add_wall(walls::Plane{{0, 0, -0.5 * R}, {0, 0, 1}}, {.name = "floor"});
    const auto e = error_of<InputError>([&] { sim.initialize(); });
    CHECK(has(e, "overlaps wall 0 'floor' by 0.0005 m = 0.5 of its radius at the start"));
  }
  {
    // after a run: a particle added between runs is checked, the ones that were there are not
    auto sim = lattice();
    sim.steps(5);
    sim.particles().position[index_of(sim, 1)] = Vec3(0, 0, 1.8 * R); // 0.2 R, moved by hand
    sim.add_particle({.position = Vec3(20 * R, 0, 0), .radius = R, .id = 100});
    CHECK_NOTHROW(sim.steps(1));
    sim.add_particle({.position = Vec3(20 * R, 1.5 * R, 0), .radius = R, .id = 101});
    const auto e = error_of<InputError>([&] { sim.steps(1); });
    CHECK((has(e, "particles 100 and 101 overlap") || has(e, "particles 101 and 100 overlap")));
    CHECK(has(e, "0.5 of the smaller radius"));
  }
  {
    MechSim::Params p;
    p.max_start_overlap = -0.1;
    const auto e = error_of<InputError>([&] { MechSim sim(p); });
    CHECK(has(e, "max_start_overlap = -0.1 is invalid"));
  }
}

TEST_CASE("a thermal run with particle materials that do not conduct is warned about, once") {
  auto make = [](double k1, double k2) {
    ThermalSim::Params p;
    p.analysis = Analysis::thermal;
    p.time_step = 1.0;
    ThermalSim sim(p);
    auto a = grain::test::glass(), b = grain::test::glass();
    a.name = "a";
    a.conductivity = k1;
    b.name = "b";
    b.conductivity = k2;
    const auto ma = sim.add_material(a), mb = sim.add_material(b);
    sim.add_particle({.position = {0, 0, 0}, .radius = R, .material = ma, .temperature = 300});
    sim.add_particle(
        {.position = {1.99 * R, 0, 0}, .radius = R, .material = mb, .temperature = 400});
    return sim;
  };
  std::vector<std::string> warnings;
  const auto saved = warning_handler();
  warning_handler() = [&](const std::string& m) { warnings.push_back(m); };
  auto none = make(0.0, 0.0);
  none.steps(1);
  REQUIRE(warnings.size() == 1);
  CHECK(has(warnings[0], "Material 'a', 'b': conductivity = 0 W/(m K) (the default) in a thermal "
                         "simulation: no particle conducts heat through its contacts"));
  auto half = make(1.0, 0.0);
  half.steps(3);
  half.steps(3);
  REQUIRE(warnings.size() == 2); // once for the same materials
  CHECK(has(warnings[1], "Material 'b': conductivity = 0 W/(m K)"));
  CHECK(has(warnings[1], "(they insulate)"));
  // the insulating particle's contact conducts nothing: k_eff = k1 k2 / (k1 + k2) = 0
  CHECK(half.particles().temperature[0] == 300.0);
  auto both = make(1.0, 1.0);
  both.steps(3);
  CHECK(warnings.size() == 2);
  CHECK(both.particles().temperature[0] > 300.0);
  warning_handler() = saved;
}

TEST_CASE("a spring table with a falling branch is followed as given (softening)") {
  // documented as intended: a table may soften (a negative slope after a peak); the dashpot of a
  // damping ratio uses max(k, 0), so it never turns into a source
  bodies::SpringParams p;
  p.spring = Table({{-1.0, -100.0}, {0.0, 0.0}, {0.01, 100.0}, {0.02, 50.0}, {1.0, 50.0}});
  p.damping_ratio = 0.5;
  CHECK_NOTHROW(bodies::validate(p));
  bodies::SpringState st;
  double k = 0.0;
  CHECK(bodies::detail::elastic_force(p, st, 0.015, 0.0, k) == doctest::Approx(75.0));
  CHECK(k == doctest::Approx(-5000.0));
  double c = -1.0, fd = -1.0;
  bodies::detail::dashpot_force(p, 0.3, k, 2.0, c, fd);
  CHECK(c == 0.0);
  CHECK(fd == 0.0);
}
