// User stages, per-particle fields, wall loads and the contact frame.
//
// Stages: hooks run in the documented order; a stage that adds a body force reproduces the
// closed-form free flight and a gravity run; the servo stage of the servo2d example holds a
// target stress. Fields follow their particles through re-sorting, removal, creation and a
// checkpoint. Wall loads: the impulse a wall receives equals the particle's momentum change,
// the walls of a bed at rest carry its weight, the torque on a wall balances its force's moment.
// Contact frame: orthonormal, right-handed, and the local components rebuild the global force.
#include "../../examples/servo_wall.hpp"
#include "../approx.hpp"
#include <cmath>
#include <doctest/doctest.h>
#include <filesystem>
#include <grain/grain.hpp>
#include <grain/io/checkpoint.hpp>
#include <limits>
#include <random>
#include <string>
#include <vector>

using namespace grain;
using grain::test::approx;

namespace {

using Contact2 = Interaction<normal::LinearSpringDashpot, tangent::SpringDashpotSlider>;
using Contact3 = Interaction<normal::Hertz<>, tangent::Mindlin, rolling::Constant>;
const Material glass{.name = "glass",
                     .density = 2500,
                     .young = 5e7,
                     .poisson = 0.25,
                     .restitution = 0.5,
                     .friction = 0.4,
                     .rolling_friction = 0.02};

/// Records the order in which its hooks run.
struct Recorder {
  std::vector<std::string> calls;
  template <class Sim>
  void initialize(Sim&) {
    calls.push_back("initialize");
  }
  template <class Sim>
  void begin_step(Sim&) {
    calls.push_back("begin_step");
  }
  template <class Sim>
  void before_search(Sim&) {
    calls.push_back("before_search");
  }
  template <class Sim>
  void after_forces(Sim&) {
    calls.push_back("after_forces");
  }
  template <class Sim>
  void end_of_step(Sim& sim) {
    calls.push_back("end_of_step t=" + std::to_string(sim.step_count()));
  }
};

/// Adds a constant body force per unit mass (an extra gravity) after the forces.
template <int D>
struct BodyForce {
  Vec<D> acceleration = Vec<D>::Zero(); // [m/s^2]
  template <class Sim>
  void after_forces(Sim& sim) {
    auto& p = sim.particles();
    for (std::size_t i = 0; i < p.size(); ++i)
      p.force[i] += p.mass[i] * acceleration;
  }
};

/// A field that remembers which particle it belongs to.
struct Owner {
  std::int64_t id = -1;
};
/// A stage that needs a field: counts the steps each particle has lived through.
struct Age {
  long value = 0;
};
struct Ageing {
  using fields = grain::fields<Age>;
  template <class Sim>
  void end_of_step(Sim& sim) {
    for (auto& a : sim.template field<Age>())
      ++a.value;
  }
};

/// A periodic stage's payload: records the step and time of each run.
struct Sampler {
  std::vector<long> steps;
  std::vector<double> times;
  long initialized = 0;
  template <class Sim>
  void initialize(Sim&) {
    ++initialized;
  }
  template <class Sim>
  void run(Sim& sim) {
    steps.push_back(sim.step_count());
    times.push_back(sim.time());
  }
  template <class Archive>
  void serialize(Archive& ar) {
    ar(steps, times);
  }
};

} // namespace

