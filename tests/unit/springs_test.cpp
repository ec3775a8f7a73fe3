// Translational springs, unspring rules and torsion springs: oscillation and damping against
// closed forms, the hysteresis loop against hand-computed values and area, the geometries,
// friction, rule firing and activation, torsion angles, and input validation.
#include "../approx.hpp"
#include "../errors.hpp"
#include "../support/tables.hpp"
#include <cmath>
#include <cstddef>
#include <doctest/doctest.h>
#include <functional>
#include <grain/bodies/spring.hpp>
#include <grain/bodies/torsion_spring.hpp>
#include <grain/bodies/unspring.hpp>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

using namespace grain;
using namespace grain::bodies;
using grain::test::approx;

namespace {

constexpr double pi = std::numbers::pi;

using grain::test::error_of;
using grain::test::has;

using grain::test::linear_table;

/// A spring along x between the origin (point 1) and (s, 0, 0) (point 2), created at s = 0.
struct Driven {
  SpringParams p;
  SpringState st;
  explicit Driven(SpringParams params) : p(std::move(params)) {
    p.geometry = SpringGeometry::constant_direction;
    p.direction = Vec3::UnitX();
    st = init_spring(p, SpringKinematics{});
  }
  SpringResult at(double s, double t = 0.0) {
    SpringKinematics k;
    k.p2 = Vec3(s, 0.0, 0.0);
    return evaluate(p, st, k, t, 1e-3, 1.0);
  }
  /// Moves from the current stroke to s in n equal increments; calls f(stroke, force) each step.
  double go(double s, int n = 2000, const std::function<void(double, double)>& f = {}) {
    const double s0 = st.stroke;
    double force = 0.0;
    for (int i = 1; i <= n; ++i) {
      const double si = i == n ? s : s0 + (s - s0) * i / n;
      force = at(si).elastic;
      if (f) f(si, force);
    }
    return force;
  }
};

/// Zero up-crossings of x(t), linearly interpolated.
struct Crossings {
  std::vector<double> t;
  double x_prev = 0.0, t_prev = 0.0;
  bool first = true;
  void add(double time, double x) {
    if (!first && x_prev < 0.0 && x >= 0.0)
      t.push_back(t_prev + (time - t_prev) * (-x_prev) / (x - x_prev));
    first = false;
    x_prev = x;
    t_prev = time;
  }
  double period() const { return (t.back() - t.front()) / double(t.size() - 1); }
};

/// A point mass m on a linear spring of stiffness k to a fixed point, integrated by velocity
/// Verlet (the damping force uses v(t) predicted as v(t - h/2) + a(t - h) h / 2). Returns the
/// measured period and the decay rate ln(x_1 / x_n) / (t_n - t_1) of the displacement maxima.
std::pair<double, double> oscillate(double m, double k, double xi, double h, double duration) {
  SpringParams p{.spring = linear_table(k), .damping_ratio = xi};
  SpringKinematics kin;
  kin.p1 = Vec3::Zero();
  kin.p2 = Vec3(1.0, 0.0, 0.0);
  SpringState st = init_spring(p, kin); // rest length 1
  double x = -0.05, v = 0.0, t = 0.0;
  const auto force = [&](double xv, double vv) {
    kin.p1 = Vec3(xv, 0.0, 0.0);
    kin.v1 = Vec3(vv, 0.0, 0.0);
    return evaluate(p, st, kin, t, h, m).force.x();
  };
  double a = force(x, v) / m;
  Crossings c;
  std::vector<std::pair<double, double>> peaks;
  double v_old = v;
  while (t < duration) {
    v += 0.5 * h * a;
    x += h * v;
    t += h;
    a = force(x, v + 0.5 * h * a) / m;
    v += 0.5 * h * a;
    c.add(t, x);
    if (v_old > 0.0 && v <= 0.0) peaks.emplace_back(t - h * v / (v - v_old), x);
    v_old = v;
  }
  const double rate = std::log(peaks.front().second / peaks.back().second) /
                      (peaks.back().first - peaks.front().first);
  return {c.period(), rate};
}

} // namespace

TEST_CASE("spring: a linear spring and a point mass oscillate at sqrt(k/m), damped at xi") {
  const double m = 2.0, k = 800.0, w = std::sqrt(k / m); // 20 rad/s
  const double T = 2.0 * pi / w;
  {
    const auto [period, rate] = oscillate(m, k, 0.0, T / 10000.0, 10.5 * T);
    MESSAGE("undamped period relative error: ", std::abs(period - T) / T, ", decay rate ", rate);
    // velocity Verlet's period error is about (w h)^2 / 24 = 1.6e-8 here
    CHECK(period == approx(T).epsilon(1e-6));
    CHECK(std::abs(rate) < 1e-6 * w);
  }
  {
    const double xi = 0.05;
    const auto [period, rate] = oscillate(m, k, xi, T / 10000.0, 10.5 * T);
    const double Td = T / std::sqrt(1.0 - xi * xi);
    MESSAGE("damped period relative error: ", std::abs(period - Td) / Td,
            ", decay rate relative error: ", std::abs(rate - xi * w) / (xi * w));
    // damped period 2 pi / (w sqrt(1 - xi^2)) and envelope exp(-xi w t); tolerances 1e-6 and 1e-5
    CHECK(period == approx(Td).epsilon(1e-6));
    CHECK(rate == approx(xi * w).epsilon(1e-5));
  }
}

