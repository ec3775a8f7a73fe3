// Bodies of a body system inside a particle simulation (bodies/coupling.hpp): particles held by
// springs and ball joints while they collide, against closed forms.
//
// - A particle on a linear spring under gravity, released at the spring's natural length:
//   z(t) = -(m g / k)(1 - cos(omega t)), omega = sqrt(k/m): the lowest point is 2 m g / k below
//   the start (gravity counted once) and the period 2 pi / omega; with a damping ratio xi the
//   peaks decay by exp(-2 pi xi / sqrt(1 - xi^2)) a period. Velocity Verlet errs by
//   O((omega h)^2) on the period, and its dashpot lag changes the decrement by O(xi omega h).
// - Two equal spheres on ball joints (pendula of length L) in an elastic (undamped Hertz)
//   collision at the bottom of the swing exchange their velocities (Newton's cradle): the first
//   stops, the second leaves with v0 = sqrt(2 g L (1 - cos theta0)) and rises to the first's
//   starting height; the joints keep their lengths.
// - A sphere hanging on a spring and resting on a floor: at rest the spring, the floor and
//   gravity balance (the contact force reaches the body).
// - A converted (analytical) sphere leaves the contact problem: another sphere falls through
//   it, and it falls freely under the system's gravity.
#include "../approx.hpp"
#include "../errors.hpp"
#include "../support/tables.hpp"
#include <array>
#include <cmath>
#include <doctest/doctest.h>
#include <filesystem>
#include <grain/bodies.hpp>
#include <grain/bodies/coupling.hpp>
#include <grain/grain.hpp>
#include <grain/io/checkpoint.hpp>
#include <numbers>
#include <vector>

using namespace grain;
using grain::test::approx;
namespace gb = grain::bodies;

namespace {

constexpr double pi = std::numbers::pi;
constexpr double g0 = 9.81;
using Elastic = Interaction<normal::Hertz<>, tangent::None>;
using Sim = Simulation<Sphere, search::CellList, Elastic, stages<gb::Coupling>>;

const Material rubber{.name = "rubber",
                      .density = 1000,
                      .young = 1e7,
                      .poisson = 0.3,
                      .restitution = 1.0,
                      .friction = 0.0};

using grain::test::linear_table;

Sim make_sim(double h) {
  Sim::Params p;
  p.time_step = h;
  p.gravity = Vec3(0, 0, -g0);
  Sim sim(p);
  sim.add_material(rubber);
  return sim;
}

std::int64_t add_sphere(Sim& sim, const Vec3& x, double r, const Vec3& v = Vec3::Zero()) {
  ParticleSpec<3> s;
  s.position = x;
  s.radius = r;
  s.velocity = v;
  return sim.add_particle(s);
}

} // namespace