TEST_CASE("periodic stages: by steps, by simulated time, by wall-clock time, with a limit") {
  using Sim = Simulation<Disk, search::CellList, Contact2, stages<periodic<Sampler>>>;
  auto make = [] {
    Sim::Params prm;
    prm.time_step = 3e-5; // below the Rayleigh time of the 1 mm glass disk, 3.8e-5 s
    Sim sim(prm);
    const auto m = sim.add_material(glass);
    sim.add_particle({.position = Vec2(0, 0), .radius = 1e-3, .material = m});
    return sim;
  };
  SUBCASE("every 7 steps: at steps 7, 14, ..., 49 of 50") {
    Sim sim = make();
    auto& ps = sim.stage<periodic<Sampler>>();
    ps.every_steps = 7;
    sim.steps(50);
    CHECK(ps.stage.steps == std::vector<long>{7, 14, 21, 28, 35, 42, 49});
    CHECK(ps.runs() == 7);
    CHECK(ps.stage.initialized == 1);
  }
  SUBCASE("every 1e-4 s at a 3e-5 s step: the first step at or after each instant, once each") {
    Sim sim = make();
    auto& ps = sim.stage<periodic<Sampler>>();
    ps.every_time = 1e-4;
    sim.steps(100); // t = 3e-3 s: 30 instants
    REQUIRE(ps.runs() == 30);
    for (std::size_t k = 0; k < ps.stage.times.size(); ++k) {
      const double instant = 1e-4 * static_cast<double>(k + 1);
      CAPTURE(k);
      CHECK(ps.stage.times[k] >= instant - 1e-16);
      CHECK(ps.stage.times[k] - 3e-5 < instant);
    }
  }
  SUBCASE("steps and time together: a run when either is due, once per step") {
    Sim sim = make();
    auto& ps = sim.stage<periodic<Sampler>>();
    ps.every_steps = 5;
    ps.every_time = 1.2e-4; // = 4 steps
    sim.steps(20);
    // steps 5, 10, 15, 20 and 4, 8, 12, 16, 20 (step 20 once)
    CHECK(ps.stage.steps == std::vector<long>{4, 5, 8, 10, 12, 15, 16, 20});
  }
  SUBCASE("a wall-clock period: never within a long period, at every step with a tiny one") {
    Sim sim = make();
    auto& ps = sim.stage<periodic<Sampler>>();
    ps.every_wall = 1e9;
    sim.steps(20);
    CHECK(ps.runs() == 0);
    ps.every_wall = 1e-300;
    sim.steps(20);
    CHECK(ps.runs() == 20);
  }
  SUBCASE("at_start and max_runs") {
    Sim sim = make();
    auto& ps = sim.stage<periodic<Sampler>>();
    ps.every_steps = 2;
    ps.at_start = true;
    ps.max_runs = 3;
    sim.steps(20);
    CHECK(ps.stage.steps == std::vector<long>{0, 2, 4});
  }
  SUBCASE("a checkpoint keeps the schedule: a restarted run runs at the same steps") {
    Sim sim = make();
    sim.stage<periodic<Sampler>>().every_steps = 7;
    sim.steps(23);
    const std::string path =
        (std::filesystem::temp_directory_path() / "grain_periodic.ckp").string();
    io::save_checkpoint(sim, path);
    sim.steps(27);
    Sim back = make();
    back.stage<periodic<Sampler>>().every_steps = 7;
    io::load_checkpoint(back, path);
    std::filesystem::remove(path);
    back.steps(27);
    CHECK(back.stage<periodic<Sampler>>().stage.steps ==
          sim.stage<periodic<Sampler>>().stage.steps);
    CHECK(back.stage<periodic<Sampler>>().runs() == 7);
  }
  SUBCASE("no period, or a bad one, is refused when the run starts") {
    Sim sim = make();
    CHECK_THROWS_WITH_AS(sim.steps(1), doctest::Contains("every_steps, every_time, every_wall"),
                         InputError);
    sim.stage<periodic<Sampler>>().every_time = -1.0;
    CHECK_THROWS_WITH_AS(sim.steps(1), doctest::Contains("every_time"), InputError);
  }
}

TEST_CASE("stages: hooks run in loop order, once per step") {
  using Sim = Simulation<Disk, search::CellList, Contact2, stages<Recorder, BodyForce<2>>>;
  Sim sim;
  const auto m = sim.add_material(glass);
  sim.add_particle({.position = Vec2(0, 0), .radius = 1e-3, .material = m});
  sim.steps(2);
  const std::vector<std::string> expected{
      "after_forces",    "initialize", "begin_step",    "before_search", "after_forces",
      "end_of_step t=1", "begin_step", "before_search", "after_forces",  "end_of_step t=2"};
  CHECK(sim.stage<Recorder>().calls == expected);
}

