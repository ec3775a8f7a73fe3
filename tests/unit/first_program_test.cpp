// What a first grain program needs: parameter structs with tables that default-construct (and
// reject a table that was never given), a spring's rest length, and a body's angular velocity in
// its own frame.
#include "../approx.hpp"
#include "../errors.hpp"
#include <grain/bodies/rigid_body.hpp>
#include <grain/bodies/spring.hpp>
#include <grain/bodies/system.hpp>
#include <grain/bodies/torsion_spring.hpp>
#include <grain/bodies/unspring.hpp>
#include <grain/grain.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <type_traits>
#include <vector>

namespace gb = grain::bodies;
using grain::Table;
using grain::Vec3;
using grain::test::approx;
using grain::test::error_of;
using grain::test::has;

namespace {

constexpr double pi = std::numbers::pi;

/// The message every owner gives for the empty table: "<object>: <name> = Table (no points) is
/// invalid; valid range: a Table of at least 2 points (...)".
std::string not_given(const std::string& object, const std::string& name) {
  return object + ": " + name +
         " = Table (no points) is invalid; valid range: a Table of at least 2 points";
}

} // namespace

// ------------------------------------------------------------------ tables not yet given

// every parameter struct with a Table member (grep "Table" in include/grain)
static_assert(std::is_default_constructible_v<Table>);
static_assert(std::is_default_constructible_v<gb::SpringParams>);
static_assert(std::is_default_constructible_v<gb::TorsionLaw>);
static_assert(std::is_default_constructible_v<gb::TorsionSpringParams>);
static_assert(std::is_default_constructible_v<gb::UnspringRule>);
static_assert(std::is_default_constructible_v<grain::VariableProperty>);

TEST_CASE("first program: a default-constructed spring takes its table later and works") {
  gb::SpringParams sp; // compiles: the table is empty until given
  sp.spring = Table({-1.0, 1.0}, {-100.0, 100.0});
  sp.geometry = gb::SpringGeometry::constant_direction;
  sp.direction = Vec3::UnitX();
  gb::SpringState st = gb::init_spring(sp, gb::SpringKinematics{});
  gb::SpringKinematics k;
  k.p2 = Vec3(0.01, 0.0, 0.0);
  const gb::SpringResult r = gb::evaluate(sp, st, k, 0.0, 1e-3, 1.0);
  CHECK(r.elastic == approx(1.0).epsilon(1e-14)); // 100 N/m x 0.01 m
}

TEST_CASE("first program: the empty table is NaN and a given table is unchanged") {
  const Table empty;
  CHECK(empty.empty());
  CHECK(empty.size() == 0);
  CHECK(std::isnan(empty(0.0)));
  std::size_t hint = 0;
  CHECK(std::isnan(empty(0.0, hint)));
  CHECK(std::isnan(empty.x_front()));
  CHECK(std::isnan(empty.x_back()));

  // a table assigned over the placeholder interpolates and holds its end values as before
  Table t;
  t = Table({0.0, 1.0, 2.0}, {20.0, 80.0, 80.0}, "ramp");
  CHECK_FALSE(t.empty());
  CHECK(t(0.5) == approx(50.0).epsilon(1e-15));
  CHECK(t(-1.0) == 20.0);
  CHECK(t(3.0) == 80.0);
  CHECK(t.label() == "Table 'ramp'");
  // a table made from points is still validated when it is made
  CHECK(has(error_of([] { Table(std::vector<double>{0.0}, std::vector<double>{1.0}); }),
            "Table: number of points = 1 is invalid; valid range: [2, inf)"));
}

TEST_CASE("first program: every object that takes a table rejects one that was never given") {
  gb::SpringParams sp;
  CHECK(has(error_of([&] { gb::validate(sp); }),
            not_given("SPRING", "spring") + " (the force-stroke table f(s) must be given)"));
  CHECK(has(error_of([&] { gb::init_spring(sp, gb::SpringKinematics{}); }),
            not_given("SPRING", "spring")));
  gb::BodySystem sys;
  sys.add_body(gb::RigidBody{});
  CHECK(has(error_of([&] { sys.add_spring(sp, 0, Vec3::Zero(), gb::world, Vec3::UnitX()); }),
            not_given("SPRING 0", "spring")));

  sp.spring = Table({-1.0, 1.0}, {-1.0, 1.0});
  sp.dashpot = Table{};
  CHECK(has(error_of([&] { gb::validate(sp); }), not_given("SPRING", "dashpot")));
  sp.dashpot.reset();
  sp.unload = Table{};
  CHECK(has(error_of([&] { gb::validate(sp); }), not_given("SPRING", "unload")));

  gb::TorsionSpringParams tp;
  tp.pitch.spring = Table{};
  CHECK(has(error_of([&] { gb::validate(tp); }), not_given("TORSION_SPRING", "pitch.spring")));
  tp.pitch.spring.reset();
  tp.yaw.dashpot = Table{};
  CHECK(has(error_of([&] { gb::validate(tp); }), not_given("TORSION_SPRING", "yaw.dashpot")));

  gb::UnspringRule rule{.tsprings = {0}, .msprings = {0}, .max = 1.0, .unload = {{0, Table{}}}};
  CHECK(has(error_of([&] { gb::Unspring u(std::move(rule), 1); }),
            not_given("UNSPRING", "unload[0]")));

  CHECK(has(error_of([] { grain::TimeFunction::table(Table{}); }),
            not_given("TimeFunction::table", "table")));

  grain::VariableProperty vp;
  vp.table = std::make_shared<const Table>();
  CHECK(has(error_of([&] { vp.validate(); }), "table = Table (no points) is invalid"));
}