TEST_CASE("spring: hysteresis with an unloading curve and yield limits follows the hand values") {
  // loading curve: 1000 N/m up to +-0.01 m (+-10 N), then 100 N/m; unloading curve: 1000 N/m
  SpringParams p{.spring = Table({-1.0, -0.01, 0.01, 1.0}, {-109.0, -10.0, 10.0, 109.0}),
                 .unload = Table({-1.0, 1.0}, {-1000.0, 1000.0}),
                 .fyc = -5.0,
                 .fyt = 5.0};
  Driven d(p);
  const double eps = 1e-9; // exact up to rounding: the branch joins are computed in closed form
  CHECK(d.go(0.004) == approx(4.0).epsilon(eps)); // elastic
  CHECK_FALSE(d.st.yielded);
  CHECK(d.go(0.0) == approx(0.0).scale(1.0).epsilon(eps)); // unloading before yield: on L
  CHECK(d.go(0.02) == approx(11.0).epsilon(eps));          // past yield
  CHECK(d.st.yielded);
  CHECK(d.go(0.03) == approx(12.0).epsilon(eps));
  CHECK(d.go(0.025) == approx(7.0).epsilon(eps)); // unloading branch 12 + 1000 (s - 0.03)
  CHECK(d.st.unloading);
  CHECK(d.go(0.028) == approx(10.0).epsilon(eps)); // a reversal stays on the branch
  CHECK(d.go(0.02) == approx(2.0).epsilon(eps));
  // the branch reaches the force of the latest compression point L(0) = 0 at s = 0.018, and the
  // compression path continues from there: f = L(s - 0.018)
  CHECK(d.go(0.01) == approx(-8.0).epsilon(eps));
  CHECK(d.go(0.0) == approx(-10.8).epsilon(eps));
  CHECK(d.go(-0.03) == approx(-13.8).epsilon(eps));
  CHECK(d.st.u_min == approx(-0.048).epsilon(eps));
  // reload: branch through (-0.03, -13.8), delta = -0.0162
  CHECK(d.go(-0.02) == approx(-3.8).epsilon(eps));
  CHECK(d.go(-0.01) == approx(6.2).epsilon(eps));
  // it reaches L(u_max) = 12 at s = -0.0042; the tension path continues: 12 + 100 (s + 0.0042)
  CHECK(d.go(0.0) == approx(12.42).epsilon(eps));
  CHECK(d.go(0.03) == approx(15.42).epsilon(eps));
  CHECK_FALSE(d.st.unloading);
}

TEST_CASE("spring: the elastic-perfectly-plastic loop encloses 4 f_y (a - s_y)") {
  // L: 1000 N/m up to 10 N at 0.01 m, then flat; U: 1000 N/m; cycles between +-0.03 m
  SpringParams p{.spring = Table({-1.0, -0.01, 0.01, 1.0}, {-10.0, -10.0, 10.0, 10.0}),
                 .unload = Table({-1.0, 1.0}, {-1000.0, 1000.0}),
                 .fyc = -5.0,
                 .fyt = 5.0};
  Driven d(p);
  d.go(0.03);
  d.go(-0.03);
  d.go(0.03);
  double area = 0.0, s_prev = d.st.stroke, f_prev = d.st.force;
  const auto trapezoid = [&](double s, double f) {
    area += 0.5 * (f + f_prev) * (s - s_prev);
    s_prev = s;
    f_prev = f;
  };
  // corners of the stabilised loop: (0.03, 10), (0.01, -10), (-0.03, -10), (-0.01, 10)
  CHECK(d.go(0.01, 4000, trapezoid) == approx(-10.0).epsilon(1e-9));
  CHECK(d.go(-0.03, 4000, trapezoid) == approx(-10.0).epsilon(1e-9));
  CHECK(d.go(-0.01, 4000, trapezoid) == approx(10.0).epsilon(1e-9));
  CHECK(d.go(0.03, 4000, trapezoid) == approx(10.0).epsilon(1e-9));
  // the work put into the spring over the cycle, the dissipated energy: 4 * 10 * (0.03 - 0.01)
  MESSAGE("loop area relative error: ", std::abs(area - 0.8) / 0.8);
  CHECK(area == approx(0.8).epsilon(1e-9));
}