TEST_CASE("stages: a body force added after the forces gives the closed-form free flight") {
  // velocity Verlet is exact for a constant force: x = x0 + v0 t + a t^2 / 2
  using Sim = Simulation<Sphere, search::CellList, Contact3, stages<BodyForce<3>>>;
  Sim::Params prm;
  prm.time_step = 1e-5;
  Sim sim(prm);
  const auto m = sim.add_material(glass);
  const Vec3 x0(0.1, 0.2, 0.3), v0(1.0, -2.0, 0.5), a(3.0, -9.81, 1.5);
  sim.add_particle({.position = x0, .radius = 1e-3, .material = m, .velocity = v0});
  sim.stage<BodyForce<3>>().acceleration = a;
  sim.steps(1000);
  const double t = sim.time();
  const Vec3 x = x0 + v0 * t + 0.5 * a * t * t, v = v0 + a * t;
  for (int d = 0; d < 3; ++d) {
    CHECK(sim.particles().position[0][d] == approx(x[d]).epsilon(1e-12));
    CHECK(sim.particles().velocity[0][d] == approx(v[d]).epsilon(1e-12));
  }
}

TEST_CASE("stages: a weight added by a stage bounces like gravity") {
  // a sphere dropped on a plane: the same rebound with gravity or with the stage's weight
  // (the sums are in a different order, so the bits may differ: 1e-9 relative)
  auto drop = [](auto sim) {
    const auto m = sim.add_material(glass);
    sim.add_wall(walls::Plane{Vec3::Zero(), Vec3::UnitZ()}, {.material = m});
    sim.add_particle({.position = Vec3(0, 0, 2e-3),
                      .radius = 1e-3,
                      .material = m,
                      .velocity = Vec3(0.1, 0, -0.5)});
    double lowest = 1.0;
    for (int k = 0; k < 4000; ++k) {
      sim.step();
      lowest = std::min(lowest, sim.particles().position[0].z());
    }
    return std::array<double, 3>{lowest, sim.particles().velocity[0].z(),
                                 sim.particles().omega[0].y()};
  };
  using WithGravity = Simulation<Sphere, search::CellList, Contact3>;
  using WithStage = Simulation<Sphere, search::CellList, Contact3, stages<BodyForce<3>>>;
  WithGravity::Params pg;
  pg.time_step = 2e-6;
  pg.gravity = Vec3(0, 0, -9.81);
  WithStage::Params ps;
  ps.time_step = 2e-6;
  WithStage staged(ps);
  staged.stage<BodyForce<3>>().acceleration = Vec3(0, 0, -9.81);
  const auto a = drop(WithGravity(pg));
  const auto b = drop(std::move(staged));
  INFO("lowest ", a[0], " vs ", b[0], "; v_z ", a[1], " vs ", b[1]);
  CHECK(a[0] < 1e-3); // it touched the plane
  CHECK(a[1] > 0.0);  // and rebounded
  for (int k = 0; k < 3; ++k)
    CHECK(b[k] == approx(a[k]).epsilon(1e-9));
}