// ------------------------------------------------------------------ spring rest length

TEST_CASE("first program: a spring created away from its rest length gives the table's force at "
          "length minus rest length") {
  // nonlinear table f(s) [m -> N]
  const Table f({-1.0, 0.0, 0.1, 0.5}, {-50.0, 0.0, 10.0, 100.0});
  const double l0 = 1.0, created = 1.2; // rest length and length at creation [m]
  gb::SpringParams p{.spring = f, .rest_length = l0};
  gb::SpringKinematics k;
  k.p2 = Vec3(0.0, created, 0.0);
  gb::SpringState st = gb::init_spring(p, k);
  CHECK(st.stroke0 == l0);
  CHECK(st.stroke == approx(created - l0).epsilon(1e-14));
  CHECK(gb::initial_stroke(p, k) == l0);
  for (const double length : {1.2, 1.05, 1.0, 0.9, 1.4, 0.3}) {
    k.p2 = Vec3(0.0, length, 0.0);
    const gb::SpringResult r = gb::evaluate(p, st, k, 0.0, 1e-3, 1.0);
    CAPTURE(length);
    CHECK(r.length == approx(length).epsilon(1e-15));
    CHECK(r.stroke == approx(length - l0).epsilon(1e-13).scale(1.0)); // seed: e . d - stroke0
    CHECK(r.elastic == approx(f(length - l0)).epsilon(1e-12).scale(1.0));
    // tension (f > 0) pulls point 1 towards point 2: +y
    CHECK(r.force.y() == approx(f(length - l0)).epsilon(1e-12).scale(1.0));
  }

  // the same force as Parmec's spring (stroke from the creation length) with the constant stroke
  // offset l0 - created
  gb::SpringParams parmec{.spring = f, .offset = grain::TimeFunction(l0 - created)};
  k.p2 = Vec3(0.0, created, 0.0);
  gb::SpringState sq = gb::init_spring(parmec, k);
  st = gb::init_spring(p, k);
  for (const double length : {1.2, 1.1, 0.95, 1.3}) {
    k.p2 = Vec3(0.0, length, 0.0);
    const gb::SpringResult a = gb::evaluate(p, st, k, 0.0, 1e-3, 1.0);
    const gb::SpringResult b = gb::evaluate(parmec, sq, k, 0.0, 1e-3, 1.0);
    CAPTURE(length);
    CHECK(a.elastic == approx(b.elastic).epsilon(1e-12).scale(1.0));
    CHECK(b.stroke == approx(length - created).epsilon(1e-13).scale(1.0));
  }

  // constant direction: the signed length c . d, rest length of either sign
  gb::SpringParams c{.spring = f,
                     .geometry = gb::SpringGeometry::constant_direction,
                     .direction = Vec3(0.0, 0.0, 2.0),
                     .rest_length = -0.2};
  k.p2 = Vec3(0.3, 0.0, -0.1);
  gb::SpringState sc = gb::init_spring(c, k);
  const gb::SpringResult rc = gb::evaluate(c, sc, k, 0.0, 1e-3, 1.0);
  CHECK(rc.stroke == approx(0.1).epsilon(1e-14));
  CHECK(rc.elastic == approx(f(0.1)).epsilon(1e-14));
}

