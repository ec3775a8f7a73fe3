// What a first grain program needs: parameter structs with tables that default-construct (and
// reject a table that was never given), a spring's rest length, a body's angular velocity in its
// own frame, and the Hertz contact time against a simulated head-on impact.
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

// ------------------------------------------------------------------ Hertz contact time

TEST_CASE("first program: the Hertz contact-time constant is 2 I (15/16)^(2/5)") {
  // I = int_0^1 dx / sqrt(1 - x^(5/2)) = sqrt(pi) Gamma(7/5) / Gamma(9/10)
  const double I = std::sqrt(pi) * std::tgamma(1.4) / std::tgamma(0.9);
  const double c_t = 2.0 * I * std::pow(15.0 / 16.0, 0.4);
  // E* = 1, R* = 1, m* = 1, v = 1: t_c = c_t
  CHECK(grain::normal::hertz_contact_time(1.0, 1.0, 1.0, 1.0) == approx(c_t).epsilon(1e-14));
  // Johnson (1985): 2.94 delta_max / v and 2.87 (m*^2 / (R* E*^2 v))^(1/5), to their 3 digits
  CHECK(std::abs(2.0 * I - 2.94) <= 5e-3);
  CHECK(std::abs(c_t - 2.87) <= 5e-3);
  // the same as the closed form the linear models use
  grain::PairProperties pair;
  pair.young_eff = 7e10;
  CHECK(grain::normal::hertz_contact_time(7e10, 1e-3, 2e-5, 0.7) ==
        approx(grain::normal::hertz_equivalent::hertz_contact_time(pair, 1e-3, 2e-5, 0.7))
            .epsilon(1e-15));
  CHECK(has(error_of([] { grain::normal::hertz_contact_time(7e10, 1e-3, 2e-5, 0.0); }),
            "normal::hertz_contact_time: v = 0 is invalid; valid range: (0, inf) m/s"));
  CHECK(has(error_of([] { grain::normal::hertz_contact_time(-1.0, 1e-3, 2e-5, 1.0); }),
            "normal::hertz_contact_time: young_eff = -1 is invalid; valid range: (0, inf) Pa"));
}

namespace {

using Undamped = grain::Interaction<grain::normal::Hertz<>, grain::tangent::None>;
using ImpactSim = grain::Simulation<grain::Sphere, grain::search::AllPairs, Undamped>;

grain::Material elastic(double young, double poisson, double density) {
  grain::Material m;
  m.young = young;
  m.poisson = poisson;
  m.density = density;
  m.restitution = 1.0; // Tsuji alpha = 0: no damping
  m.friction = 0.0;
  return m;
}

/// Head-on impact of a glass sphere (R = 1 mm) and a steel sphere (R = 1.5 mm) at the relative
/// normal velocity v; returns the simulated contact duration and the predicted t_c.
std::pair<double, double> impact_duration(double v) {
  const grain::Material glass = elastic(7.0e10, 0.22, 2500.0);
  const grain::Material steel = elastic(2.1e11, 0.29, 7850.0);
  const double r1 = 1.0e-3, r2 = 1.5e-3;
  const double m1 = glass.density * 4.0 / 3.0 * pi * r1 * r1 * r1;
  const double m2 = steel.density * 4.0 / 3.0 * pi * r2 * r2 * r2;
  const double e_eff = 1.0 / ((1.0 - glass.poisson * glass.poisson) / glass.young +
                              (1.0 - steel.poisson * steel.poisson) / steel.young);
  const double r_eff = r1 * r2 / (r1 + r2), m_eff = m1 * m2 / (m1 + m2);
  const double t_c = grain::normal::hertz_contact_time(e_eff, r_eff, m_eff, v);

  ImpactSim::Params params;
  params.time_step = t_c / 200.0; // about 200 steps in contact
  ImpactSim sim(params);
  const auto mg = sim.add_material(glass);
  const auto ms = sim.add_material(steel);
  grain::ParticleSpec<3> a, b;
  a.radius = r1;
  a.material = mg;
  a.velocity = Vec3(0.5 * v, 0.0, 0.0);
  b.position = Vec3(r1 + r2 + 3.37 * v * params.time_step, 0.0, 0.0); // touch after 3.37 steps
  b.radius = r2;
  b.material = ms;
  b.velocity = Vec3(-0.5 * v, 0.0, 0.0);
  const auto ia = sim.add_particle(a);
  const auto ib = sim.add_particle(b);
  const auto overlap = [&] {
    const auto& q = sim.particles();
    return r1 + r2 - (q.position[sim.index_of(ib)] - q.position[sim.index_of(ia)]).norm();
  };
  // contact from the zero crossing of the overlap before the first overlapping sample to the one
  // after the last, each interpolated linearly between the two samples around it
  double t_prev = sim.time(), d_prev = overlap(), t_on = -1.0, t_off = -1.0;
  for (int k = 0; k < 1000 && t_off < 0.0; ++k) {
    sim.step();
    const double t = sim.time(), d = overlap();
    if (d > 0.0 && d_prev <= 0.0) t_on = t_prev + (t - t_prev) * (-d_prev) / (d - d_prev);
    if (d <= 0.0 && d_prev > 0.0) t_off = t_prev + (t - t_prev) * d_prev / (d_prev - d);
    t_prev = t;
    d_prev = d;
  }
  REQUIRE(t_on >= 0.0);
  REQUIRE(t_off > t_on);
  return {t_off - t_on, t_c};
}

} // namespace

TEST_CASE(
    "first program: hertz_contact_time is the duration of a simulated undamped Hertz impact") {
  for (const double v : {0.1, 1.0, 5.0}) {
    const auto [simulated, predicted] = impact_duration(v);
    MESSAGE("v = " << v << " m/s: t_c = " << predicted << " s, simulated " << simulated
                   << " s, relative difference " << simulated / predicted - 1.0);
    CHECK(simulated == approx(predicted).epsilon(1e-2)); // 1 % (measured: -1.3e-5)
  }
}
