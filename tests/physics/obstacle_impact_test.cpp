// Spheres against obstacles (triangle meshes moving rigidly), run as full simulations.
//
// - A sphere dropped on a flat square obstacle of 2 or 8 triangles, over a face, exactly over a
//   shared edge (the diagonal), next to it and over the vertex shared by 8 triangles, bounces as
//   on a walls::Plane through the square: the largest overlap and the rebound velocity agree to
//   1e-9 relative (untilted: bit for bit; tilted, where the body-frame tests and the plane's
//   formula round differently, to round-off), with one wall contact at every step.
// - A sphere sliding without friction across the shared diagonal feels the plane's force at
//   every step (relative difference below 1e-9; independent triangles double it there).
// - A sphere hitting a convex edge of a box along the bisector of its faces has exactly one
//   contact, whose normal is the edge's; it rebounds along that normal with the rebound speed of
//   a head-on impact on a plane (1e-9 relative).
// - An obstacle pushed with a time-function velocity V hits a sphere at rest; the sphere leaves
//   with v' = (1 + e) V (in the obstacle's frame it arrives with V and leaves with e V). With the
//   linear spring-dashpot (unclamped) the model's restitution is e exactly in continuous time;
//   the time stepping errs by at most 1.1 n zeta omega0 dt e (the contact-onset and -end
//   jumps, n = 2, see the linear restitution test): 3.7e-4 for e = 0.5 at dt = t_c/2000, and by
//   O((omega0 dt)^2) for e = 1. The same impact with a moving walls::Plane agrees to 1e-9.

#include "../support/materials.hpp"
#include "../support/meshes.hpp"
#include <grain/grain.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

namespace {

using namespace grain;
using HertzContact = Interaction<normal::Hertz<>, tangent::None>;
using HertzSim = Simulation<Sphere, search::CellList, HertzContact>;

using grain::test::box;
using grain::test::material;
using grain::test::moved;
using grain::test::square2;
using grain::test::square8;

/// One bounce: the largest overlap with the plane of the floor, the rebound normal velocity and
/// the most wall contacts at one step.
struct Bounce {
  double overlap = 0.0;
  double rebound = 0.0;
  std::size_t contacts = 0;
  long steps = 0; ///< steps in contact
};

/// Drops a sphere (radius r, speed v along -n) on the floor through `p` with normal `n`, made by
/// `add_floor(sim, material)`, and follows it until it has left the floor.
template <class AddFloor>
Bounce drop(const Vec3& start, const Vec3& p, const Vec3& n, AddFloor add_floor) {
  const double r = 0.05, v = 1.0;
  HertzSim::Params prm;
  prm.time_step = 1e-5;
  prm.gravity = -9.81 * n;
  HertzSim sim(prm);
  const auto k = sim.add_material(material(0.7));
  add_floor(sim, k);
  sim.add_particle({.position = start, .radius = r, .material = k, .velocity = -v * n});
  Bounce b;
  bool touched = false;
  for (long s = 0; s < 20000; ++s) {
    sim.step();
    const double h = (sim.particles().position[0] - p).dot(n);
    b.contacts = std::max(b.contacts, sim.contact_counts().second);
    if (h < r) {
      touched = true;
      ++b.steps;
      b.overlap = std::max(b.overlap, r - h);
    } else if (touched && h > r + 1e-3) {
      b.rebound = sim.particles().velocity[0].dot(n);
      return b;
    }
  }
  FAIL("the sphere did not leave the floor");
  return b;
}

} // namespace