TEST_CASE("spring: an unloading curve alone gives a nonlinear loading/unloading pair") {
  // ylim default (0, 0): the unloading curve is used from the first non-zero force
  SpringParams p{.spring = Table({-0.1, 0.0, 0.01, 0.02, 0.1}, {-100.0, 0.0, 1.0, 4.0, 84.0}),
                 .unload = Table({-1.0, 1.0}, {-1000.0, 1000.0})};
  Driven d(p);
  CHECK(d.go(0.015) == approx(2.5).epsilon(1e-12));
  CHECK(d.go(0.02) == approx(4.0).epsilon(1e-12));
  CHECK(d.go(0.018) == approx(2.0).epsilon(1e-9)); // unloading: 4 + 1000 (s - 0.02)
  CHECK(d.go(0.02) == approx(4.0).epsilon(1e-9));  // back to the latest point
  CHECK(d.go(0.03) == approx(14.0).epsilon(1e-9)); // and along L again
  // without the unloading curve the same table is elastic both ways
  Driven e(SpringParams{.spring = p.spring});
  e.go(0.02);
  CHECK(e.go(0.018) == approx(3.4).epsilon(1e-12));
}

TEST_CASE("spring: the stroke offset shifts the curve, and stops at yield") {
  Driven d(SpringParams{.spring = linear_table(1000.0), .offset = TimeFunction::linear(0.0, 0.01)});
  CHECK(d.at(0.02, 1.0).elastic == approx(10.0).epsilon(1e-12));
  CHECK(d.at(0.02, 2.0).elastic == approx(0.0).scale(1.0).epsilon(1e-12));
  CHECK(d.at(0.02, 3.0).elastic == approx(-10.0).epsilon(1e-12));

  Driven y(SpringParams{.spring = linear_table(1000.0),
                        .unload = linear_table(1000.0),
                        .fyc = -5.0,
                        .fyt = 5.0,
                        .offset = TimeFunction::linear(0.0, 0.01)});
  CHECK(y.at(0.004, 0.0).elastic == approx(4.0).epsilon(1e-12));
  CHECK(y.at(0.004, 1.0).elastic == approx(-6.0).epsilon(1e-12)); // crosses fyc: yields
  CHECK(y.st.yielded);
  CHECK(y.at(0.004, 2.0).elastic == approx(-6.0).epsilon(1e-12)); // offset kept at its yield value
}

