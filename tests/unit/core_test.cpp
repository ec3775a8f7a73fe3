// Materials, shapes, input validation.
#include "../approx.hpp"
#include "../errors.hpp"
#include <cmath>
#include <doctest/doctest.h>
#include <grain/grain.hpp>
#include <limits>
#include <numbers>
#include <string>

using namespace grain;

namespace {
using grain::test::error_of;
using grain::test::has;

using Contact2 = Interaction<normal::LinearSpringDashpot, tangent::SpringDashpotSlider>;
using Sim2 = Simulation<Disk, search::AllPairs, Contact2>;
using Contact3 = Interaction<normal::Hertz<>, tangent::SpringDashpotSlider>;
using Sim3 = Simulation<Sphere, search::CellList, Contact3>;
const Material glass{.name = "glass", .density = 2500, .young = 7e10, .poisson = 0.25};
} // namespace

TEST_CASE("shape mass and inertia") {
  const double r = 2e-3, rho = 2500;
  Sim3 s3;
  auto m = s3.add_material(glass);
  s3.add_particle({.position = Vec3::Zero(), .radius = r, .material = m});
  const double ms = rho * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  CHECK(s3.particles().mass[0] == grain::test::approx(ms).epsilon(1e-14));
  CHECK(s3.particles().inertia[0] == grain::test::approx(0.4 * ms * r * r).epsilon(1e-14));

  Sim2 disk({}, Disk{.thickness = 1e-3});
  m = disk.add_material(glass);
  disk.add_particle({.position = Vec2::Zero(), .radius = r, .material = m});
  const double md = rho * std::numbers::pi * r * r * 1e-3;
  CHECK(disk.particles().mass[0] == grain::test::approx(md).epsilon(1e-14));
  CHECK(disk.particles().inertia[0] == grain::test::approx(0.5 * md * r * r).epsilon(1e-14));

  Sim2 sphere_like({}, Disk{.sphere_mass = true});
  m = sphere_like.add_material(glass);
  sphere_like.add_particle({.position = Vec2::Zero(), .radius = r, .material = m});
  CHECK(sphere_like.particles().mass[0] == grain::test::approx(ms).epsilon(1e-14));
  CHECK(sphere_like.particles().inertia[0] == grain::test::approx(0.4 * ms * r * r).epsilon(1e-14));
}

TEST_CASE("pair properties follow the mixing rules") {
  const Material a{
      .density = 1000, .young = 1e9, .poisson = 0.2, .restitution = 0.4, .friction = 0.2};
  const Material b{.density = 1000,
                   .young = 3e9,
                   .poisson = 0.4,
                   .shear = 1e9,
                   .restitution = 0.8,
                   .friction = 0.6};
  const auto p = PairProperties::mix(a, b);
  CHECK(p.young_eff == grain::test::approx(1.0 / ((1 - 0.04) / 1e9 + (1 - 0.16) / 3e9)));
  const double ga = 1e9 / (2 * 1.2);
  CHECK(p.shear_eff == grain::test::approx(1.0 / ((2 - 0.2) / ga + (2 - 0.4) / 1e9)));
  CHECK(p.restitution == grain::test::approx(0.6));
  CHECK(p.friction == grain::test::approx(0.4));
  CHECK(p.poisson_avg == grain::test::approx(0.3));
  // damping ratio zeta = -ln e / sqrt(ln^2 e + pi^2)
  const double l = std::log(0.6);
  CHECK(p.damping_ratio() ==
        grain::test::approx(-l / std::sqrt(l * l + std::numbers::pi * std::numbers::pi)));
  const auto o = PairProperties::mix(a, b, {.restitution = 0.9, .friction = 0.1});
  CHECK(o.restitution == grain::test::approx(0.9));
  CHECK(o.friction == grain::test::approx(0.1));
}