TEST_CASE("obstacle: a sphere bounces on a flat square of triangles as on a plane") {
  struct Case {
    std::string where;
    bool eight;
    double x, y;
  };
  const Case cases[] = {
      {"over a face", false, 0.7, 0.2},
      {"exactly over the diagonal", false, 0.3, 0.3},
      {"1e-7 m next to the diagonal", false, 0.3 + 1e-7, 0.3},
      {"over a face of 8", true, 0.6, 0.3},
      {"over the vertex shared by 8 triangles", true, 0.5, 0.5},
      {"over an edge shared in the 8-triangle square", true, 0.5, 0.25},
      {"over a diagonal of the 8-triangle square", true, 0.25, 0.25},
      {"next to the shared vertex", true, 0.5 + 1e-9, 0.5 - 1e-9},
  };
  const Eigen::Matrix3d tilt =
      Eigen::AngleAxisd(0.4, Vec3(1, 2, 0.3).normalized()).toRotationMatrix();
  for (const bool tilted : {false, true})
    for (const auto& c : cases) {
      CAPTURE(c.where);
      CAPTURE(tilted);
      const Eigen::Matrix3d Q = tilted ? tilt : Eigen::Matrix3d::Identity();
      const Vec3 s = tilted ? Vec3(0.2, -0.1, 0.3) : Vec3::Zero();
      const Vec3 n = Q * Vec3::UnitZ();
      const Vec3 start = Q * Vec3(c.x, c.y, 0.06) + s;
      const auto mesh = moved(c.eight ? square8() : square2(), Q, s);
      const Bounce plane = drop(start, s, n, [&](HertzSim& sim, std::uint32_t k) {
        sim.add_wall(walls::Plane{s, n}, {.material = k});
      });
      const Bounce ob = drop(start, s, n, [&](HertzSim& sim, std::uint32_t k) {
        add_obstacle(sim, mesh, {.name = "floor", .material = k, .reference_point = s});
      });
      const double d_overlap = std::abs(ob.overlap / plane.overlap - 1.0);
      const double d_rebound = std::abs(ob.rebound / plane.rebound - 1.0);
      INFO("overlap ", ob.overlap, " m (plane ", plane.overlap, "), relative difference ",
           d_overlap, "; rebound ", ob.rebound, " m/s (plane ", plane.rebound,
           "), relative difference ", d_rebound);
      CHECK(plane.steps > 500);
      CHECK(plane.rebound > 0.5);
      CHECK(ob.contacts == 1);
      CHECK(d_overlap < 1e-9);
      CHECK(d_rebound < 1e-9);
      if (!tilted) {
        CHECK(ob.overlap == plane.overlap);
        CHECK(ob.rebound == plane.rebound);
      }
    }
}

TEST_CASE("obstacle: a sphere sliding across the shared diagonal feels the plane's force") {
  // frictionless, under gravity, starting slightly above the floor: it bounces, settles and
  // slides from (0.45, 0.15) across the diagonal y = x to (0.15, 0.45)
  auto run = [](int floor, std::vector<Vec3>& force, std::vector<std::size_t>& contacts) {
    HertzSim::Params prm;
    prm.time_step = 2e-5;
    prm.gravity = Vec3(0, 0, -9.81);
    HertzSim sim(prm);
    const auto k = sim.add_material(material(0.3));
    if (floor == 0) sim.add_wall(walls::Plane{Vec3::Zero(), Vec3::UnitZ()}, {.material = k});
    if (floor == 1) add_obstacle(sim, square2(), {.name = "floor", .material = k});
    if (floor == 2) // the same triangles as independent walls
      for (const auto& t : square2().triangles)
        sim.add_wall(walls::Triangle{square2().vertices[t[0]], square2().vertices[t[1]],
                                     square2().vertices[t[2]]},
                     {.material = k});
    sim.add_particle({.position = Vec3(0.45, 0.15, 0.0505),
                      .radius = 0.05,
                      .material = k,
                      .velocity = Vec3(-0.3, 0.3, 0)});
    for (long s = 0; s < 50000; ++s) {
      sim.step();
      force.push_back(sim.particles().force[0]);
      contacts.push_back(sim.contact_counts().second);
    }
    return sim.particles().position[0];
  };
  std::vector<Vec3> fp, fo, ft;
  std::vector<std::size_t> cp, co, ct;
  const Vec3 end_plane = run(0, fp, cp);
  const Vec3 end_obstacle = run(1, fo, co);
  run(2, ft, ct);
  REQUIRE(end_plane.y() > end_plane.x()); // it crossed the diagonal
  double worst = 0.0, worst_lone = 0.0;
  std::size_t most = 0;
  long touching = 0;
  for (std::size_t s = 0; s < fp.size(); ++s) {
    const double scale = std::max(fp[s].norm(), 1e-3);
    worst = std::max(worst, (fo[s] - fp[s]).norm() / scale);
    worst_lone = std::max(worst_lone, (ft[s] - fp[s]).norm() / scale);
    most = std::max(most, co[s]);
    touching += co[s] == 1;
  }
  INFO("largest force difference relative to the plane's ", worst,
       " (independent triangles: ", worst_lone, "), steps touching ", touching, " of ", fp.size());
  CHECK(worst < 1e-9);
  CHECK(most == 1);
  CHECK(touching > 40000);
  CHECK((end_obstacle - end_plane).norm() < 1e-12);
  CHECK(worst_lone > 0.5); // the check would see the double force of independent triangles
}