TEST_CASE("spring: geometries give the direction, length and stroke of their definitions") {
  const double eps = 1e-12;
  SUBCASE("point to point: the direction follows the points") {
    SpringParams p{.spring = linear_table(2.0), .damping_ratio = 0.0};
    SpringKinematics k;
    k.p2 = Vec3(3.0, 4.0, 0.0);
    SpringState st = init_spring(p, k);
    CHECK(st.stroke0 == approx(5.0).epsilon(eps));
    k.p2 = Vec3(6.0, 8.0, 0.0);
    k.v2 = Vec3(1.8, 2.4, 0.0);
    const SpringResult r = evaluate(p, st, k, 0.0, 1e-3, 1.0);
    CHECK(r.length == approx(10.0).epsilon(eps));
    CHECK(r.stroke == approx(5.0).epsilon(eps));
    CHECK(r.velocity == approx(3.0).epsilon(eps));
    CHECK((r.direction - Vec3(0.6, 0.8, 0.0)).norm() < eps);
    CHECK((r.force - Vec3(6.0, 8.0, 0.0)).norm() < eps); // tension pulls point 1 towards point 2
  }
  SUBCASE("constant direction") {
    SpringParams p{.spring = linear_table(2.0),
                   .geometry = SpringGeometry::constant_direction,
                   .direction = Vec3(0.0, 0.0, 2.0)};
    SpringKinematics k;
    k.p2 = Vec3(1.0, 1.0, 1.0);
    SpringState st = init_spring(p, k);
    k.p2 = Vec3(5.0, -3.0, 1.5);
    const SpringResult r = evaluate(p, st, k, 0.0, 1e-3, 1.0);
    CHECK(r.stroke == approx(0.5).epsilon(eps));
    CHECK((r.force - Vec3(0.0, 0.0, 1.0)).norm() < eps);
  }
  SUBCASE("planar: the follower direction projected on the plane normal to the direction") {
    SpringParams p{.spring = linear_table(2.0),
                   .geometry = SpringGeometry::planar,
                   .direction = Vec3(0.0, 0.0, 1.0)};
    SpringKinematics k;
    k.p2 = Vec3(3.0, 0.0, 7.0);
    SpringState st = init_spring(p, k);
    CHECK(st.stroke0 == approx(3.0).epsilon(eps));
    k.p2 = Vec3(0.0, 4.0, -2.0);
    const SpringResult r = evaluate(p, st, k, 0.0, 1e-3, 1.0);
    CHECK(r.length == approx(4.0).epsilon(eps));
    CHECK(r.stroke == approx(1.0).epsilon(eps));
    CHECK((r.direction - Vec3(0.0, 1.0, 0.0)).norm() < eps);
    CHECK((r.force - Vec3(0.0, 2.0, 0.0)).norm() < eps);
  }
  SUBCASE("point to plane: the stroke is the signed distance; a contact table pushes out") {
    SpringParams p{.spring = Table({-1.0, 0.0, 1.0}, {-1000.0, 0.0, 0.0}),
                   .damping_ratio = 0.5,
                   .geometry = SpringGeometry::point_to_plane};
    SpringKinematics k;
    k.p2 = Vec3(0.0, 0.0, 1.0);
    k.normal = Vec3(0.0, 0.0, 1.0);
    k.p1 = Vec3(0.3, 0.2, 1.5);
    SpringState st = init_spring(p, k);
    CHECK(st.stroke0 == 0.0);
    k.p1 = Vec3(0.3, 0.2, 0.9);
    SpringResult r = evaluate(p, st, k, 0.0, 1e-3, 1.0);
    CHECK(r.stroke == approx(-0.1).epsilon(eps));
    CHECK((r.force - Vec3(0.0, 0.0, 100.0)).norm() < 1e-9);
    k.p1 = Vec3(0.3, 0.2, 1.2);
    k.v1 = Vec3(0.0, 0.0, 2.0); // separating: no elastic force, so no dashpot force either
    r = evaluate(p, st, k, 0.0, 1e-3, 1.0);
    CHECK(r.stroke == approx(0.2).epsilon(eps));
    CHECK(r.total == 0.0);
    CHECK(r.force.norm() == 0.0);
    // penetrating with velocity: the dashpot 2 xi sqrt(k m) v adds to the elastic force
    k.p1 = Vec3(0.3, 0.2, 0.9);
    k.v1 = Vec3(0.0, 0.0, -1.0);
    r = evaluate(p, st, k, 0.0, 1e-3, 4.0);
    CHECK(r.velocity == approx(-1.0).epsilon(eps));
    CHECK(r.damping == approx(-2.0 * 0.5 * std::sqrt(1000.0 * 4.0)).epsilon(eps));
  }
  SUBCASE("an inactive spring gives no force") {
    SpringParams p{.spring = linear_table(2.0), .inactive = true};
    SpringKinematics k;
    k.p2 = Vec3(1.0, 0.0, 0.0);
    SpringState st = init_spring(p, k);
    CHECK(st.code == spring_code::inactive);
    k.p2 = Vec3(2.0, 0.0, 0.0);
    const SpringResult r = evaluate(p, st, k, 0.0, 1e-3, 1.0);
    CHECK(r.stroke == approx(1.0).epsilon(eps));
    CHECK(r.force.norm() == 0.0);
    activate(st);
    CHECK(evaluate(p, st, k, 0.0, 1e-3, 1.0).elastic == approx(2.0).epsilon(eps));
    CHECK(st.code == spring_code::activated);
  }
}

TEST_CASE("spring: friction") {
  // a contact element pressed 0.1 m into the plane z = 0: f = -100 N
  SpringParams p{.spring = Table({-1.0, 0.0, 1.0}, {-1000.0, 0.0, 0.0}),
                 .geometry = SpringGeometry::point_to_plane,
                 .friction = 0.5};
  SpringKinematics k;
  k.normal = Vec3::UnitZ();
  k.p1 = Vec3(0.0, 0.0, 0.0);
  SUBCASE("kskn = 0: sliding friction mu abs(F) against the tangential velocity") {
    SpringState st = init_spring(p, k);
    k.p1 = Vec3(0.0, 0.0, -0.1);
    k.v1 = Vec3(1.0, 2.0, -0.3);
    const SpringResult r = evaluate(p, st, k, 0.0, 1e-3, 1.0);
    CHECK(r.elastic == approx(-100.0).epsilon(1e-12));
    CHECK(r.friction == approx(50.0).epsilon(1e-12));
    CHECK((r.friction_force - 50.0 * Vec3(-1.0, -2.0, 0.0) / std::sqrt(5.0)).norm() < 1e-9);
  }
  SUBCASE("kskn > 0: sticks with k_t = kskn k_n, slips at the Coulomb limit, sticks on reversal") {
    p.kskn = 0.5; // k_t = 500 N/m, limit 50 N
    SpringState st = init_spring(p, k);
    k.p1 = Vec3(0.0, 0.0, -0.1);
    k.v1 = Vec3(0.1, 0.0, 0.0);
    const double h = 0.01; // 1 mm of sliding per step, 0.5 N per step while sticking
    SpringResult r;
    for (int i = 1; i <= 60; ++i)
      r = evaluate(p, st, k, i * h, h, 1.0);
    CHECK(r.friction_force.x() == approx(-30.0).epsilon(1e-9));
    CHECK_FALSE(st.slipping);
    for (int i = 61; i <= 120; ++i)
      r = evaluate(p, st, k, i * h, h, 1.0);
    CHECK(r.friction == approx(50.0).epsilon(1e-12));
    CHECK(st.slipping);
    CHECK(st.tangential[0] == approx(-0.1).epsilon(1e-12)); // truncated at the limit
    k.v1 = Vec3(-0.1, 0.0, 0.0);
    r = evaluate(p, st, k, 1.21, h, 1.0);
    CHECK(r.friction_force.x() == approx(-49.5).epsilon(1e-9)); // sticks at once
    CHECK_FALSE(st.slipping);
    // the history is turned into a new tangent plane with its length kept
    k.normal = Vec3(1.0, 0.0, 1.0).normalized();
    k.p1 = -0.1 * k.normal; // the same 100 N normal force
    k.v1 = Vec3::Zero();
    evaluate(p, st, k, 1.22, h, 1.0);
    CHECK(std::abs(load<3>(st.tangential).dot(k.normal)) < 1e-15);
    CHECK(load<3>(st.tangential).norm() == approx(0.099).epsilon(1e-12));
  }
}