TEST_CASE("fields: follow their particles through sorting, removal, creation and checkpoints") {
  using Sim = Simulation<Disk, search::CellList, Contact2, fields<Owner>, stages<Ageing>>;
  Sim::Params prm;
  prm.gravity = Vec2(0, -9.81);
  prm.max_start_overlap = std::numeric_limits<double>::infinity(); // a random, overlapping pile
  Sim sim(prm, Disk{.sphere_mass = true});
  const auto m = sim.add_material(glass);
  const double L = 0.03;
  sim.add_wall(walls::Segment{Vec2(0, 0), Vec2(L, 0)}, {.material = m});
  sim.add_wall(walls::Segment{Vec2(0, 0), Vec2(0, 2 * L)}, {.material = m});
  sim.add_wall(walls::Segment{Vec2(L, 0), Vec2(L, 2 * L)}, {.material = m});
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 150; ++k)
    sim.add_particle({.position = Vec2(L * (0.05 + 0.9 * u(rng)), 2 * L * (0.05 + 0.9 * u(rng))),
                      .radius = 5e-4 + 3e-4 * u(rng),
                      .material = m,
                      .velocity = Vec2(u(rng) - 0.5, u(rng) - 0.5)});
  // late particles (new field values F{}) and a sink that removes some
  for (int k = 0; k < 10; ++k)
    sim.add_particle({.position = Vec2(L * (0.1 + 0.08 * k), 1.9 * L),
                      .radius = 5e-4,
                      .material = m,
                      .creation_time = 0.02});
  sim.add_sink(regions::Box<2>{Vec2(0, 0), Vec2(0.3 * L, 0.3 * L)}, 0.03, 0.031);
  sim.initialize();
  for (std::size_t i = 0; i < sim.size(); ++i)
    sim.field<Owner>()[i].id = sim.particles().id[i];
  const long rebuilds0 = sim.counters().rebuilds;
  sim.run(0.05);
  const auto& p = sim.particles();
  CHECK(sim.counters().rebuilds > rebuilds0 + 5); // re-sorted many times
  CHECK(sim.removed_ids().size() > 0);
  CHECK(sim.field<Owner>().size() == p.size());
  std::size_t late = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const bool born_late = p.id[i] >= 150;
    late += born_late;
    CHECK(sim.field<Owner>()[i].id == (born_late ? -1 : p.id[i]));
    // every step of its life: the early ones all steps, the late ones those since 0.02 s
    const long steps = sim.field<Age>()[i].value;
    if (born_late)
      CHECK(steps < sim.step_count() * 0.61);
    else
      CHECK(steps == sim.step_count());
  }
  CHECK(late == 10);

  const std::string path = (std::filesystem::temp_directory_path() / "grain_fields.ckp").string();
  io::save_checkpoint(sim, path);
  Sim back(prm, Disk{.sphere_mass = true});
  back.add_material(glass);
  for (const auto& w : sim.walls())
    back.add_wall(w.geometry, w.options);
  io::load_checkpoint(back, path);
  std::filesystem::remove(path);
  REQUIRE(back.size() == sim.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    CHECK(back.field<Owner>()[i].id == sim.field<Owner>()[i].id);
    CHECK(back.field<Age>()[i].value == sim.field<Age>()[i].value);
  }
}

TEST_CASE("wall loads: the impulse on a wall is the particle's momentum change") {
  // an oblique impact with friction and rolling resistance on a plane at an angle: the wall
  // force summed over the steps (times dt) is minus the particle's momentum change, and the
  // torque about the wall's pivot minus the change of the particle's angular momentum about it
  using Sim = Simulation<Sphere, search::CellList, Contact3>;
  Sim::Params prm;
  prm.time_step = 1e-6;
  Sim sim(prm);
  const auto m = sim.add_material(glass);
  const Vec3 n = Vec3(0.2, -0.1, 1.0).normalized();
  const auto w = sim.add_wall(walls::Plane{Vec3(0.01, 0.02, 0.0), n},
                              {.material = m, .has_pivot = true, .pivot = Vec3(0.05, -0.03, 0.0)});
  const double R = 1e-3;
  const Vec3 x0 = Vec3(0.01, 0.02, 0.0) + 1.001 * R * n;
  sim.add_particle({.position = x0,
                    .radius = R,
                    .material = m,
                    .velocity = Vec3(0.3, 0.2, -0.4) - 0.6 * n,
                    .omega = Vec3(50, -20, 10)});
  sim.initialize();
  const auto& p = sim.particles();
  const Vec3 c = sim.walls()[w].pivot;
  auto momentum = [&] { return Vec3(p.mass[0] * p.velocity[0]); };
  auto angular = [&] {
    return Vec3(p.inertia[0] * p.omega[0] + (p.position[0] - c).cross(p.mass[0] * p.velocity[0]));
  };
  const Vec3 P0 = momentum(), L0 = angular();
  Vec3 impulse = Vec3::Zero(), angular_impulse = Vec3::Zero();
  bool touched = false;
  for (int k = 0; k < 3000; ++k) {
    sim.step();
    // velocity Verlet: the force of a step acts half in this step's kick and half in the next;
    // the particle starts and ends free, so the plain sum is the whole impulse
    impulse += sim.wall_force(w) * prm.time_step;
    angular_impulse += sim.wall_torque(w) * prm.time_step;
    touched = touched || sim.wall_force(w).norm() > 0;
  }
  REQUIRE(touched);
  REQUIRE(sim.wall_force(w).norm() == 0.0); // free again
  const Vec3 dP = momentum() - P0, dL = angular() - L0;
  INFO("impulse ", impulse.transpose(), " dP ", dP.transpose());
  CHECK((impulse + dP).norm() < 1e-10 * dP.norm());
  INFO("angular impulse ", angular_impulse.transpose(), " dL ", dL.transpose());
  CHECK((angular_impulse + dL).norm() < 1e-9 * dL.norm());
}