TEST_CASE("first program: a mass released on a spring away from its rest length oscillates about "
          "the rest length") {
  // mass m at the origin, a linear spring k to the fixed point (L_c, 0, 0) with rest length L0:
  // x(t) = (L_c - L0)(1 - cos w t), so the length runs between L_c and 2 L0 - L_c
  const double m = 2.0, k = 800.0, l0 = 1.0, lc = 1.2, w = std::sqrt(k / m), T = 2.0 * pi / w;
  gb::BodySystem s;
  gb::RigidBody b;
  b.mass = m;
  b.inertia = Eigen::Matrix3d::Identity() * 1e-3;
  s.add_body(b);
  s.add_spring({.spring = Table({-10.0, 10.0}, {-10.0 * k, 10.0 * k}), .rest_length = l0}, 0,
               Vec3::Zero(), gb::world, Vec3(lc, 0.0, 0.0));
  double lmin = lc, lmax = 0.0, sum = 0.0;
  long n = 0;
  s.run(T, T / 4000.0, [&](const gb::BodySystem& sys) {
    const double length = lc - sys.bodies().position[0].x();
    lmin = std::min(lmin, length);
    lmax = std::max(lmax, length);
    sum += length;
    ++n;
  });
  const double amplitude = lc - l0;
  MESSAGE("shortest length - (2 L0 - L_c) = "
          << lmin - (2.0 * l0 - lc) << " m, longest - L_c = " << lmax - lc
          << " m, mean - L0 = " << sum / double(n) - l0 << " m");
  // sampled extremes and mean within 1e-5 of the amplitude 0.2 m (velocity Verlet at
  // w h = 2 pi / 4000: amplitude and phase errors of order (w h)^2 = 2.5e-6)
  CHECK(std::abs(lmin - (2.0 * l0 - lc)) <= 1e-5 * amplitude);
  CHECK(std::abs(lmax - lc) <= 1e-5 * amplitude);
  CHECK(std::abs(sum / double(n) - l0) <= 1e-5 * amplitude); // the mean over one period is L0
}

TEST_CASE("first program: rest_length is checked") {
  gb::SpringParams p{.spring = Table({-1.0, 1.0}, {-1.0, 1.0}), .rest_length = -0.5};
  CHECK(has(error_of([&] { gb::validate(p); }),
            "SPRING: rest_length = -0.5 is invalid; valid range: [0, inf) m"));
  p.rest_length = std::numeric_limits<double>::quiet_NaN();
  p.geometry = gb::SpringGeometry::constant_direction;
  p.direction = Vec3::UnitX();
  CHECK(has(error_of([&] { gb::validate(p); }),
            "SPRING: rest_length = nan is invalid; valid range: a finite length [m]"));
  p.rest_length = 0.1;
  p.geometry = gb::SpringGeometry::point_to_plane;
  CHECK(has(error_of([&] { gb::validate(p); }),
            "SPRING: rest_length = 0.1 is invalid; valid range: none for the point_to_plane "
            "geometry"));
}

// ------------------------------------------------------------------ angular velocity, body frame

TEST_CASE("first program: local_omega gives the angular velocity in the body's own frame") {
  // a body whose inertia is not diagonal in its reference frame (principal axes != reference
  // axes), turned by a known rotation; spatial omega = Lambda Omega for a chosen Omega
  const Eigen::Matrix3d lambda = (Eigen::AngleAxisd(0.7, Vec3(1.0, 2.0, 2.0).normalized()) *
                                  Eigen::AngleAxisd(-1.1, Vec3::UnitZ()))
                                     .toRotationMatrix();
  const Vec3 omega_body(0.3, -2.0, 5.0);
  gb::RigidBodies bodies;
  gb::RigidBody b;
  b.inertia = gb::inertia_tensor(2.0, 3.0, 4.0, 0.3, -0.2, 0.1);
  b.rotation = lambda;
  b.omega = lambda * omega_body;
  const std::size_t i = bodies.add(b);
  const Vec3 got = gb::local_omega(bodies, i);
  CHECK((got - omega_body).norm() <= 1e-14 * omega_body.norm());
  CHECK((gb::rotation(bodies, i) * got - bodies.omega[i]).norm() <= 1e-14 * omega_body.norm());

  // rotation about a principal axis stays steady: omega and Omega are constant, and the body
  // turns by w t about the world axis Lambda0 e_z (dLambda/dt = Lambda [Omega]x)
  gb::RigidBody spin;
  spin.inertia = Eigen::Vector3d(1.0, 2.0, 3.0).asDiagonal();
  spin.rotation = lambda;
  const double w = 5.0, t = 0.4;
  spin.omega = lambda * Vec3(0.0, 0.0, w);
  const std::size_t j = bodies.add(spin);
  gb::clear_forces(bodies);
  for (int step = 0; step < 400; ++step)
    gb::step(bodies, t / 400.0, [](gb::RigidBodies&) {});
  CHECK((gb::local_omega(bodies, j) - Vec3(0.0, 0.0, w)).norm() <= 1e-12 * w);
  const Eigen::Matrix3d expected =
      Eigen::AngleAxisd(w * t, lambda * Vec3::UnitZ()).toRotationMatrix() * lambda;
  CHECK((gb::rotation(bodies, j) - expected).cwiseAbs().maxCoeff() <= 1e-12);

  // the particles of a 3D simulation: orientation R (body axes -> world) and spatial omega
  grain::ParticleArrays<3> p;
  p.orientation.push_back(Eigen::Quaterniond(lambda));
  p.omega.push_back(lambda * omega_body);
  CHECK((gb::local_omega(p, 0) - omega_body).norm() <= 1e-14 * omega_body.norm());
}