TEST_CASE("unspring: a rule fires after nfreq consecutive checks and unloads and activates") {
  // springs 0, 1 tested; 2 undone at once; 3 unloaded along a curve; 4 dormant, then activated
  std::vector<Driven> s;
  for (int i = 0; i < 5; ++i)
    s.emplace_back(SpringParams{.spring = linear_table(100.0), .inactive = i == 4});
  std::vector<SpringState> states(5);
  std::vector<SpringResult> results(5);
  UnspringRule rule{.tsprings = {0, 1},
                    .msprings = {2, 3},
                    .max = 10.0,
                    .nsteps = 2,
                    .nfreq = 3,
                    .unload = {{3, Table({0.0, 0.01}, {0.0, 5.0})}},
                    .activate = {4}};
  Unspring u(std::move(rule), 5);
  std::vector<double> stroke{0.06, 0.06, 0.03, 0.05, 0.02};
  int fired_at = 0;
  const auto step = [&](int call) {
    for (std::size_t i = 0; i < 5; ++i) {
      s[i].st = states[i];
      results[i] = s[i].at(stroke[i]);
      states[i] = s[i].st;
    }
    const bool was_fired = u.fired();
    const UnspringEvent ev = u.update(results, states);
    CHECK(ev.checked == (call % 2 == 0 && !was_fired)); // no checks after firing
    if (ev.fired) fired_at = call;
    return ev;
  };
  for (std::size_t i = 0; i < 5; ++i)
    states[i] = s[i].st;
  step(1);
  CHECK(step(2).value == approx(12.0).epsilon(1e-12)); // 6 + 6 N > 10 N: count 1
  CHECK(u.count() == 1);
  stroke[0] = 0.01; // 1 + 6 = 7 N: inside, the count restarts
  step(3);
  step(4);
  CHECK(u.count() == 0);
  stroke[0] = 0.06;
  for (int call = 5; call <= 10; ++call)
    step(call);
  CHECK(fired_at == 10);
  CHECK(u.fired());
  CHECK(states[2].code == spring_code::inactive);
  CHECK(states[3].code == 0);
  CHECK(results[3].elastic == approx(5.0).epsilon(1e-12));
  CHECK_FALSE(u.activated());
  // spring 3: increments of either sign lower the force by g(sum abs(ds)) = 500 N/m * path
  stroke[3] = 0.052;
  step(11);
  CHECK(results[2].force.norm() == 0.0);
  CHECK(results[3].elastic == approx(4.0).epsilon(1e-9));
  CHECK(results[3].damping == 0.0);
  stroke[3] = 0.05;
  step(12);
  CHECK(results[3].elastic == approx(3.0).epsilon(1e-9));
  CHECK(results[4].force.norm() == 0.0);
  stroke[3] = 0.06; // path 0.014 m: past the end of the curve, fully unloaded
  step(13);
  CHECK(results[3].elastic == 0.0);
  CHECK(states[3].code == spring_code::inactive);
  CHECK(u.activated());
  CHECK(states[4].code == spring_code::activated);
  stroke[3] = 0.05;
  step(14);
  CHECK(results[3].elastic == 0.0); // zero ever after
  CHECK(results[4].elastic == approx(2.0).epsilon(1e-12));
  CHECK(results[4].code == spring_code::activated);
}