TEST_CASE("wall loads and the servo stage: a bed pressed to a target stress") {
  // the servo2d example in small: 96 disks, a lid driven by ServoWall<2>; at rest the lid holds
  // the target stress (0.5 %) and the walls together carry the weight of the bed (1e-3)
  using Sim = Simulation<Disk, search::CellList, Contact2, stages<ServoWall<2>>>;
  Sim::Params prm;
  prm.gravity = Vec2(0, -9.81);
  prm.damping_translational = 0.0;
  Sim sim(prm, Disk{.sphere_mass = true});
  const auto m = sim.add_material(glass);
  const double s = 2.5e-3, width = 8 * s, lid_y = 13 * s;
  sim.add_wall(walls::Segment{Vec2(0, 0), Vec2(width, 0)}, {.material = m});
  sim.add_wall(walls::Segment{Vec2(0, 0), Vec2(0, 2 * lid_y)}, {.material = m});
  sim.add_wall(walls::Segment{Vec2(width, 0), Vec2(width, 2 * lid_y)}, {.material = m});
  const auto lid =
      sim.add_wall(walls::Segment{Vec2(0, lid_y), Vec2(width, lid_y)}, {.material = m});
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double weight = 0.0;
  for (int j = 0; j < 12; ++j)
    for (int i = 0; i < 8; ++i) {
      const double r = 0.8e-3 + 0.4e-3 * u(rng);
      sim.add_particle({.position = Vec2((i + 0.5) * s + 1e-4 * (u(rng) - 0.5), (j + 0.5) * s),
                        .radius = r,
                        .material = m});
      weight += sim.particles().mass.back() * 9.81;
    }
  auto& servo = sim.stage<ServoWall<2>>();
  servo.wall = lid;
  servo.area = width * 2e-3;
  servo.target = 1e4;
  servo.gain = 1e-5;
  servo.max_speed = 0.1;
  sim.run(0.2);
  // over the last 0.02 s: the largest stress error, and the wall forces averaged over the steps
  // (rattlers bounce in their cages: the walls carry the weight on average)
  double worst = 0.0;
  Vec2 mean = Vec2::Zero();
  const long n = std::lround(0.02 / sim.time_step());
  for (long k = 0; k < n; ++k) {
    sim.step();
    worst = std::max(worst, std::abs(servo.stress - servo.target) / servo.target);
    Vec2 sum = Vec2::Zero(), net = Vec2::Zero();
    for (std::size_t w = 0; w < sim.walls().size(); ++w)
      sum += sim.wall_force(w);
    for (std::size_t i = 0; i < sim.size(); ++i)
      net += sim.particles().force[i];
    mean += sum / static_cast<double>(n);
    // the bookkeeping: the particles feel their weight and minus the wall forces, nothing else
    REQUIRE((net - Vec2(0, -weight) + sum).norm() < 1e-12 * weight);
  }
  INFO("stress error ", worst, "; mean wall forces ", mean.transpose(), " weight ", weight,
       "; kinetic energy ", sim.kinetic_energy());
  CHECK(worst < 5e-3);
  CHECK(std::abs(mean.x()) < 1e-3 * weight);
  CHECK(mean.y() == approx(-weight).epsilon(1e-3));
}

