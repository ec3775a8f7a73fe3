// Clumps: mass properties of unions of spheres and disks against closed forms; a clump in free
// flight keeps its shape, its momentum follows gravity and its angular momentum is conserved; a
// clump colliding with a single sphere conserves momentum and angular momentum; a clump dropped on
// a plane lands as a rigid body and the plane takes the momentum it loses.
#include "../approx.hpp"
#include "../errors.hpp"
#include <cmath>
#include <doctest/doctest.h>
#include <filesystem>
#include <grain/clumps.hpp>
#include <grain/grain.hpp>
#include <grain/io/checkpoint.hpp>
#include <numbers>
#include <vector>

using namespace grain;
using grain::test::approx;

namespace {

constexpr double pi = std::numbers::pi;
using Contact3 = Interaction<normal::Hertz<>, tangent::Mindlin, rolling::Constant>;
using Contact2 = Interaction<normal::LinearSpringDashpot, tangent::SpringDashpotSlider>;
using Sim3 = Simulation<Sphere, search::CellList, Contact3, stages<Clumps<3>>>;
using Sim2 = Simulation<Disk, search::CellList, Contact2, stages<Clumps<2>>>;
const Material stone{.name = "stone",
                     .density = 2600,
                     .young = 5e7,
                     .poisson = 0.25,
                     .restitution = 0.5,
                     .friction = 0.5,
                     .rolling_friction = 0.01};

/// Volume of a spherical cap of height h cut from a sphere of radius r.
double cap(double r, double h) { return pi * h * h * (3 * r - h) / 3; }

/// Largest relative change of the member-to-member distances of clump c since `d0`.
template <class Sim, class Cl>
double shape_drift(const Sim& sim, const Cl& cl, std::size_t c, const std::vector<double>& d0) {
  const auto& ids = cl.member_ids(c);
  double worst = 0.0;
  std::size_t k = 0;
  for (std::size_t a = 0; a < ids.size(); ++a)
    for (std::size_t b = a + 1; b < ids.size(); ++b, ++k) {
      const double d = (sim.particles().position[sim.index_of(ids[a])] -
                        sim.particles().position[sim.index_of(ids[b])])
                           .norm();
      worst = std::max(worst, std::abs(d - d0[k]) / d0[k]);
    }
  return worst;
}
template <class Sim, class Cl>
std::vector<double> distances(const Sim& sim, const Cl& cl, std::size_t c) {
  const auto& ids = cl.member_ids(c);
  std::vector<double> d;
  for (std::size_t a = 0; a < ids.size(); ++a)
    for (std::size_t b = a + 1; b < ids.size(); ++b)
      d.push_back((sim.particles().position[sim.index_of(ids[a])] -
                   sim.particles().position[sim.index_of(ids[b])])
                      .norm());
  return d;
}

} // namespace