TEST_CASE("torsion spring: angles of known relative rotations") {
  using Eigen::AngleAxisd;
  using Eigen::Quaterniond;
  const Quaterniond I = Quaterniond::Identity();
  TorsionSpringParams p;
  const TorsionFrames f = torsion_frames(I, I, Vec3::UnitZ(), Vec3::UnitX());
  const auto angles = [&](const Quaterniond& q1, const Quaterniond& q2, const TorsionFrames& fr) {
    return evaluate(p, fr, TorsionKinematics{q1, q2, Vec3::Zero(), Vec3::Zero()}, Vec3::Ones())
        .angles;
  };
  const double eps = 1e-12;
  CHECK((angles(Quaterniond(AngleAxisd(0.3, Vec3::UnitX())), I, f) - Vec3(0.3, 0, 0)).norm() < eps);
  CHECK((angles(Quaterniond(AngleAxisd(0.4, Vec3::UnitY())), I, f) - Vec3(0, 0.4, 0)).norm() < eps);
  CHECK((angles(Quaterniond(AngleAxisd(-0.5, Vec3::UnitZ())), I, f) - Vec3(0, 0, -0.5)).norm() <
        eps);
  // a twist gamma about z followed by a swing beta about (cos a, sin a, 0)
  const double a = 0.7, beta = 0.5, gamma = 0.9;
  const Quaterniond q = Quaterniond(AngleAxisd(beta, Vec3(std::cos(a), std::sin(a), 0.0))) *
                        Quaterniond(AngleAxisd(gamma, Vec3::UnitZ()));
  const Vec3 c = angles(q, I, f);
  CHECK((c - Vec3(beta * std::cos(a), beta * std::sin(a), gamma)).norm() < eps);
  // the swing angle is the angle between the z axes: the cone angle
  p.cone = {true, true, false};
  CHECK(cone_angle(p, c) ==
        approx(std::acos((q * Vec3::UnitZ()).dot(Vec3::UnitZ()))).epsilon(1e-12));
  // body 2 rotated, frames not aligned with the body axes: a relative yaw about the world zdir
  const Quaterniond q0(AngleAxisd(1.1, Vec3(1.0, -2.0, 0.5).normalized()));
  const Vec3 zdir = Vec3(1.0, 1.0, 0.0), xdir = Vec3(0.0, 0.0, 3.0);
  const TorsionFrames g = torsion_frames(q0, q0, zdir, xdir);
  const Quaterniond q1 = Quaterniond(AngleAxisd(0.25, zdir.normalized())) * q0;
  CHECK((angles(q1, q0, g) - Vec3(0, 0, 0.25)).norm() < eps);
  const Quaterniond q2 = Quaterniond(AngleAxisd(-0.35, xdir.normalized())) * q0;
  CHECK((angles(q2, q0, g) - Vec3(-0.35, 0, 0)).norm() < eps);
  // the same from rotation matrices
  const auto km = TorsionKinematics::from_matrices(q2.toRotationMatrix(), q0.toRotationMatrix(),
                                                   Vec3::Zero(), Vec3::Zero());
  CHECK((evaluate(p, g, km, Vec3::Ones()).angles - Vec3(-0.35, 0, 0)).norm() < eps);
}

TEST_CASE("torsion spring: a rotor on a linear torque table oscillates at sqrt(k/J)") {
  const double J = 0.5, k = 8.0, w = std::sqrt(k / J); // 4 rad/s
  TorsionSpringParams p;
  p.yaw.spring = Table({-10.0, 10.0}, {-10.0 * k, 10.0 * k});
  validate(p);
  const Eigen::Quaterniond I = Eigen::Quaterniond::Identity();
  const TorsionFrames f = torsion_frames(I, I, Vec3::UnitZ(), Vec3::UnitX());
  const double T = 2.0 * pi / w, h = T / 10000.0;
  double th = 0.2, om = 0.0, t = 0.0;
  const auto torque = [&](double angle) {
    TorsionKinematics kin;
    kin.q1 = Eigen::Quaterniond(Eigen::AngleAxisd(angle, Vec3::UnitZ()));
    kin.w1 = Vec3(0.0, 0.0, om);
    return evaluate(p, f, kin, Vec3::Constant(J)).torque.z();
  };
  double alpha = torque(th) / J;
  Crossings c;
  while (t < 10.5 * T) {
    om += 0.5 * h * alpha;
    th += h * om;
    t += h;
    alpha = torque(th) / J;
    om += 0.5 * h * alpha;
    c.add(t, th);
  }
  MESSAGE("torsion period relative error: ", std::abs(c.period() - T) / T);
  CHECK(c.period() == approx(T).epsilon(1e-6)); // measured 1e-8

  // damping ratio: c = 2 xi sqrt(k J) against the rate z . (w1 - w2)
  p.yaw.damping_ratio = 0.1;
  TorsionKinematics kin;
  kin.w1 = Vec3(0.0, 0.0, 1.5);
  kin.w2 = Vec3(0.0, 0.0, 0.5);
  const TorsionResult r = evaluate(p, f, kin, Vec3::Constant(J));
  CHECK(r.rates.z() == approx(1.0).epsilon(1e-12));
  CHECK(r.torque.z() == approx(-2.0 * 0.1 * std::sqrt(k * J)).epsilon(1e-12));
}

