// Multi-node facets: a sphere at rest on a triangle loads its three nodes as its barycentric
// coordinates say; a sphere dropped on a belt of facets driven through their nodes ends rolling
// at 2/7 of the belt speed (a disk at 1/3 in 2D); a sphere hitting a facet with free nodes
// conserves the momentum of sphere and nodes.
#include "../approx.hpp"
#include "../errors.hpp"
#include <cmath>
#include <doctest/doctest.h>
#include <grain/grain.hpp>
#include <grain/walls/facets.hpp>

using namespace grain;
using grain::test::approx;

namespace {
using Contact3 = Interaction<normal::Hertz<>, tangent::Mindlin>;
using Contact2 = Interaction<normal::LinearSpringDashpot, tangent::SpringDashpotSlider>;
using Sim3 = Simulation<Sphere, search::CellList, Contact3, stages<Facets<3>>>;
using Sim2 = Simulation<Disk, search::CellList, Contact2, stages<Facets<2>>>;
const Material rubber{.name = "rubber",
                      .density = 1200,
                      .young = 2e7,
                      .poisson = 0.4,
                      .restitution = 0.3,
                      .friction = 0.6};
} // namespace

TEST_CASE("facets: a sphere at rest on a triangle loads the nodes by its barycentric weights") {
  Sim3::Params prm;
  prm.gravity = Vec3(0, 0, -9.81);
  prm.damping_translational = 2e-3; // settles in 0.1 s
  Sim3 sim(prm);
  const auto m = sim.add_material(rubber);
  auto& f = sim.stage<Facets<3>>();
  const Vec3 a(0, 0, 0), b(0.02, 0.002, 0), c(0.004, 0.018, 0);
  const auto na = f.add_node({.position = a}), nb = f.add_node({.position = b}),
             nc = f.add_node({.position = c});
  f.add_facet(sim, {na, nb, nc}, {.name = "plate", .material = m});
  // the sphere above the point of barycentric coordinates (0.2, 0.3, 0.5)
  const Vec3 q = 0.2 * a + 0.3 * b + 0.5 * c;
  const double R = 1e-3;
  sim.add_particle({.position = q + Vec3(0, 0, 1.2 * R), .radius = R, .material = m});
  sim.run(0.15);
  const double W = sim.particles().mass[0] * 9.81;
  INFO("loads ", f.contact_load(na).transpose(), " | ", f.contact_load(nb).transpose(), " | ",
       f.contact_load(nc).transpose(), "; weight ", W);
  CHECK(f.contact_load(na).z() == approx(-0.2 * W).epsilon(1e-6));
  CHECK(f.contact_load(nb).z() == approx(-0.3 * W).epsilon(1e-6));
  CHECK(f.contact_load(nc).z() == approx(-0.5 * W).epsilon(1e-6));
  // force and moment of the node loads are those of the contact
  Vec3 sum = Vec3::Zero(), moment = Vec3::Zero();
  for (auto n : {na, nb, nc}) {
    sum += f.contact_load(n);
    moment += f.position(n).cross(f.contact_load(n));
  }
  CHECK((sum - sim.wall_force(0)).norm() < 1e-12 * W);
  // the moment of a vertical load about the origin is horizontal: its x and y components
  Vec3 wall_moment = Vec3::Zero();
  sim.for_each_wall_load([&](std::int64_t, std::size_t, const Vec3& p, const Vec3& F) {
    wall_moment += Vec3(p.x(), p.y(), 0.0).cross(F); // about the facet's plane: q x F
  });
  REQUIRE(std::abs(wall_moment.x()) > 1e-3 * W * 1e-3);
  CHECK(moment.x() == approx(wall_moment.x()).epsilon(1e-12));
  CHECK(moment.y() == approx(wall_moment.y()).epsilon(1e-12));
}