TEST_CASE("clump mass properties: unions of spheres and disks against closed forms") {
  // one sphere: V = 4/3 pi r^3, J = 2/5 m r^2
  const auto one = union_moments(std::vector<Vec3>{Vec3(0.1, -0.2, 0.3)}, {0.5});
  CHECK(one.measure == approx(4.0 / 3.0 * pi * 0.125).epsilon(1e-13));
  CHECK((one.centroid - Vec3(0.1, -0.2, 0.3)).norm() < 1e-14);
  CHECK(one.inertia(0, 0) == approx(0.4 * one.measure * 0.25).epsilon(1e-13));
  CHECK(std::abs(one.inertia(0, 1)) < 1e-15);

  // two equal spheres, centres 1.2 r apart on a tilted axis: V = 2 V_s - 2 V_cap, and the moments
  // about the axis and across it from the union's axisymmetric profile (1D quadrature)
  const double r = 1e-3, d = 1.2e-3;
  const Vec3 axis = Vec3(1, 2, -0.5).normalized();
  const auto two = union_moments(std::vector<Vec3>{Vec3::Zero(), d * axis}, {r, r});
  const double V = 2 * 4.0 / 3.0 * pi * r * r * r - 2 * cap(r, r - d / 2);
  CHECK(two.measure == approx(V).epsilon(1e-11));
  CHECK((two.centroid - 0.5 * d * axis).norm() < 1e-14 * r);
  double j_axis = 0.0, j_cross = 0.0;
  {
    // profile rho^2(s) = max(r^2 - s^2, r^2 - (s - d)^2), polynomial on [-r, d/2] and [d/2, d + r]
    const auto& [x, w] = detail::gauss_legendre<24>();
    for (auto [a, b] : {std::pair{-r, d / 2}, std::pair{d / 2, d + r}})
      for (int k = 0; k < 24; ++k) {
        const double s = 0.5 * (a + b) + 0.5 * (b - a) * x[k], ws = 0.5 * (b - a) * w[k];
        const double q = std::max(r * r - s * s, r * r - (s - d) * (s - d));
        j_axis += ws * 0.5 * pi * q * q;
        j_cross += ws * (0.25 * pi * q * q + pi * q * (s - d / 2) * (s - d / 2));
      }
  }
  const Vec3 across = axis.cross(Vec3::UnitZ()).normalized();
  CHECK(axis.dot(two.inertia * axis) == approx(j_axis).epsilon(1e-11));
  CHECK(across.dot(two.inertia * across) == approx(j_cross).epsilon(1e-11));
  // three spheres, pairwise overlapping, no triple overlap (the centre of the triangle is 1.04 r
  // from each): inclusion-exclusion by pairs
  const double s3 = 1.8e-3;
  const std::vector<Vec3> tri{Vec3(0, 0, 0), Vec3(s3, 0, 0),
                              Vec3(s3 / 2, s3 * std::sqrt(3.0) / 2, 0)};
  const auto three = union_moments(tri, {r, r, r});
  CHECK(three.measure ==
        approx(3 * 4.0 / 3.0 * pi * r * r * r - 6 * cap(r, r - s3 / 2)).epsilon(1e-11));

  // two disks: A = 2 pi r^2 - 2 (segment); polar moment of one disk pi r^4 / 2
  const auto disk = union_moments(std::vector<Vec2>{Vec2(0.3, 0.1)}, {0.2});
  CHECK(disk.measure == approx(pi * 0.04).epsilon(1e-13));
  CHECK(disk.inertia == approx(0.5 * pi * 0.2 * 0.2 * 0.2 * 0.2).epsilon(1e-13));
  const double th = 2 * std::acos(d / (2 * r));
  const auto pair2 = union_moments(std::vector<Vec2>{Vec2::Zero(), Vec2(0.6 * d, 0.8 * d)}, {r, r});
  CHECK(pair2.measure == approx(2 * pi * r * r - r * r * (th - std::sin(th))).epsilon(1e-13));

  // input errors
  using grain::test::error_of, grain::test::has;
  CHECK(has(error_of([] { (void)union_moments(std::vector<Vec3>{}, {}); }), "members = 0"));
  CHECK(has(error_of([] { (void)union_moments(std::vector<Vec3>{Vec3::Zero()}, {-1.0}); }),
            "radius = -1"));
  CHECK(has(error_of([] {
              (void)union_moments(std::vector<Vec3>{Vec3::Zero()}, {1.0, 2.0});
            }),
            "one radius per member"));
}

TEST_CASE("clump moments do not depend on where the clump is made") {
  // the same three spheres made at the origin and 10 km away: the same volume and inertia
  // (about the centroid) to 1e-8 relative (adding the offset rounds the centres by about
  // 1e-12 m, 1e-9 of the radii), the centroid moved by the offset. About a far origin,
  // int r r^T - V c c^T would lose all digits (eps |c|^2 / r^2 >> 1 here).
  const std::vector<double> r = {1e-3, 1e-3, 0.8e-3};
  const std::vector<Vec3> c = {Vec3(0, 0, 0), Vec3(1.5e-3, 0, 0), Vec3(0.7e-3, 1.2e-3, 0.3e-3)};
  const Vec3 far(1e4, -2e4, 5e3);
  std::vector<Vec3> moved;
  for (const auto& x : c)
    moved.push_back(x + far);
  const auto a = union_moments(c, r), b = union_moments(moved, r);
  CHECK(b.measure == approx(a.measure).epsilon(1e-8));
  CHECK((b.inertia - a.inertia).norm() <= 1e-8 * a.inertia.norm());
  CHECK((b.centroid - far - a.centroid).norm() <= 1e-9 * 1e-3); // round-off of |far| ~ 1e-12 m
}