TEST_CASE("torsion spring: a cone couples roll and pitch into one radial angle") {
  TorsionSpringParams p;
  p.roll.spring = Table({0.0, 0.1, 1.0}, {0.0, 0.0, 90.0}); // free up to 0.1 rad, then 100 N m/rad
  p.cone = {true, true, false};
  validate(p);
  const Eigen::Quaterniond I = Eigen::Quaterniond::Identity();
  const TorsionFrames f = torsion_frames(I, I, Vec3::UnitZ(), Vec3::UnitX());
  const double a = 0.6, beta = 0.3;
  TorsionKinematics kin;
  kin.q1 = Eigen::Quaterniond(Eigen::AngleAxisd(beta, Vec3(std::cos(a), std::sin(a), 0.0)));
  const TorsionResult r = evaluate(p, f, kin, Vec3::Ones());
  CHECK(cone_angle(p, r.angles) == approx(beta).epsilon(1e-12));
  const double T = 100.0 * (beta - 0.1); // 20 N m about the swing axis, restoring
  CHECK(r.torque.norm() == approx(T).epsilon(1e-12));
  CHECK(r.torque.dot(Vec3(std::cos(a), std::sin(a), 0.0)) == approx(-T).epsilon(1e-12));
  // inside the cone: no torque although each angle alone would be past 0.1 rad in a box
  kin.q1 = Eigen::Quaterniond(Eigen::AngleAxisd(0.09, Vec3(1.0, 1.0, 0.0).normalized()));
  CHECK(evaluate(p, f, kin, Vec3::Ones()).torque.norm() == 0.0);
}

TEST_CASE("springs: bad input raises InputError naming the object, the value and the range") {
  const auto bad = [](SpringParams p) {
    return error_of([&] { init_spring(p, SpringKinematics{}); });
  };
  std::string m = bad(SpringParams{.spring = linear_table(1.0), .fyc = 2.0, .name = "S7"});
  CHECK(has(m, "S7: fyc = 2 is invalid; valid range: (-inf, 0]"));
  m = bad(SpringParams{.spring = linear_table(1.0), .fyt = -1.0});
  CHECK(has(m, "fyt = -1 is invalid; valid range: [0, inf)"));
  m = bad(SpringParams{.spring = linear_table(1.0), .damping_ratio = -0.1});
  CHECK(has(m, "damping_ratio = -0.1 is invalid; valid range: [0, inf)"));
  m = bad(SpringParams{
      .spring = linear_table(1.0), .dashpot = linear_table(1.0), .damping_ratio = 0.1});
  CHECK(has(m, "damping_ratio = 0.1 is invalid; valid range: 0 when a dashpot table is given"));
  m = bad(SpringParams{.spring = linear_table(1.0), .geometry = SpringGeometry::planar});
  CHECK(has(m, "|direction| = 0 is invalid; valid range: (0, inf)"));
  m = bad(SpringParams{.spring = linear_table(1.0),
                       .geometry = SpringGeometry::constant_direction,
                       .direction = Vec3(std::nan(""), 0.0, 1.0)});
  CHECK(has(m, "direction = (nan, 0, 1) is invalid; valid range: finite components"));
  m = bad(SpringParams{.spring = linear_table(1.0), .friction = std::nan("")});
  CHECK(has(m, "friction = nan is invalid"));
  m = bad(SpringParams{.spring = linear_table(1.0), .kskn = -1.0});
  CHECK(has(m, "kskn = -1 is invalid; valid range: [0, inf)"));
  m = bad(
      SpringParams{.spring = linear_table(1.0), .unload = Table({0.0, 1.0, 2.0}, {0.0, 2.0, 1.0})});
  CHECK(has(m, "unload Table y[2] = 1 is invalid; valid range: (2, inf)"));
  CHECK(has(error_of([] { Table({0.0, 0.0}, {1.0, 2.0}, "spring"); }), "Table 'spring': x[1] = 0"));

  TorsionSpringParams t;
  t.pitch.damping_ratio = -1.0;
  CHECK(has(error_of([&] { validate(t); }), "pitch.damping_ratio = -1 is invalid"));
  t.pitch.damping_ratio = 0.0;
  t.cone = {false, true, false};
  CHECK(has(error_of([&] { validate(t); }), "number of cone angles = 1 is invalid"));
  const Eigen::Quaterniond I = Eigen::Quaterniond::Identity();
  CHECK(has(error_of([&] { torsion_frames(I, I, Vec3::UnitZ(), Vec3(1.0, 0.0, 0.1)); }),
            "zdir . xdir (unit) = 0.0995037"));
  CHECK(has(error_of([&] { torsion_frames(I, I, Vec3::Zero(), Vec3::UnitX()); }), "|zdir| = 0"));

  const auto rule_error = [](UnspringRule r) {
    return error_of([&] { Unspring u(std::move(r), 4); });
  };
  CHECK(has(rule_error(UnspringRule{.tsprings = {}, .msprings = {1}, .max = 1.0}),
            "UNSPRING: number of tsprings = 0 is invalid; valid range: [1, inf)"));
  CHECK(has(rule_error(UnspringRule{.tsprings = {0, 0}, .msprings = {1}, .max = 1.0}),
            "tsprings[1] = 0"));
  CHECK(has(rule_error(UnspringRule{.tsprings = {0}, .msprings = {4}, .max = 1.0}),
            "msprings[0] = 4 is invalid; valid range: [0, 4)"));
  CHECK(has(rule_error(UnspringRule{.tsprings = {0}, .msprings = {1}, .min = 2.0, .max = 1.0}),
            "min = 2 is invalid; valid range: (-inf, max) = (-inf, 1)"));
  CHECK(has(rule_error(UnspringRule{.tsprings = {0}, .msprings = {1}}), "limits = (none, none)"));
  CHECK(has(rule_error(UnspringRule{.tsprings = {0}, .msprings = {1}, .max = 1.0, .nfreq = 0}),
            "nfreq = 0 is invalid; valid range: [1, inf)"));
  CHECK(has(rule_error(UnspringRule{.tsprings = {0},
                                    .msprings = {1},
                                    .max = 1.0,
                                    .unload = {{2, Table({0.0, 1.0}, {0.0, 1.0})}}}),
            "unload[0] spring = 2 is invalid; valid range: a spring of msprings"));
  CHECK(has(rule_error(UnspringRule{.tsprings = {0},
                                    .msprings = {1},
                                    .max = 1.0,
                                    .unload = {{1, Table({0.0, 1.0}, {0.5, 1.0})}}}),
            "first point = (0, 0.5) is invalid; valid range: (0, 0)"));
}