TEST_CASE("contact frame: orthonormal, right-handed, and local components rebuild the force") {
  using Sim = Simulation<Sphere, search::CellList, Contact3>;
  Sim::Params prm;
  prm.gravity = Vec3(0, 0, -100.0);                                // settles in 0.03 s
  prm.max_start_overlap = std::numeric_limits<double>::infinity(); // a random, overlapping pile
  Sim sim(prm);
  const auto m = sim.add_material(glass);
  const double L = 0.01;
  for (int d = 0; d < 3; ++d) {
    sim.add_wall(walls::Plane{Vec3::Zero(), Vec3::Unit(d)}, {.material = m});
    sim.add_wall(walls::Plane{Vec3::Constant(L), -Vec3::Unit(d)}, {.material = m});
  }
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 200; ++k)
    sim.add_particle({.position = Vec3(L * (0.1 + 0.8 * u(rng)), L * (0.1 + 0.8 * u(rng)),
                                       L * (0.1 + 0.8 * u(rng))),
                      .radius = 4e-4 + 2e-4 * u(rng),
                      .material = m,
                      .velocity = Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5)});
  sim.run(0.03);
  std::size_t count = 0, walls_seen = 0, sliding = 0;
  double worst = 0.0;
  sim.for_each_contact([&](const Sim::ContactViewType& c) {
    ++count;
    walls_seen += c.wall;
    const auto& f = c.frame;
    worst = std::max({worst, std::abs(f.normal.norm() - 1), std::abs(f.tangent1.norm() - 1),
                      std::abs(f.tangent2.norm() - 1), std::abs(f.normal.dot(f.tangent1)),
                      std::abs(f.normal.dot(f.tangent2)), std::abs(f.tangent1.dot(f.tangent2)),
                      (f.tangent1.cross(f.tangent2) - f.normal).norm()});
    CHECK((f.normal - c.geometry.normal).norm() == 0.0);
    const Vec3 local = c.force_local();
    const double scale = c.force().norm();
    CHECK((f.to_global(local) - c.force()).norm() <= 1e-14 * scale);
    // the normal component is the repulsion (n points from i to its partner)
    CHECK(local[0] == approx(-c.result.normal.force).epsilon(1e-12).scale(scale));
    // the tangential components are those of the friction force
    CHECK(std::hypot(local[1], local[2]) ==
          approx(c.result.tangent.force.norm()).epsilon(1e-12).scale(scale));
    const Vec3 t = c.torque_i_local();
    CHECK((f.to_global(t) - c.result.torque_i).norm() <=
          1e-14 * (c.result.torque_i.norm() + 1e-30));
    // model data: the tangential spring's state after this evaluation; a sliding contact
    // carries the Coulomb force mu F_n
    CHECK(c.data.tangent.sliding == c.result.tangent.sliding);
    if (c.data.tangent.sliding) {
      ++sliding;
      CHECK(c.result.tangent.force.norm() ==
            approx(glass.friction * std::max(c.result.normal.force, 0.0)).epsilon(1e-12));
    }
  });
  CHECK(sliding > 0);
  CHECK(count > 200);
  CHECK(walls_seen > 0);
  CHECK(worst < 1e-14);
}

TEST_CASE("contact frame in 2D: the tangent is the normal turned by +90 degrees") {
  for (double a : {0.0, 0.7, 2.0, -2.5, 3.14159}) {
    const Vec2 n(std::cos(a), std::sin(a));
    const auto f = ContactFrame<2>::from_normal(n);
    CHECK(cross(f.normal, f.tangent) == approx(1.0).epsilon(1e-15));
    const Vec2 v(0.3, -1.7);
    CHECK((f.to_global(f.to_local(v)) - v).norm() < 1e-15);
  }
  // continuous across the horizontal plane and at the vertical (the frame's one discontinuity is
  // at n = -(1, 2, 3)/sqrt(14))
  for (const Vec3& n0 : {Vec3(1, 0, 0), Vec3(0.6, -0.8, 0), Vec3(0, 0, 1), Vec3(0, 0, -1)}) {
    const Vec3 e = n0.unitOrthogonal();
    const auto a = ContactFrame<3>::from_normal((n0 + 1e-9 * e).normalized());
    const auto b = ContactFrame<3>::from_normal((n0 - 1e-9 * e).normalized());
    CHECK((a.tangent1 - b.tangent1).norm() < 1e-8);
    CHECK((a.tangent2 - b.tangent2).norm() < 1e-8);
  }
  // 3D frames near the poles and the equator
  for (const Vec3& n : {Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(1, 0, 0), Vec3(0, -1, 0),
                        Vec3(1e-9, 0, -1).normalized(), Vec3(0.3, -0.4, 0.5).normalized()}) {
    const auto f = ContactFrame<3>::from_normal(n);
    CHECK((f.tangent1.cross(f.tangent2) - n).norm() < 1e-15);
    CHECK(std::abs(f.tangent1.dot(n)) < 1e-15);
  }
}