TEST_CASE("clumps: free flight keeps the shape, follows gravity and conserves angular momentum") {
  Sim3::Params prm;
  prm.gravity = Vec3(0, 0, -9.81);
  prm.time_step = 1e-5;
  Sim3 sim(prm);
  const auto m = sim.add_material(stone);
  const auto shape = clump_shape(
      std::vector<Vec3>{Vec3(0, 0, 0), Vec3(1.2e-3, 0, 0), Vec3(0.4e-3, 1.1e-3, 0.2e-3)},
      {1e-3, 0.8e-3, 0.9e-3}, Sphere{});
  auto& cl = sim.stage<Clumps<3>>();
  const auto c = cl.add(sim, shape,
                        {.position = Vec3(0, 0, 1),
                         .velocity = Vec3(0.2, -0.1, 1.0),
                         .omega = Vec3(30, -50, 80),
                         .material = m});
  // members' masses add up to the clump's, which comes from the union (overlaps once)
  double members = 0.0;
  for (auto id : cl.member_ids(c))
    members += sim.particles().mass[sim.index_of(id)];
  CHECK(members == approx(cl.mass(c)).epsilon(1e-14));
  CHECK(cl.mass(c) == approx(stone.density * shape.moments.measure).epsilon(1e-15));
  sim.initialize();
  const auto d0 = distances(sim, cl, c);
  const Vec3 P0 = cl.momentum(c), L0 = cl.spin(c);
  const double e0 = cl.kinetic_energy();
  sim.steps(5000);
  const double t = sim.time();
  INFO("shape drift ", shape_drift(sim, cl, c, d0));
  CHECK(shape_drift(sim, cl, c, d0) < 1e-12);
  CHECK((cl.momentum(c) - (P0 + cl.mass(c) * prm.gravity * t)).norm() < 1e-12 * P0.norm());
  CHECK((cl.spin(c) - L0).norm() < 1e-12 * L0.norm());
  // the rotational energy of a torque-free asymmetric body: O(h^2), no drift
  const double rot0 = e0 - 0.5 * P0.squaredNorm() / cl.mass(c);
  const double rot = cl.kinetic_energy() - 0.5 * cl.momentum(c).squaredNorm() / cl.mass(c);
  CHECK(rot == approx(rot0).epsilon(1e-5));
  // members move with the clump
  const auto& p = sim.particles();
  for (auto id : cl.member_ids(c)) {
    const auto i = sim.index_of(id);
    CHECK((p.velocity[i] - cl.point_velocity(c, p.position[i])).norm() < 1e-12);
  }
}

TEST_CASE("clumps: a clump hits a single sphere; momentum and angular momentum are conserved") {
  Sim3::Params prm;
  prm.time_step = 2e-7;
  Sim3 sim(prm);
  const auto m = sim.add_material(stone);
  const auto shape =
      clump_shape(std::vector<Vec3>{Vec3(0, 0, 0), Vec3(1.5e-3, 0, 0)}, {1e-3, 1e-3}, Sphere{});
  auto& cl = sim.stage<Clumps<3>>();
  const auto c = cl.add(sim, shape,
                        {.position = Vec3(0, 0, 0),
                         .velocity = Vec3(0.5, 0, 0),
                         .omega = Vec3(0, 0, 20),
                         .material = m});
  const auto ball =
      sim.add_particle({.position = Vec3(3.2e-3, 0.6e-3, 0.2e-3), .radius = 1e-3, .material = m});
  sim.initialize();
  const auto& p = sim.particles();
  auto total_p = [&] {
    return Vec3(cl.momentum(c) + p.mass[sim.index_of(ball)] * p.velocity[sim.index_of(ball)]);
  };
  auto total_l = [&] {
    const auto b = sim.index_of(ball);
    return Vec3(cl.spin(c) + cl.position(c).cross(cl.momentum(c)) + p.inertia[b] * p.omega[b] +
                p.position[b].cross(p.mass[b] * p.velocity[b]));
  };
  const Vec3 P0 = total_p(), L0 = total_l();
  const auto d0 = distances(sim, cl, c);
  bool touched = false;
  for (int k = 0; k < 40000; ++k) {
    sim.step();
    touched = touched || p.velocity[sim.index_of(ball)].norm() > 0;
  }
  REQUIRE(touched);
  CHECK(sim.contact_counts().first == 0); // apart again (and the members never touch each other)
  INFO("ball velocity ", p.velocity[sim.index_of(ball)].transpose());
  CHECK((total_p() - P0).norm() < 1e-12 * P0.norm());
  CHECK((total_l() - L0).norm() < 1e-10 * L0.norm());
  CHECK(shape_drift(sim, cl, c, d0) < 1e-12);
}