TEST_CASE("unspring: SUM, MIN, MAX and abs of each entity") {
  std::vector<SpringResult> r(3);
  const double stroke[3] = {0.1, -0.3, 0.2}, total[3] = {5.0, -7.0, 1.0};
  for (std::size_t i = 0; i < 3; ++i) {
    r[i].stroke = stroke[i];
    r[i].total = total[i];
    r[i].elastic = total[i] - 1.0;
    r[i].friction = double(i);
  }
  const auto value = [&](SpringEntity e, SpringOperator op, bool abs) {
    return Unspring(UnspringRule{.tsprings = {0, 1, 2},
                                 .msprings = {0},
                                 .min = -1.0,
                                 .entity = e,
                                 .op = op,
                                 .abs = abs},
                    3)
        .value(r);
  };
  const double eps = 1e-12;
  CHECK(value(SpringEntity::stroke, SpringOperator::sum, false) ==
        approx(0.0).scale(1.0).epsilon(eps));
  CHECK(value(SpringEntity::stroke, SpringOperator::sum, true) == approx(0.6).epsilon(eps));
  CHECK(value(SpringEntity::total_force, SpringOperator::min, false) == approx(-7.0).epsilon(eps));
  CHECK(value(SpringEntity::total_force, SpringOperator::max, true) == approx(7.0).epsilon(eps));
  CHECK(value(SpringEntity::elastic_force, SpringOperator::sum, false) ==
        approx(-4.0).epsilon(eps));
  CHECK(value(SpringEntity::friction_force, SpringOperator::max, false) ==
        approx(2.0).epsilon(eps));
}

TEST_CASE("spring: a dashpot table adds f_d(v), and nothing while the elastic force is zero") {
  // elastic force only in compression; dashpot table 50 N s/m up to 1 m/s, then 50 N
  Driven d(SpringParams{.spring = Table({-1.0, 0.0, 1.0}, {-100.0, 0.0, 0.0}),
                        .dashpot = Table({-1.0, 1.0}, {-50.0, 50.0})});
  SpringKinematics k;
  k.p2 = Vec3(-0.1, 0.0, 0.0);
  k.v2 = Vec3(-0.4, 0.0, 0.0);
  SpringResult r = evaluate(d.p, d.st, k, 0.0, 1e-3, 1.0);
  CHECK(r.elastic == approx(-10.0).epsilon(1e-12));
  CHECK(r.damping == approx(-20.0).epsilon(1e-12));
  CHECK(r.total == approx(-30.0).epsilon(1e-12));
  k.v2 = Vec3(-3.0, 0.0, 0.0);
  CHECK(evaluate(d.p, d.st, k, 0.0, 1e-3, 1.0).damping == approx(-50.0).epsilon(1e-12));
  k.p2 = Vec3(0.1, 0.0, 0.0);
  k.v2 = Vec3(0.4, 0.0, 0.0);
  r = evaluate(d.p, d.st, k, 0.0, 1e-3, 1.0);
  CHECK(r.elastic == 0.0);
  CHECK(r.damping == 0.0);
  CHECK(r.force.norm() == 0.0);
}