TEST_CASE("coupled bodies: a particle on a spring oscillates at sqrt(k/m) under gravity once") {
  const double r = 0.01, k = 100.0;
  const double m = rubber.density * 4.0 / 3.0 * pi * r * r * r;
  const double w = std::sqrt(k / m), T = 2 * pi / w;
  Sim sim = make_sim(T / 2000);
  const auto id = add_sphere(sim, Vec3(0, 0, 0), r);
  auto& c = sim.stage<gb::Coupling>();
  const auto b = c.attach(sim, id);
  c.system().add_spring({.spring = linear_table(k)}, static_cast<long>(b), Vec3::Zero(), gb::world,
                        Vec3(0, 0, 0.1));
  double z_min = 0.0, t_min = 0.0;
  sim.initialize();
  for (int n = 0; n < 1000 + 100; ++n) { // about half a period
    sim.step();
    const double z = sim.particles().position[0].z();
    if (z < z_min) {
      z_min = z;
      t_min = sim.time();
    }
  }
  // the lowest point, 2 m g / k below the start, at half a period (the step resolves the time)
  MESSAGE("spring: z_min / (2 m g / k) - 1 = " << -z_min / (2 * m * g0 / k) - 1
                                               << ", t_min - T/2 = " << t_min - T / 2 << " s");
  CHECK(-z_min == approx(2 * m * g0 / k).epsilon(1e-5));
  CHECK(std::abs(t_min - T / 2) <= sim.time_step());
  CHECK(c.particle_of(b) == id);

  SUBCASE("with a damping ratio the peaks decay at xi") {
    const double xi = 0.05;
    Sim s2 = make_sim(T / 2000);
    s2.set_gravity(Vec3::Zero());
    const auto id2 = add_sphere(s2, Vec3::Zero(), r, Vec3(0, 0, 0.3)); // launched upwards
    auto& c2 = s2.stage<gb::Coupling>();
    const auto b2 = c2.attach(s2, id2);
    c2.system().add_spring({.spring = linear_table(k), .damping_ratio = xi}, static_cast<long>(b2),
                           Vec3::Zero(), gb::world, Vec3(0, 0, 0.1));
    std::vector<double> peaks, times;
    double z1 = 0.0, z2 = 0.0;
    s2.initialize();
    for (int n = 0; n < 4 * 2000 + 10; ++n) {
      s2.step();
      const double z = s2.particles().position[0].z();
      if (n > 1 && z2 > z1 && z2 >= z) {
        peaks.push_back(z2);
        times.push_back(s2.time() - s2.time_step());
      }
      z1 = z2;
      z2 = z;
    }
    REQUIRE(peaks.size() >= 3);
    const double decrement = std::log(peaks[0] / peaks[2]) / 2;
    MESSAGE("damped spring: decrement / closed form - 1 = "
            << decrement / (2 * pi * xi / std::sqrt(1 - xi * xi)) - 1 << ", period error "
            << (times[2] - times[0]) / 2 / (2 * pi / (w * std::sqrt(1 - xi * xi))) - 1);
    CHECK(decrement == approx(2 * pi * xi / std::sqrt(1 - xi * xi)).epsilon(2e-3));
    const double wd = w * std::sqrt(1 - xi * xi);
    CHECK((times[2] - times[0]) / 2 == approx(2 * pi / wd).epsilon(1e-3));
  }
}

TEST_CASE("coupled bodies: Newton's cradle of two pendula on ball joints exchanges velocities") {
  const double r = 0.01, L = 0.2, theta0 = 0.3;
  Sim sim = make_sim(1e-5);
  // ball 2 hangs at rest at the origin, ball 1 is pulled back by theta0 on its circle
  const Vec3 pivot1(-2 * r, 0, L), pivot2(0, 0, L);
  const auto id2 = add_sphere(sim, Vec3(0, 0, 0), r);
  const auto id1 = add_sphere(sim, pivot1 + L * Vec3(-std::sin(theta0), 0, -std::cos(theta0)), r);
  auto& c = sim.stage<gb::Coupling>();
  const auto b1 = c.attach(sim, id1), b2 = c.attach(sim, id2);
  c.system().add_ball_joint(static_cast<long>(b1), pivot1);
  c.system().add_ball_joint(static_cast<long>(b2), pivot2);
  const double v0 = std::sqrt(2 * g0 * L * (1 - std::cos(theta0)));
  const double h0 = L * (1 - std::cos(theta0));
  const auto& bodies = c.system().bodies();
  bool touched = false, parted = false;
  double v_before = 0.0, z2_max = 0.0;
  Vec3 v1_after = Vec3::Zero(), v2_after = Vec3::Zero();
  sim.initialize();
  for (int n = 0; n < 60000; ++n) {
    const double v1 = bodies.velocity[b1].norm();
    sim.step();
    const double gap = (bodies.position[b2] - bodies.position[b1]).norm() - 2 * r;
    if (!touched && gap < 0) {
      touched = true;
      v_before = v1;
    }
    if (touched && !parted && gap > 0) {
      parted = true;
      v1_after = bodies.velocity[b1];
      v2_after = bodies.velocity[b2];
    }
    z2_max = std::max(z2_max, bodies.position[b2].z());
    if (parted && bodies.velocity[b2].z() < 0) break; // ball 2 at its highest point
  }
  REQUIRE(parted);
  MESSAGE("cradle: v_before/v0 - 1 = "
          << v_before / v0 - 1 << ", |v1_after|/v = " << v1_after.norm() / v_before
          << ", v2_after/v - 1 = " << v2_after.x() / v_before - 1
          << ", z2_max/h0 - 1 = " << z2_max / h0 - 1 << ", joint gaps "
          << c.system().joint_result(0).gap << ", " << c.system().joint_result(1).gap);
  CHECK(v_before == approx(v0).epsilon(1e-3));
  // the exchange: ball 1 stops, ball 2 takes its velocity (momentum m v to 1e-3)
  CHECK(v1_after.norm() / v_before < 2e-3);
  CHECK(v2_after.x() == approx(v_before).epsilon(2e-3)); // momentum m v passed on
  // ball 2 rises to ball 1's starting height, on its joint
  CHECK(z2_max == approx(h0).epsilon(2e-3));
  CHECK(c.system().joint_result(0).gap < 1e-10);
  CHECK(c.system().joint_result(1).gap < 1e-10);
  CHECK((bodies.position[b2] - pivot2).norm() == approx(L).epsilon(1e-10));
}