TEST_CASE("obstacle: a sphere hitting a convex edge of a box has one contact, the edge's") {
  // box [0, 1] x [0, 1] x [-1, 0], each side two triangles; the sphere comes along the bisector
  // of the top and front faces onto the edge y = 0, z = 0
  const walls::TriangleMesh cube = box(Vec3(0, 0, -1), Vec3(1, 1, 0));
  const double r = 0.05, v = 1.0;
  const Vec3 bisector = Vec3(0, -1, 1).normalized();
  auto run = [&](bool edge, Vec3& velocity, std::size_t& most, double& worst_normal) {
    HertzSim::Params prm;
    prm.time_step = 1e-5;
    HertzSim sim(prm);
    const auto k = sim.add_material(material(0.7));
    if (edge)
      add_obstacle(sim, cube,
                   {.name = "box", .material = k, .reference_point = Vec3(0.5, 0.5, -0.5)});
    else // the plane through the edge, perpendicular to the bisector
      sim.add_wall(walls::Plane{Vec3(0.4, 0, 0), bisector}, {.material = k});
    sim.add_particle({.position = Vec3(0.4, 0, 0) + (r + 0.001) * bisector,
                      .radius = r,
                      .material = k,
                      .velocity = -v * bisector});
    most = 0;
    worst_normal = 0.0;
    for (long s = 0; s < 4000; ++s) {
      sim.step();
      std::size_t n = 0;
      sim.for_each_contact([&](auto, auto, bool wall, const auto& g, const auto&) {
        n += wall;
        worst_normal = std::max(worst_normal, (g.normal + bisector).norm());
      });
      most = std::max(most, n);
    }
    velocity = sim.particles().velocity[0];
  };
  Vec3 v_edge, v_plane;
  std::size_t most_edge = 0, most_plane = 0;
  double normal_edge = 0.0, normal_plane = 0.0;
  run(true, v_edge, most_edge, normal_edge);
  run(false, v_plane, most_plane, normal_plane);
  INFO("rebound ", v_edge.transpose(), " m/s (plane: ", v_plane.transpose(),
       "), largest normal deviation ", normal_edge);
  CHECK(most_edge == 1);
  CHECK(normal_edge < 1e-12);
  CHECK(v_edge.dot(bisector) > 0.5 * v);                            // it rebounded
  CHECK((v_edge - v_edge.dot(bisector) * bisector).norm() < 1e-12); // along the edge normal
  CHECK(std::abs(v_edge.dot(bisector) / v_plane.dot(bisector) - 1.0) < 1e-9);
}

namespace {

using LsdContact = Interaction<normal::LinearSpringDashpot, tangent::None>;
using LsdSim = Simulation<Sphere, search::AllPairs, LsdContact>;

/// A floor pushed up with velocity V(t) (a ramp from 0 to V over 2e-4 s, then V) hits a sphere
/// at rest; returns the sphere's final velocity. `obstacle`: a 2-triangle square, else a plane.
double pushed(bool obstacle, double e, double V, double dt, double stiffness) {
  LsdSim::Params prm;
  prm.time_step = dt;
  prm.contact.normal.stiffness = stiffness;
  prm.contact.normal.no_cohesion = false;
  LsdSim sim(prm);
  const auto k = sim.add_material(material(e));
  const double r = 1e-3;
  const auto v =
      VectorTimeFunction<3>::along(Vec3::UnitZ(), TimeFunction::table({{0.0, 0.0}, {2e-4, V}}));
  if (obstacle) {
    walls::TriangleMesh m =
        moved(square2(), 0.01 * Eigen::Matrix3d::Identity(), Vec3(-0.005, -0.005, 0.0));
    add_obstacle(sim, m, {.name = "pusher", .material = k, .velocity = v});
  } else {
    sim.add_wall(walls::Plane{Vec3::Zero(), Vec3::UnitZ()}, {.material = k});
    sim.add_group("pusher", {}, {0});
    sim.prescribe_motion("pusher", v, std::nullopt);
  }
  // the floor reaches the sphere at t = 4e-4 s, 2e-4 s after the ramp (it moved V 3e-4 by then)
  // and leaves it about 3e-4 s later
  sim.add_particle({.position = Vec3(0.001, 0.002, r + V * 3e-4), .radius = r, .material = k});
  sim.run(1.5e-3);
  return sim.particles().velocity[0].z();
}

} // namespace