TEST_CASE("bad input names the object, the value and the valid range") {
  Sim3 sim;
  auto m = sim.add_material(glass);

  auto e = error_of(
      [&] { sim.add_particle({.position = Vec3::Zero(), .radius = -1e-3, .material = m}); });
  CHECK(has(e, "sphere particle"));
  CHECK(has(e, "radius = -0.001"));
  CHECK(has(e, "(0, inf)"));

  e = error_of([&] { sim.add_material({.name = "foam", .density = 0, .young = 1e6}); });
  CHECK(has(e, "Material 'foam'"));
  CHECK(has(e, "density = 0"));
  CHECK(has(e, "(0, inf)"));

  e = error_of(
      [&] { sim.add_material({.name = "rubber", .density = 1000, .young = 1e6, .poisson = 0.5}); });
  CHECK(has(e, "Material 'rubber'"));
  CHECK(has(e, "poisson = 0.5"));
  CHECK(has(e, "(-1, 0.5)"));

  e = error_of(
      [&] { sim.add_material({.name = "odd", .density = 1000, .young = 1e6, .poisson = -1.2}); });
  CHECK(has(e, "poisson = -1.2"));

  const double nan = std::numeric_limits<double>::quiet_NaN();
  e = error_of(
      [&] { sim.add_particle({.position = Vec3(0, nan, 0), .radius = 1e-3, .material = m}); });
  CHECK(has(e, "sphere particle"));
  CHECK(has(e, "position"));
  CHECK(has(e, "nan"));
  CHECK(has(e, "finite"));

  e = error_of(
      [&] { sim.add_particle({.position = Vec3::Zero(), .radius = 1e-3, .material = 7}); });
  CHECK(has(e, "material = 7"));
  CHECK(has(e, "[0, 1)"));

  Sim2 s2;
  auto m2 = s2.add_material(glass);
  e = error_of([&] {
    s2.add_wall(walls::Segment{Vec2(1, 1), Vec2(1, 1)}, {.name = "floor", .material = m2});
  });
  CHECK(has(e, "Wall 'floor'"));
  CHECK(has(e, "segment length = 0"));
  CHECK(has(e, "(0, inf)"));

  e = error_of([&] { s2.add_wall(walls::Circle{Vec2::Zero(), -2.0}, {.name = "drum"}); });
  CHECK(has(e, "Wall 'drum'"));
  CHECK(has(e, "circle radius = -2"));

  e = error_of([&] { sim.add_wall(walls::Plane{Vec3::Zero(), Vec3(0, 0, 2)}, {.name = "base"}); });
  CHECK(has(e, "Wall 'base'"));
  CHECK(has(e, "plane normal length = 2"));

  e = error_of([&] { Sim2 bad({}, Disk{.thickness = 0.0}); });
  CHECK(has(e, "Disk: thickness = 0"));

  e = error_of([&] { Sim3 bad({.contact = {.normal = {}, .tangent = {.stiffness = -5.0}}}); });
  CHECK(has(e, "tangent::SpringDashpotSlider: stiffness = -5"));
}

TEST_CASE("a time step above the stable limit is refused with both values") {
  Sim3 sim({.time_step = 1e-3});
  auto m = sim.add_material({.density = 2500, .young = 1e7, .poisson = 0.3});
  sim.add_particle({.position = Vec3::Zero(), .radius = 5e-4, .material = m});
  const double critical = sim.critical_time_step();
  // Rayleigh time of the benchmark material: 4.32699e-5 s
  CHECK(sim.rayleigh_time() == grain::test::approx(4.32699e-5).epsilon(1e-5));
  const auto e = error_of([&] { sim.step(); });
  CHECK(has(e, "time_step = 0.001"));
  CHECK(has(e, detail::to_text(critical)));
  CHECK(has(e, "stable limit"));

  Sim3 ok({.time_step = 0.5 * critical});
  m = ok.add_material({.density = 2500, .young = 1e7, .poisson = 0.3});
  ok.add_particle({.position = Vec3::Zero(), .radius = 5e-4, .material = m});
  ok.step();
  CHECK(ok.time_step() == 0.5 * critical);

  Sim3 automatic;
  m = automatic.add_material({.density = 2500, .young = 1e7, .poisson = 0.3});
  automatic.add_particle({.position = Vec3::Zero(), .radius = 5e-4, .material = m});
  automatic.initialize();
  CHECK(automatic.time_step() == grain::test::approx(0.1 * automatic.critical_time_step()));
}

TEST_CASE("contact time-step limit follows the stiffness") {
  // linear spring of given stiffness: limit 2 sqrt(m*/k) for the particle pair (m* = m/2)
  Sim2 sim({.contact = {.normal = {.stiffness = 1e3}}});
  auto m = sim.add_material({.density = 2500, .young = 1e9, .poisson = 0.3});
  sim.add_particle({.position = Vec2::Zero(), .radius = 1e-3, .material = m});
  const double mass = sim.particles().mass[0];
  CHECK(sim.contact_time_step() == grain::test::approx(2.0 * std::sqrt(0.5 * mass / 1e3)));
}