TEST_CASE("coupled bodies: spring, floor and gravity balance on a hanging sphere") {
  const double r = 0.01, k = 20.0;
  const double m = rubber.density * 4.0 / 3.0 * pi * r * r * r;
  Sim sim = make_sim(2e-5);
  sim.add_wall(walls::Plane{Vec3(0, 0, 0), Vec3(0, 0, 1)});
  // natural length reached 2 mm above the floor contact: the floor takes the rest of the weight
  const auto id = add_sphere(sim, Vec3(0, 0, r + 0.001), r);
  auto& c = sim.stage<gb::Coupling>();
  const auto b = c.attach(sim, id);
  c.system().add_spring({.spring = linear_table(k), .damping_ratio = 0.7}, static_cast<long>(b),
                        Vec3(0, 0, r + 0.001), gb::world, Vec3(0, 0, r + 0.003));
  sim.set_damping(0.03); // [N s/m]: settles the undamped contact (decay rate c/(2m) = 3.6/s)
  sim.run(2.0);
  REQUIRE(std::abs(sim.particles().velocity[0].z()) < 1e-10);  // at rest
  const double spring = c.system().spring_result(0).force.z(); // on the sphere, upwards
  const double floor = -sim.wall_force(0).z();                 // the wall's reaction on it
  CHECK(spring > 0.0);
  CHECK(floor > 0.0);
  CHECK(spring + floor == approx(m * g0).epsilon(1e-6));
  // the spring is stretched by the 1 mm gap plus the overlap delta, the floor pushes with
  // Hertz's 4/3 E* sqrt(r) delta^1.5, E* = E / (2 (1 - nu^2)) (sphere and wall of one material)
  const double delta = r - sim.particles().position[0].z();
  CHECK(spring == approx(k * (0.001 + delta)).epsilon(1e-9));
  const double e_star = rubber.young / (2 * (1 - rubber.poisson * rubber.poisson));
  CHECK(floor == approx(4.0 / 3.0 * e_star * std::sqrt(r) * std::pow(delta, 1.5)).epsilon(1e-6));
}

TEST_CASE("coupled bodies: a converted sphere leaves contact and falls freely") {
  const double r = 0.01;
  Sim sim = make_sim(1e-5);
  const auto a = add_sphere(sim, Vec3(0, 0, 0.1), r, Vec3(0.1, 0, 0));
  // 5 mm into it: a contact would throw it away
  const auto below = add_sphere(sim, Vec3(0, 0, 0.085), r);
  auto& c = sim.stage<gb::Coupling>();
  const auto b = c.convert(sim, a, {.mass = 0.5});
  CHECK(c.system().bodies().mass[b] == 0.5);
  CHECK(c.system().bodies().radius[b] == r); // shown by the body output
  CHECK(c.particle_of(b) == -1);
  CHECK(sim.size() == 1);
  CHECK(sim.removed_ids() == std::vector<std::int64_t>{a});
  CHECK_THROWS_AS(c.attach(sim, a), InputError);
  sim.steps(2000);
  const double t = sim.time();
  const Vec3 x = c.system().bodies().position[b];
  CHECK((x - Vec3(0.1 * t, 0, 0.1 - g0 * t * t / 2)).norm() < 1e-12);
  // the other sphere fell freely too: nothing pushed it
  const Vec3 y = sim.particles().position[sim.index_of(below)];
  CHECK((y - Vec3(0, 0, 0.085 - g0 * t * t / 2)).norm() < 1e-12);
}