TEST_CASE("clumps: a dumbbell dropped on a plane lands lying and the plane takes its momentum") {
  Sim3::Params prm;
  prm.gravity = Vec3(0, 0, -9.81);
  prm.time_step = 2e-6;
  Sim3 sim(prm);
  const auto m = sim.add_material(stone);
  const auto floor = sim.add_wall(walls::Plane{Vec3::Zero(), Vec3::UnitZ()}, {.material = m});
  const double r = 1e-3;
  const auto shape =
      clump_shape(std::vector<Vec3>{Vec3(-0.8 * r, 0, 0), Vec3(0.8 * r, 0, 0)}, {r, r}, Sphere{});
  auto& cl = sim.stage<Clumps<3>>();
  // tilted by 30 degrees about y, spinning a little
  const Eigen::Matrix3d tilt = Eigen::AngleAxisd(pi / 6, Vec3::UnitY()).toRotationMatrix();
  const auto c = cl.add(sim, shape,
                        {.position = Vec3(0, 0, 4 * r),
                         .rotation = tilt,
                         .velocity = Vec3(0.05, 0, 0),
                         .omega = Vec3(0, 0, 5),
                         .material = m});
  sim.initialize();
  const auto d0 = distances(sim, cl, c);
  const Vec3 P0 = cl.momentum(c);
  Vec3 impulse = Vec3::Zero();
  double worst_shape = 0.0;
  const long n = 100000; // 0.2 s
  for (long k = 0; k < n; ++k) {
    sim.step();
    impulse += sim.wall_force(floor) * prm.time_step;
    if (k % 1000 == 0) worst_shape = std::max(worst_shape, shape_drift(sim, cl, c, d0));
  }
  const double t = sim.time();
  CHECK(worst_shape < 1e-12);
  // velocity Verlet applies the force of the last step for half a step only (the first one was 0)
  impulse -= 0.5 * sim.wall_force(floor) * prm.time_step;
  // momentum balance: dP = M g t - (impulse on the plane)
  const Vec3 dP = cl.momentum(c) - P0;
  INFO("dP ", dP.transpose(), " M g t - J ", (cl.mass(c) * prm.gravity * t - impulse).transpose());
  CHECK((dP - (cl.mass(c) * prm.gravity * t - impulse)).norm() < 1e-9 * cl.mass(c) * 9.81 * t);
  // at rest, lying: both members on the plane, the axis horizontal, the centroid at about r
  CHECK(cl.kinetic_energy() < 1e-9 * cl.mass(c) * 9.81 * r);
  const auto& p = sim.particles();
  for (auto id : cl.member_ids(c))
    CHECK(p.position[sim.index_of(id)].z() == approx(r).epsilon(5e-3));
  CHECK(cl.position(c).z() == approx(r).epsilon(5e-3));
  // the plane carries the clump's weight
  CHECK(sim.wall_force(floor).z() == approx(-cl.mass(c) * 9.81).epsilon(1e-6));
}

TEST_CASE("clumps in 2D: disks and sphere-mass disks") {
  for (bool sphere_mass : {false, true}) {
    Sim2::Params prm;
    prm.time_step = 1e-5;
    prm.gravity = Vec2(0, -9.81);
    Sim2 sim(prm, Disk{.thickness = 2e-3, .sphere_mass = sphere_mass});
    const auto m = sim.add_material(stone);
    const auto shape =
        clump_shape(std::vector<Vec2>{Vec2(0, 0), Vec2(1.5e-3, 0), Vec2(0.7e-3, 1.2e-3)},
                    {1e-3, 1e-3, 0.8e-3}, sim.shape());
    auto& cl = sim.stage<Clumps<2>>();
    const auto c = cl.add(sim, shape,
                          {.position = Vec2(0, 0.1),
                           .rotation = 0.3,
                           .velocity = Vec2(0.3, 0.5),
                           .omega = 40.0,
                           .material = m});
    sim.initialize();
    const auto d0 = distances(sim, cl, c);
    const double L0 = cl.spin(c);
    const Vec2 P0 = cl.momentum(c);
    sim.steps(3000);
    CHECK(shape_drift(sim, cl, c, d0) < 1e-12);
    CHECK(cl.spin(c) == approx(L0).epsilon(1e-13));
    CHECK((cl.momentum(c) - (P0 + cl.mass(c) * prm.gravity * sim.time())).norm() <
          1e-12 * P0.norm());
    // a sphere-mass disk clump has the moments of the union of spheres
    if (sphere_mass)
      CHECK(cl.mass(c) == approx(stone.density *
                                 union_moments(std::vector<Vec3>{Vec3(0, 0, 0), Vec3(1.5e-3, 0, 0),
                                                                 Vec3(0.7e-3, 1.2e-3, 0)},
                                               {1e-3, 1e-3, 0.8e-3})
                                     .measure)
                              .epsilon(1e-13));
    else
      CHECK(cl.mass(c) == approx(stone.density * 2e-3 *
                                 union_moments(std::vector<Vec2>{Vec2(0, 0), Vec2(1.5e-3, 0),
                                                                 Vec2(0.7e-3, 1.2e-3)},
                                               {1e-3, 1e-3, 0.8e-3})
                                     .measure)
                              .epsilon(1e-13));
  }
}