TEST_CASE("obstacle: pushed by a time-function velocity, it throws a sphere at rest at (1+e)V") {
  const double V = 0.5, K = 1e3;
  const double m = 2500.0 * 4.0 / 3.0 * std::numbers::pi * 1e-9; // sphere of radius 1e-3
  const double omega0 = std::sqrt(K / m);
  for (const double e : {0.5, 1.0}) {
    CAPTURE(e);
    const double l = std::log(e);
    const double zeta = -l / std::sqrt(l * l + std::numbers::pi * std::numbers::pi);
    const double tc = std::numbers::pi / (omega0 * std::sqrt(1 - zeta * zeta));
    const double dt = tc / 2000;
    const double bound = e < 1 ? 1.1 * 2 * zeta * omega0 * dt * e : 1e-6;
    const double v_ob = pushed(true, e, V, dt, K);
    const double v_plane = pushed(false, e, V, dt, K);
    INFO("v' = ", v_ob, " m/s, (1 + e) V = ", (1 + e) * V,
         ", relative to V: ", std::abs(v_ob / V - (1 + e)), " (bound ", bound,
         "); moving plane: ", v_plane);
    CHECK(std::abs(v_ob / V - (1 + e)) < bound);
    CHECK(std::abs(v_ob / v_plane - 1) < 1e-9);
  }
}

namespace {

/// A sphere (radius 1e-3 m, material 0) falls without gravity at 0.1 m/s onto triangle `t` of a
/// 2-triangle square obstacle whose triangles have materials 1 and 2 (per-triangle materials);
/// the pairs (0, 1) and (0, 2) have restitutions 0.5 and 0.8, the pair (0, 2) a stiffness of
/// 4e3 N/m instead of 1e3 N/m. Returns the rebound velocity over the impact velocity and the
/// wall materials seen by the contacts.
double triangle_restitution(int t, std::vector<std::uint32_t>& seen) {
  const double r = 1e-3, v0 = 0.1, K = 1e3;
  const double m = 2500.0 * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  const double l = std::log(0.8);
  const double zeta = -l / std::sqrt(l * l + std::numbers::pi * std::numbers::pi);
  // the shorter of the two contacts: k = 4e3 N/m, e = 0.8
  const double tc = std::numbers::pi / (std::sqrt(4.0 * K / m) * std::sqrt(1 - zeta * zeta));
  LsdSim::Params prm;
  prm.time_step = tc / 2000;
  prm.contact.normal.stiffness = K;
  prm.contact.normal.no_cohesion = false;
  LsdSim sim(prm);
  const auto ball = sim.add_material(material(0.9));
  const auto soft = sim.add_material(material(0.9));
  const auto stiff = sim.add_material(material(0.9));
  sim.set_pair(ball, soft, {.restitution = 0.5});
  sim.set_pair(ball, stiff, {.restitution = 0.8});
  LsdContact::Params p = prm.contact;
  p.normal.stiffness = 4.0 * K;
  sim.set_pair_parameters(ball, stiff, p);
  const walls::TriangleMesh square =
      moved(square2(), 0.01 * Eigen::Matrix3d::Identity(), Vec3::Zero());
  const auto ob = add_obstacle(sim, square, {.name = "two colours", .materials = {soft, stiff}});
  for (std::uint32_t k = 0; k < ob.count; ++k)
    seen.push_back(sim.walls()[ob.wall(k)].options.material);
  // triangle 0 is (0, 0)-(1, 0)-(1, 1) (y < x), triangle 1 is (0, 0)-(1, 1)-(0, 1)
  const Vec3 above = t == 0 ? Vec3(0.007, 0.002, 0.0) : Vec3(0.002, 0.007, 0.0);
  sim.add_particle({.position = above + Vec3(0, 0, r * (1 + 1e-12)),
                    .radius = r,
                    .material = ball,
                    .velocity = Vec3(0, 0, -v0)});
  bool touched = false;
  for (long s = 0; s < 100000; ++s) {
    sim.step();
    const bool touching = sim.contact_counts().second > 0;
    if (touching) touched = true;
    if (touched && !touching) break;
  }
  REQUIRE(touched);
  return sim.particles().velocity[0].z() / v0;
}

} // namespace

TEST_CASE("obstacle: each triangle contacts with the pair parameters of its own material") {
  // Linear spring-dashpot: the rebound is e v0 exactly in continuous time; the time stepping
  // (t_c/2000) errs by less than 1.1 n zeta omega0 dt e (n = 2): 1.9e-4 (e = 0.5, k = 1e3 N/m)
  // and 2.0e-4 (e = 0.8, k = 4e3 N/m). Tolerance 1e-3.
  std::vector<std::uint32_t> seen;
  const double e0 = triangle_restitution(0, seen);
  const double e1 = triangle_restitution(1, seen);
  MESSAGE("restitution over triangle 0: ", e0, " (pair 0.5), over triangle 1: ", e1, " (pair 0.8)");
  CHECK(seen == std::vector<std::uint32_t>{1, 2, 1, 2});
  CHECK(std::abs(e0 - 0.5) < 1e-3);
  CHECK(std::abs(e1 - 0.8) < 1e-3);
}