TEST_CASE("coupled bodies: a step above the springs' critical step is rejected") {
  const double r = 0.01;
  Sim sim = make_sim(5e-5); // below the contacts' limit
  const auto id = add_sphere(sim, Vec3(0, 0, 0), r);
  auto& c = sim.stage<gb::Coupling>();
  const auto b = c.attach(sim, id);
  c.system().add_spring({.spring = linear_table(1e8)}, static_cast<long>(b), Vec3::Zero(),
                        gb::world, Vec3(0, 0, 0.1));
  const auto e = test::error_of([&] { sim.initialize(); });
  CHECK(test::has(e, "time_step = 5e-05"));
  CHECK(test::has(e, "critical step of the coupled body system"));
  CHECK_THROWS_AS(sim.steps(1), InputError);      // not run after all
  CHECK_THROWS_AS(c.attach(sim, id), InputError); // already a body
}

TEST_CASE("coupled bodies: an attached particle under a prescribed motion is refused") {
  // the body places its particle every step: a fixed velocity of the simulation on the same
  // particle would be dropped silently, so the run does not start
  const double r = 0.01;
  Sim sim = make_sim(1e-5);
  const auto id = add_sphere(sim, Vec3(0, 0, 0), r);
  add_sphere(sim, Vec3(0.1, 0, 0), r);
  auto& c = sim.stage<gb::Coupling>();
  c.attach(sim, id);
  sim.add_group("moved", {id});
  sim.fix_velocity("moved", Vec3(0.1, 0, 0));
  const auto e = test::error_of([&] { sim.steps(1); });
  CHECK(test::has(e, "Coupling: particle id = " + std::to_string(id)));
  CHECK(test::has(e, "prescribed motion or restraint"));
  CHECK(sim.time() == 0.0);
}

namespace {
/// A cradle of two pendula (ball joints) whose first ball also hangs on a damped spring; a
/// third, free sphere lies on a floor in the path of the second ball.
Sim cradle_with_spring() {
  const double r = 0.01, L = 0.2, theta0 = 0.3;
  Sim sim = make_sim(1e-5);
  sim.add_wall(walls::Plane{Vec3(0, 0, -r), Vec3(0, 0, 1)});
  const Vec3 pivot1(-2 * r, 0, L), pivot2(0, 0, L);
  const auto id2 = add_sphere(sim, Vec3(0, 0, 0), r);
  const auto id1 = add_sphere(sim, pivot1 + L * Vec3(-std::sin(theta0), 0, -std::cos(theta0)), r);
  add_sphere(sim, Vec3(2.2 * r + 0.01, 0, 0.0), r);
  auto& c = sim.stage<gb::Coupling>();
  const auto b1 = c.attach(sim, id1), b2 = c.attach(sim, id2);
  c.system().add_ball_joint(static_cast<long>(b1), pivot1);
  c.system().add_ball_joint(static_cast<long>(b2), pivot2);
  c.system().add_spring({.spring = linear_table(0.02), .damping_ratio = 0.1}, static_cast<long>(b1),
                        sim.particles().position[sim.index_of(id1)], gb::world, Vec3(-0.3, 0, 0.0));
  return sim;
}
} // namespace

TEST_CASE("coupled bodies: a checkpoint resumes bit for bit; another system is refused") {
  const auto path = std::filesystem::temp_directory_path() / "grain_coupling.ckpt";
  Sim a = cradle_with_spring(), b = cradle_with_spring(), never = cradle_with_spring();
  a.steps(23000); // through the collision of the pendula (at about 22400 steps)
  io::save_checkpoint(a, path.string());
  a.steps(6000); // ball 2 hits the free sphere
  io::load_checkpoint(b, path.string());
  b.steps(6000);
  never.steps(29000); // saving changes nothing either
  for (std::size_t i = 0; i < a.size(); ++i)
    CHECK(a.particles().position[i] == never.particles().position[i]);
  const auto& ba = a.stage<gb::Coupling>().system();
  const auto& bb = b.stage<gb::Coupling>().system();
  for (std::size_t k = 0; k < ba.bodies().size(); ++k) {
    CHECK(ba.bodies().position[k] == bb.bodies().position[k]);
    CHECK(ba.bodies().velocity[k] == bb.bodies().velocity[k]);
  }
  CHECK(ba.spring_result(0).total == bb.spring_result(0).total);
  CHECK(ba.time() == bb.time());
  for (std::size_t i = 0; i < a.size(); ++i) {
    CHECK(a.particles().position[i] == b.particles().position[i]);
    CHECK(a.particles().velocity[i] == b.particles().velocity[i]);
  }
  // the free sphere was hit: the comparison covers contacts of attached and free particles
  CHECK(a.particles().velocity[a.index_of(2)].x() > 1e-3);
  Sim other = cradle_with_spring();
  other.stage<gb::Coupling>().system().add_body(gb::sphere_body(0.01, 1000.0, Vec3(1, 1, 1)));
  CHECK(test::has(test::error_of([&] { io::load_checkpoint(other, path.string()); }),
                  "body system with 2 bodies"));
  std::filesystem::remove(path);
}