TEST_CASE("wall loads: bad wall index") {
  using Sim = Simulation<Disk, search::CellList, Contact2>;
  Sim sim;
  sim.add_material(glass);
  std::string what;
  try {
    (void)sim.wall_force(3);
  } catch (const InputError& e) {
    what = e.what();
  }
  CHECK(what.find("wall index 3") != std::string::npos);
  CHECK(what.find("[0, 0)") != std::string::npos);
}

namespace {
/// A stage that throws in after_forces of the step that ends at step `at` (the particles have
/// already drifted in that step).
struct ThrowAt {
  long at = -1;
  template <class Sim>
  void after_forces(Sim& sim) {
    if (sim.step_count() + 1 == at) throw std::runtime_error("stage failed");
  }
};
} // namespace

TEST_CASE("stages: an exception inside a step refuses stepping and saving until a load") {
  using Sim = Simulation<Disk, search::CellList, Contact2, stages<ThrowAt>>;
  auto make = [] {
    Sim sim({.time_step = 1e-5, .gravity = Vec2(0, -9.81)});
    const auto m = sim.add_material(glass);
    sim.add_particle({.position = Vec2(0, 0), .radius = 1e-3, .material = m});
    return sim;
  };
  const std::string path =
      (std::filesystem::temp_directory_path() / "grain_interrupted.ckp").string();
  Sim sim = make();
  sim.steps(3);
  io::save_checkpoint(sim, path);
  sim.stage<ThrowAt>().at = 6;
  CHECK_THROWS_WITH_AS(sim.steps(5), "stage failed", std::runtime_error);
  // the particle drifted in step 6, the time did not advance: part of a step
  CHECK(sim.interrupted());
  CHECK(sim.step_count() == 5);
  CHECK_THROWS_WITH_AS(sim.step(), doctest::Contains("interrupted by an exception"), InputError);
  CHECK_THROWS_WITH_AS(io::save_checkpoint(sim, path + "2"),
                       doctest::Contains("grain::io::save_checkpoint"), InputError);
  // loading a checkpoint continues from whole steps, as an uninterrupted run
  sim.stage<ThrowAt>().at = -1;
  io::load_checkpoint(sim, path);
  CHECK_FALSE(sim.interrupted());
  sim.steps(5);
  Sim straight = make();
  straight.steps(8);
  CHECK(sim.particles().position[0] == straight.particles().position[0]);
  CHECK(sim.particles().velocity[0] == straight.particles().velocity[0]);
  std::filesystem::remove(path);
}

TEST_CASE("stages: an exception between steps leaves whole steps") {
  // a damping function that turns negative is found before the step moves anything
  using Sim = Simulation<Disk, search::CellList, Contact2>;
  auto make = [] {
    Sim sim({.time_step = 1e-5, .gravity = Vec2(0, -9.81)});
    const auto m = sim.add_material(glass);
    sim.add_particle({.position = Vec2(0, 0), .radius = 1e-3, .material = m});
    sim.set_damping(TimeFunction::linear(1e-4, -1.0), TimeFunction::constant(0.0));
    return sim;
  };
  Sim sim = make();
  CHECK_THROWS_AS(sim.steps(20), InputError);
  CHECK_FALSE(sim.interrupted());
  // the state is that of whole steps: the same as a run of step_count() steps
  const long n = sim.step_count();
  CHECK(n >= 9);
  Sim whole = make();
  whole.steps(n);
  CHECK(sim.particles().position[0] == whole.particles().position[0]);
  CHECK(sim.particles().velocity[0] == whole.particles().velocity[0]);
}