TEST_CASE("clumps: a shape made by hand without shares or inertia is refused") {
  // ClumpShape is a plain struct: one filled in by hand must have a share per member summing to
  // 1 and (2D) a positive moment of inertia, or the members' masses would be read past the end
  Sim2::Params prm;
  prm.time_step = 1e-5;
  Sim2 sim(prm, Disk{.thickness = 2e-3});
  const auto m = sim.add_material(stone);
  auto& cl = sim.stage<Clumps<2>>();
  ClumpShape<2> s;
  s.offsets = {Vec2(0, 0)};
  s.radii = {1e-3};
  s.moments.measure = 3.14e-6;
  auto e = test::error_of([&] { cl.add(sim, s, {.material = m, .name = "hand"}); });
  CHECK(test::has(e, "Clump 'hand': shares = 0 is invalid; valid range: 1 (one per member"));
  s.share = {0.5};
  e = test::error_of([&] { cl.add(sim, s, {.material = m, .name = "hand"}); });
  CHECK(test::has(e, "Clump 'hand': sum of the shares = 0.5 is invalid"));
  s.share = {1.0};
  e = test::error_of([&] { cl.add(sim, s, {.material = m, .name = "hand"}); });
  CHECK(test::has(e, "Clump 'hand': moment of inertia = 0 is invalid; valid range: (0, inf)"));
  CHECK(cl.size() == 0);
  CHECK(sim.size() == 0);
}

TEST_CASE("clumps: a checkpoint resumes bit for bit; a different clump count is refused") {
  auto setup = [](Sim3& sim, int clumps) {
    const auto m = sim.add_material(stone);
    sim.add_wall(walls::Plane{Vec3::Zero(), Vec3::UnitZ()}, {.material = m});
    const auto shape =
        clump_shape(std::vector<Vec3>{Vec3(0, 0, 0), Vec3(1.4e-3, 0, 0)}, {1e-3, 0.9e-3}, Sphere{});
    for (int k = 0; k < clumps; ++k)
      sim.stage<Clumps<3>>().add(sim, shape,
                                 {.position = Vec3(3e-3 * k, 0, 2e-3 + 1e-3 * k),
                                  .omega = Vec3(10, 5 * k, -3),
                                  .material = m});
  };
  Sim3::Params prm;
  prm.gravity = Vec3(0, 0, -9.81);
  prm.time_step = 2e-6;
  Sim3 a(prm);
  setup(a, 3);
  a.steps(3000);
  const std::string path = (std::filesystem::temp_directory_path() / "grain_clumps.ckp").string();
  io::save_checkpoint(a, path);
  Sim3 b(prm);
  setup(b, 3);
  io::load_checkpoint(b, path);
  a.steps(2000);
  b.steps(2000);
  for (std::size_t i = 0; i < a.size(); ++i)
    CHECK((a.particles().position[i] - b.particles().position[i]).norm() == 0.0);
  for (std::size_t c = 0; c < 3; ++c)
    CHECK((a.stage<Clumps<3>>().omega(c) - b.stage<Clumps<3>>().omega(c)).norm() == 0.0);
  Sim3 wrong(prm);
  setup(wrong, 2);
  CHECK(grain::test::has(grain::test::error_of([&] { io::load_checkpoint(wrong, path); }),
                         "clumps = 3"));
  std::filesystem::remove(path);
}