// An attached body without springs or joints moves exactly as the free particle it was: the
// contact forces see the velocities velocity Verlet predicts (a dashpot contact with e = 0.5
// on a floor), and a change of gravity between runs reaches both alike. The sums of the loads
// differ in rounding (contact + weight is split and added again), hence 1e-12.
TEST_CASE("coupled bodies: an attached body without springs moves as the free particle") {
  const double r = 0.01;
  auto drop = [&](bool attach) {
    Sim::Params p;
    p.time_step = 2e-6;
    p.gravity = Vec3(0, 0, -g0);
    Sim sim(p);
    Material m = rubber;
    m.restitution = 0.5;
    m.friction = 0.3;
    sim.add_material(m);
    sim.add_wall(walls::Plane{Vec3(0, 0, 0), Vec3(0, 0, 1)});
    ParticleSpec<3> s;
    s.position = Vec3(0, 0, r + 1e-4);
    s.radius = r;
    s.velocity = Vec3(0.2, 0, -0.5);
    s.omega = Vec3(0, 3, 0);
    const auto id = sim.add_particle(s);
    if (attach) sim.stage<gb::Coupling>().attach(sim, id);
    sim.steps(3000); // through the impact
    sim.set_gravity(Vec3(0, 0, -2 * g0));
    sim.steps(1000);
    const auto i = sim.index_of(id);
    return std::array<Vec3, 3>{sim.particles().position[i], sim.particles().velocity[i],
                               sim.particles().omega[i]};
  };
  const auto free = drop(false), body = drop(true);
  REQUIRE(free[1].z() > 0.0); // rebounded
  CHECK((body[0] - free[0]).norm() <= 1e-12 * free[0].norm());
  CHECK((body[1] - free[1]).norm() <= 1e-12 * free[1].norm());
  CHECK((body[2] - free[2]).norm() <= 1e-12 * free[2].norm());
  MESSAGE("attached vs free: velocity difference " << (body[1] - free[1]).norm() << " m/s");
}

// A re-initialisation between runs (sim.initialize(), also made by attach and convert) is a
// set-up, not a step: a body in free fall keeps v = -g t exactly (velocity Verlet is exact for
// a constant force; tolerance 1e-12 relative for the sums of h), and the system counts only the
// steps made.
TEST_CASE("coupled bodies: a re-initialisation between runs does not advance the bodies") {
  const double h = 1e-4;
  Sim sim = make_sim(h);
  const auto a = add_sphere(sim, Vec3(0, 0, 0), 0.01);
  const auto b = add_sphere(sim, Vec3(1, 0, 0), 0.01);
  auto& c = sim.stage<gb::Coupling>();
  const auto k = c.attach(sim, a);
  sim.steps(100);
  const auto& sys = c.system();
  CHECK(sys.step_count() == 100);
  CHECK(sys.bodies().velocity[k].z() == approx(-g0 * 100 * h).epsilon(1e-12));
  sim.initialize();
  c.attach(sim, b); // initialises again
  CHECK(sys.step_count() == 100);
  CHECK(sys.bodies().velocity[k].z() == approx(-g0 * 100 * h).epsilon(1e-12));
  sim.steps(100);
  CHECK(sys.step_count() == 200);
  CHECK(sys.bodies().velocity[k].z() == approx(-g0 * 200 * h).epsilon(1e-12));
  CHECK(sim.particles().velocity[sim.index_of(a)].z() == approx(-g0 * 200 * h).epsilon(1e-12));
}