TEST_CASE("facets: a belt driven through its nodes brings a sphere to 2/7 of its speed") {
  Sim3::Params prm;
  prm.gravity = Vec3(0, 0, -9.81);
  Sim3 sim(prm);
  const auto m = sim.add_material(rubber);
  auto& f = sim.stage<Facets<3>>();
  const double u = 0.2; // belt speed [m/s]
  const VectorTimeFunction<3> belt(Vec3(u, 0, 0));
  std::array<std::size_t, 4> n;
  const double L = 0.03, w = 0.01;
  const std::array<Vec3, 4> corner{Vec3(-L, -w, 0), Vec3(0.005, -w, 0), Vec3(0.005, w, 0),
                                   Vec3(-L, w, 0)};
  for (int k = 0; k < 4; ++k)
    n[k] = f.add_node({.position = corner[k], .driven_velocity = belt});
  f.add_facet(sim, {n[0], n[1], n[2]}, {.material = m});
  f.add_facet(sim, {n[0], n[2], n[3]}, {.material = m});
  const double R = 1e-3;
  sim.add_particle(
      {.position = Vec3(0, -0.005, R), .radius = R, .material = m}); // away from the diagonal
  sim.run(0.06);
  const auto& p = sim.particles();
  INFO("sphere v ", p.velocity[0].transpose(), " omega ", p.omega[0].transpose());
  // rolling without slip on the belt: v - omega x (R n) = u, with I = 2/5 m R^2: v = 2/7 u
  CHECK(p.velocity[0].x() == approx(2.0 / 7.0 * u).epsilon(1e-3));
  CHECK(p.omega[0].y() * R == approx(-5.0 / 7.0 * u).epsilon(1e-3));
  // the nodes moved with the belt
  CHECK((f.position(n[0]) - (corner[0] + Vec3(u * sim.time(), 0, 0))).norm() < 1e-12);
}

TEST_CASE("facets in 2D: a segment belt brings a disk to 1/3 of its speed") {
  Sim2::Params prm;
  prm.gravity = Vec2(0, -9.81);
  Sim2 sim(prm);
  const auto m = sim.add_material(rubber);
  auto& f = sim.stage<Facets<2>>();
  const double u = 0.2;
  const VectorTimeFunction<2> belt(Vec2(u, 0));
  const auto a = f.add_node({.position = Vec2(-0.03, 0), .driven_velocity = belt});
  const auto b = f.add_node({.position = Vec2(0.005, 0), .driven_velocity = belt});
  f.add_facet(sim, {a, b}, {.material = m});
  const double R = 1e-3;
  sim.add_particle({.position = Vec2(0, R), .radius = R, .material = m});
  sim.run(0.06);
  const auto& p = sim.particles();
  INFO("disk v ", p.velocity[0].transpose(), " omega ", p.omega[0]);
  // the tangential spring still holds a little oscillation: 0.5 %
  CHECK(p.velocity[0].x() == approx(u / 3.0).epsilon(5e-3));
  CHECK(p.velocity[0].x() + p.omega[0] * R == approx(u).epsilon(5e-3)); // no slip
}

TEST_CASE("facets: a sphere hits a facet of free nodes; momentum of sphere and nodes is kept") {
  Sim3::Params prm;
  prm.time_step = 2e-7;
  Sim3 sim(prm);
  const auto m = sim.add_material(rubber);
  auto& f = sim.stage<Facets<3>>();
  const double mn = 2e-3; // node mass [kg]
  const auto a = f.add_node({.position = Vec3(0, 0, 0), .mass = mn});
  const auto b = f.add_node({.position = Vec3(0.01, 0, 0), .mass = mn});
  const auto c = f.add_node({.position = Vec3(0, 0.01, 0), .mass = mn});
  f.add_facet(sim, {a, b, c}, {.material = m});
  const double R = 1e-3;
  sim.add_particle({.position = Vec3(0.003, 0.002, 1.05 * R),
                    .radius = R,
                    .material = m,
                    .velocity = Vec3(0.1, 0.05, -0.5)});
  sim.initialize();
  auto total = [&] {
    Vec3 P = sim.particles().mass[0] * sim.particles().velocity[0];
    for (auto k : {a, b, c})
      P += mn * f.velocity(k);
    return P;
  };
  const Vec3 P0 = total();
  bool hit = false;
  for (int k = 0; k < 3000; ++k) {
    sim.step();
    hit = hit || f.velocity(a).norm() > 0;
  }
  REQUIRE(hit);
  CHECK(sim.contact_counts().second == 0); // apart again
  INFO("P0 ", P0.transpose(), " P ", total().transpose());
  CHECK((total() - P0).norm() < 1e-12 * P0.norm());
  // the facet went down, the sphere up
  CHECK(f.velocity(a).z() < 0);
  CHECK(sim.particles().velocity[0].z() > 0);
}

TEST_CASE("facets: bad input") {
  using grain::test::error_of, grain::test::has;
  Sim3 sim;
  sim.add_material(rubber);
  auto& f = sim.stage<Facets<3>>();
  CHECK(has(error_of([&] { f.add_node({.mass = -1.0}); }), "mass = -1"));
  const auto a = f.add_node({.position = Vec3::Zero()});
  CHECK(has(error_of([&] {
              f.add_facet(sim, {a, 1, 2}, {.name = "skin"});
            }),
            "Facet 'skin': node index = 1"));
}
