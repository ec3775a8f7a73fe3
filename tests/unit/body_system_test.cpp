// The body system: springs, torsion springs and ball joints on rigid bodies against closed forms
// (oscillator frequency and decay, pendulum period and length, momentum, joint reaction, torsion
// frequency), critical steps (sharp stability limit, CRITICAL lists, adaptive stepping), an
// unspring rule in the loop, and input validation.
#include "../approx.hpp"
#include "../errors.hpp"
#include "../support/tables.hpp"
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <doctest/doctest.h>
#include <filesystem>
#include <fstream>
#include <grain/bodies/output.hpp>
#include <grain/bodies/system.hpp>
#include <grain/io/console.hpp>
#include <grain/io/csv.hpp>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

using grain::Table;
using grain::Vec3;
using grain::test::approx;
namespace gb = grain::bodies;

namespace {

constexpr double pi = std::numbers::pi;

using grain::test::error_of;
using grain::test::has;

/// A body of mass m with the isotropic inertia j at x.
gb::RigidBody body(double m, double j, const Vec3& x, const Vec3& v = Vec3::Zero()) {
  gb::RigidBody b;
  b.mass = m;
  b.inertia = Eigen::Matrix3d::Identity() * j;
  b.position = x;
  b.velocity = v;
  return b;
}

using grain::test::linear_table;

/// Mean period of upward zero crossings of the samples x(t_k) (linear interpolation).
struct Crossings {
  std::vector<double> times;
  double last_t = 0.0, last_x = 0.0;
  bool first = true;
  void add(double t, double x) {
    if (!first && last_x < 0.0 && x >= 0.0)
      times.push_back(last_t + (t - last_t) * (-last_x) / (x - last_x));
    first = false;
    last_t = t;
    last_x = x;
  }
  double period() const { return (times.back() - times.front()) / double(times.size() - 1); }
};

/// A body of mass m (tiny inertia) at the origin on a spring along x to the fixed point (1, 0, 0)
/// (constant direction: linear at any amplitude).
gb::BodySystem oscillator(double m, double k, double xi, double v0) {
  gb::BodySystem s;
  s.add_body(body(m, 1e-3, Vec3::Zero(), Vec3(v0, 0.0, 0.0)));
  gb::SpringParams p{.spring = linear_table(k, 1e6),
                     .damping_ratio = xi,
                     .geometry = gb::SpringGeometry::constant_direction,
                     .direction = Vec3::UnitX()};
  s.add_spring(p, 0, Vec3::Zero(), gb::world, Vec3(1.0, 0.0, 0.0));
  return s;
}

} // namespace

TEST_CASE("body system: a mass on a linear spring oscillates at sqrt(k/m) and decays at xi") {
  const double m = 2.0, k = 800.0, w = std::sqrt(k / m), T = 2.0 * pi / w;
  const double h = T / 2000.0;
  SUBCASE("undamped") {
    gb::BodySystem s = oscillator(m, k, 0.0, 0.1);
    Crossings c;
    for (int n = 0; n < 20 * 2000; ++n) {
      s.step(h);
      c.add(s.time(), s.bodies().position[0].x());
    }
    // velocity Verlet: period error (w h)^2 / 24 = 4e-7
    CHECK(c.period() == approx(T).epsilon(1e-6));
    MESSAGE("oscillator: undamped period error ", c.period() / T - 1.0);
    // the spring pulls towards the fixed point with the elastic force
    CHECK(s.spring_mass(0) == approx(m).epsilon(1e-12));
  }
  SUBCASE("damped, xi = 0.05") {
    const double xi = 0.05;
    gb::BodySystem s = oscillator(m, k, xi, 0.1);
    Crossings c;
    std::vector<std::pair<double, double>> maxima;
    double x0 = 0.0, x1 = 0.0;
    for (int n = 0; n < 10 * 2000; ++n) {
      s.step(h);
      const double x = s.bodies().position[0].x();
      c.add(s.time(), x);
      if (n >= 2 && x1 > x0 && x1 >= x) maxima.emplace_back(s.time() - h, x1);
      x0 = x1;
      x1 = x;
    }
    const double wd = w * std::sqrt(1.0 - xi * xi);
    // the dashpot sees the half-step velocity v(t + h/2) = v(t + h) - h/2 a: a force
    // c h/2 (k/m) x in phase with the spring, which shortens the period by xi w h / 2 (7.9e-5);
    // the rest is the (w h)^2 / 24 = 4e-7 of the scheme
    const double lag = xi * w * h / 2.0;
    CHECK(std::abs(c.period() / (2.0 * pi / wd) - 1.0 + lag) < 1e-6);
    const double rate = std::log(maxima.front().second / maxima.back().second) /
                        (maxima.back().first - maxima.front().first);
    // the dashpot sees the half-step velocity: an O(h) lag; measured 6e-4 relative at T/2000
    CHECK(rate == approx(xi * w).epsilon(2e-3));
    MESSAGE("oscillator: damped period error ", c.period() / (2.0 * pi / wd) - 1.0,
            ", decay rate error ", rate / (xi * w) - 1.0);
  }
}

TEST_CASE("body system: a pendulum on a ball joint has the compound period and keeps its length") {
  const double m = 1.5, j = 0.02, L = 0.8, g = 9.81;
  const double T0 = 2.0 * pi * std::sqrt((j + m * L * L) / (m * g * L));
  SUBCASE("small amplitude: period") {
    const double a = 0.01; // rad
    gb::BodySystem s(Vec3(0.0, 0.0, -g));
    s.add_body(body(m, j, Vec3(L * std::sin(a), 0.0, -L * std::cos(a))));
    s.add_ball_joint(0, Vec3::Zero());
    const double h = 1e-3;
    Crossings c;
    double max_gap = 0.0;
    for (int n = 0; n < static_cast<int>(20 * T0 / h); ++n) {
      s.step(h);
      c.add(s.time(), s.bodies().position[0].x());
      max_gap = std::max(max_gap, std::abs(s.bodies().position[0].norm() - L));
    }
    // finite amplitude: T = T0 (1 + a^2/16 + ...); discretisation (w h)^2/24 = 4e-7
    CHECK(c.period() == approx(T0 * (1.0 + a * a / 16.0)).epsilon(2e-6));
    // the joint gap is closed to 1e-12 of the arm after every drift
    CHECK(max_gap < 1e-11 * L);
    MESSAGE("pendulum: period error ", c.period() / (T0 * (1.0 + a * a / 16.0)) - 1.0,
            ", max |length - L| ", max_gap);
  }
  SUBCASE("large amplitude: length and energy over 100 periods") {
    const double a = 1.0;
    gb::BodySystem s(Vec3(0.0, 0.0, -g));
    // a velocity the joint allows: the joint point at rest, v = omega x (c - joint)
    gb::RigidBody b = body(m, j, Vec3(L * std::sin(a), 0.0, -L * std::cos(a)), Vec3(0.0, 0.3, 0.0));
    b.omega = b.position.cross(b.velocity) / (L * L);
    s.add_body(b);
    s.add_ball_joint(0, Vec3::Zero());
    const double h = 1e-3;
    const double e0 = s.kinetic_energy() + s.potential_energy();
    const double motion = m * g * L * (1.0 - std::cos(a)) + 0.5 * (m + j / (L * L)) * 0.09;
    double max_gap = 0.0, max_de = 0.0, max_joint_gap = 0.0;
    int max_drifts = 0;
    const int n = static_cast<int>(100 * T0 / h);
    for (int k = 0; k < n; ++k) {
      s.step(h);
      max_gap = std::max(max_gap, std::abs(s.bodies().position[0].norm() - L));
      max_joint_gap = std::max(max_joint_gap, s.joint_result(0).gap);
      max_drifts = std::max(max_drifts, s.joint_drifts());
      max_de = std::max(max_de, std::abs(s.kinetic_energy() + s.potential_energy() - e0));
    }
    // the gap is closed to 1e-12 of the arm after every drift: no accumulation over 1.9e5 steps
    CHECK(max_gap < 1e-11 * L);
    CHECK(max_joint_gap < 1e-11 * L);
    CHECK(max_drifts <= 4); // each extra drift reduces the gap by about h |omega| = 3e-3
    // energy: O(h^2) fluctuation without drift (measured 2.0e-5 J, 7.9e-5 J at h = 2e-3, 5.0e-6 J
    // at h = 5e-4), relative to the energy of the motion (5.5 J)
    CHECK(max_de < 1e-5 * motion);
    MESSAGE("pendulum a = 1: max |length - L| / L = ", max_gap / L, ", max joint gap ",
            max_joint_gap, ", max |dE| / E_motion = ", max_de / motion,
            ", drifts per step <= ", max_drifts);
  }
}

TEST_CASE("body system: the joint reaction of a body hanging at rest is its weight") {
  const double m = 3.0, g = 9.81;
  gb::BodySystem s(Vec3(0.0, 0.0, -g));
  gb::RigidBody b = body(m, 0.1, Vec3(0.0, 0.0, -0.5));
  b.inertia = gb::inertia_tensor(0.1, 0.2, 0.25, 0.01, 0.0, 0.02);
  s.add_body(b);
  s.add_ball_joint(0, Vec3::Zero());
  for (int n = 0; n < 100; ++n)
    s.step(1e-3);
  const Vec3 r = s.joint_result(0).reaction;
  CHECK(r.z() == approx(m * g).epsilon(1e-12));
  CHECK(std::abs(r.x()) + std::abs(r.y()) < 1e-12 * m * g);
  CHECK(s.bodies().velocity[0].norm() < 1e-11 * g * 1e-3); // the 1e-12 regularisation
  CHECK(s.bodies().position[0].z() == approx(-0.5).epsilon(1e-14));
}

TEST_CASE("body system: two bodies joined by a ball joint conserve momentum") {
  gb::BodySystem s;
  gb::RigidBody a = body(2.0, 0.1, Vec3(-0.5, 0.0, 0.0), Vec3(0.3, 1.0, -0.2));
  a.inertia = gb::inertia_tensor(0.1, 0.15, 0.2, 0.01, 0.0, 0.0);
  a.omega = Vec3(0.5, -1.0, 2.0);
  gb::RigidBody b = body(1.0, 0.05, Vec3(0.4, 0.1, 0.0), Vec3(-0.4, 0.2, 0.5));
  b.omega = Vec3(-1.0, 0.0, 0.7);
  s.add_body(a);
  s.add_body(b);
  s.add_ball_joint(0, Vec3(0.0, 0.05, 0.0), 1);
  // the points must move together: start them with the same velocity by one joint solve
  const auto momentum = [&] {
    Vec3 p = Vec3::Zero(), l = Vec3::Zero();
    const auto& B = s.bodies();
    for (std::size_t i = 0; i < 2; ++i) {
      p += B.mass[i] * B.velocity[i];
      l += gb::angular_momentum(B, i) + B.position[i].cross(B.mass[i] * B.velocity[i]);
    }
    return std::pair{p, l};
  };
  const auto [p0, l0] = momentum();
  double max_gap = 0.0;
  for (int n = 0; n < 20000; ++n) {
    s.step(1e-3);
    max_gap = std::max(max_gap, s.joint_result(0).gap);
  }
  const auto [p1, l1] = momentum();
  // equal and opposite impulses: linear momentum to round-off; the impulses act at p1 and p2,
  // which differ by the gap left after the drift (below 1e-12 of the arm), so the angular
  // momentum changes by |lambda| |gap| per step
  CHECK((p1 - p0).norm() < 1e-12 * p0.norm());
  CHECK((l1 - l0).norm() < 1e-10 * l0.norm());
  CHECK(max_gap < 1e-11);
  const auto [q1, q2] = s.joint_points(0);
  const Vec3 u = gb::point_velocity(s.bodies(), 0, q1) - gb::point_velocity(s.bodies(), 1, q2);
  CHECK(u.norm() < 1e-12);
  MESSAGE("joined bodies: |dP|/|P| = ", (p1 - p0).norm() / p0.norm(),
          ", |dL|/|L| = ", (l1 - l0).norm() / l0.norm(), ", max gap ", max_gap);
}

TEST_CASE("body system: two ball joints on an axis make a hinge") {
  // a body hinged on the z axis by two joints at z = +-0.2, gravity along -x: a pendulum about z
  const double m = 1.0, g = 9.81, d = 0.5;
  gb::RigidBody b = body(m, 0.0, Vec3(-d, 0.0, 0.0));
  b.inertia = gb::inertia_tensor(0.02, 0.03, 0.04, 0.0, 0.0, 0.0);
  const double a = 0.01;
  b.position = Vec3(-d * std::cos(a), d * std::sin(a), 0.0);
  gb::BodySystem s(Vec3(-g, 0.0, 0.0));
  s.add_body(b);
  s.add_ball_joint(0, Vec3(0.0, 0.0, 0.2));
  s.add_ball_joint(0, Vec3(0.0, 0.0, -0.2));
  const double T0 = 2.0 * pi * std::sqrt((0.04 + m * d * d) / (m * g * d));
  Crossings c;
  const double h = 1e-3;
  for (int n = 0; n < static_cast<int>(10 * T0 / h); ++n) {
    s.step(h);
    c.add(s.time(), s.bodies().position[0].y());
  }
  CHECK(c.period() == approx(T0 * (1.0 + a * a / 16.0)).epsilon(2e-6));
  CHECK(std::abs(s.bodies().position[0].z()) < 1e-12);
  MESSAGE("hinge: period error ", c.period() / (T0 * (1.0 + a * a / 16.0)) - 1.0);
  // at rest the two joints carry the weight together: vertical (x) reactions sum to m g
  CHECK((s.joint_result(0).reaction + s.joint_result(1).reaction).x() ==
        approx(m * g).epsilon(1e-2));
}

TEST_CASE("body system: a torsion spring to a fixed frame oscillates at sqrt(k/J)") {
  const double k = 8.0, Jz = 0.5;
  gb::RigidBody b = body(1.0, 0.0, Vec3(0.3, 0.0, 0.0));
  b.inertia = gb::inertia_tensor(0.3, 0.4, Jz, 0.0, 0.0, 0.0);
  b.omega = Vec3(0.0, 0.0, 0.2);
  gb::BodySystem s;
  s.add_body(b);
  gb::TorsionSpringParams p;
  p.yaw.spring = linear_table(k);
  s.add_torsion_spring(p, 0, gb::world, Vec3::UnitZ(), Vec3::UnitX());
  const double w = std::sqrt(k / Jz), T = 2.0 * pi / w, h = T / 2000.0;
  Crossings c;
  for (int n = 0; n < 20 * 2000; ++n) {
    s.step(h);
    c.add(s.time(), s.torsion_result(0).angles.z());
  }
  CHECK(c.period() == approx(T).epsilon(1e-6));
  MESSAGE("torsion: period error ", c.period() / T - 1.0);
  const auto list = s.critical_torsion(1);
  REQUIRE(list.size() == 1);
  CHECK(list[0].omega == approx(w).epsilon(1e-12));
}

TEST_CASE("body system: the spring-mass system is stable at 0.99 h_crit and not at 1.01 h_crit") {
  for (const double xi : {0.0, 0.1, 0.5, 1.0}) {
    CAPTURE(xi);
    gb::BodySystem probe = oscillator(2.0, 800.0, xi, 0.1);
    const double hc = probe.critical();
    CHECK(hc == approx(gb::critical_step(20.0, xi)).epsilon(1e-12));
    for (const double f : {0.99, 1.01}) {
      gb::BodySystem s = oscillator(2.0, 800.0, xi, 0.1);
      double amp = 0.0;
      for (int n = 0; n < 2000; ++n) {
        s.step(f * hc);
        const double x = std::abs(s.bodies().position[0].x());
        amp = std::isfinite(x) ? std::max(amp, x) : std::numeric_limits<double>::infinity();
      }
      CAPTURE(f);
      // initial amplitude v0 / w = 5e-3 m
      if (f < 1.0)
        CHECK(amp < 10 * 5e-3);
      else
        CHECK(amp > 1e3 * 5e-3);
    }
  }
}

TEST_CASE("body system: CRITICAL lists the n lowest estimates in order") {
  gb::BodySystem s;
  // body 0: two parallel springs to fixed points (k = 100, 300); body 1: one spring (k = 50) to
  // body 2; body 2 also on a spring (k = 1000, xi = 0.2) to a fixed point
  s.add_body(body(1.0, 1e-3, Vec3::Zero()));
  s.add_body(body(2.0, 1e-3, Vec3(0.0, 2.0, 0.0)));
  s.add_body(body(4.0, 1e-3, Vec3(0.0, 3.0, 0.0)));
  s.add_spring({.spring = linear_table(100.0)}, 0, Vec3::Zero(), gb::world, Vec3(1.0, 0.0, 0.0));
  s.add_spring({.spring = linear_table(300.0)}, 0, Vec3::Zero(), gb::world, Vec3(-1.0, 0.0, 0.0));
  s.add_spring({.spring = linear_table(50.0)}, 1, Vec3(0.0, 2.0, 0.0), 2, Vec3(0.0, 3.0, 0.0));
  s.add_spring({.spring = linear_table(1000.0), .damping_ratio = 0.2}, 2, Vec3(0.0, 3.0, 0.0),
               gb::world, Vec3(0.0, 4.0, 0.0));
  const auto c = s.critical(3, 10);
  const double w0 = 10.0, w1 = std::sqrt(300.0), w2 = std::sqrt(50.0 / (2.0 * 4.0 / 6.0));
  const double w3 = std::sqrt(1000.0 / 4.0);
  REQUIRE(c.springs.size() == 3);
  // ascending: spring 3 (w 15.8, xi 0.2), spring 1 (w 17.3), spring 0 (w 10)
  CHECK(c.springs[0].index == 3);
  CHECK(c.springs[1].index == 1);
  CHECK(c.springs[2].index == 0);
  CHECK(c.springs[0].omega == approx(w3).epsilon(1e-12));
  CHECK(c.springs[0].damping_ratio == 0.2);
  CHECK(c.springs[0].step == approx(gb::critical_step(w3, 0.2)).epsilon(1e-12));
  CHECK(c.springs[1].omega == approx(w1).epsilon(1e-12));
  CHECK(c.springs[2].omega == approx(w0).epsilon(1e-12));
  for (std::size_t i = 1; i < c.springs.size(); ++i)
    CHECK(c.springs[i - 1].step <= c.springs[i].step);
  // bodies: sqrt of the sum of the omega^2 of their springs; the largest damping ratio
  // (body 2: w 17.0, xi 0.2, h 0.0973; body 0: w 20, h 0.1; body 1: w 6.1)
  REQUIRE(c.bodies.size() == 3);
  CHECK(c.bodies[0].index == 2);
  CHECK(c.bodies[0].omega == approx(std::sqrt(w3 * w3 + w2 * w2)).epsilon(1e-12));
  CHECK(c.bodies[0].damping_ratio == 0.2);
  CHECK(c.bodies[0].step ==
        approx(gb::critical_step(std::sqrt(w3 * w3 + w2 * w2), 0.2)).epsilon(1e-12));
  CHECK(c.bodies[1].index == 0);
  CHECK(c.bodies[1].omega == approx(20.0).epsilon(1e-12)); // sqrt((100 + 300) / 1)
  CHECK(c.bodies[1].damping_ratio == 0.0);
  CHECK(c.bodies[2].index == 1);
  CHECK(c.bodies[2].omega == approx(w2).epsilon(1e-12));
  for (std::size_t i = 1; i < c.bodies.size(); ++i)
    CHECK(c.bodies[i - 1].step <= c.bodies[i].step);
  CHECK(s.critical() == c.bodies[0].step);
  CHECK(s.critical(1, 1).springs.size() == 1);
  CHECK(s.critical(0, 0).bodies.empty());
}

TEST_CASE(
    "body system: adaptive stepping follows factor x the critical step, off springs give none") {
  // a body falls onto a critically damped point-to-plane contact element (no force while above
  // the plane) and comes to rest on it
  const double m = 1.0, k = 1e4, g = 9.81, xi = 1.0;
  gb::BodySystem s(Vec3(0.0, 0.0, -g));
  s.add_body(body(m, 1e-3, Vec3(0.0, 0.0, 0.05)));
  gb::SpringParams p{.spring = Table({-1.0, 0.0, 1.0}, {-k, 0.0, 0.0}),
                     .damping_ratio = xi,
                     .geometry = gb::SpringGeometry::point_to_plane};
  s.add_spring(p, 0, Vec3(0.0, 0.0, 0.05), gb::world, Vec3::Zero(), Vec3::UnitZ());
  const double h = 1e-2, hc = gb::critical_step(std::sqrt(k / m), xi); // 8.3e-3 s
  // open: no current estimate; the bound takes the table's stiff branch
  CHECK(std::isinf(s.critical()));
  CHECK(s.critical_bound() == approx(hc).epsilon(1e-12));
  CHECK(s.critical_bound(1, 1).springs.at(0).step == approx(hc).epsilon(1e-12));
  s.set_adaptive(0.5);
  std::vector<double> steps;
  double last = s.time();
  auto record = [&](const gb::BodySystem& sys) {
    steps.push_back(sys.time() - last);
    last = sys.time();
  };
  s.run(0.5, h, record);
  CHECK(s.time() == approx(0.5).epsilon(1e-14));
  const auto near = [](double a, double b) { return std::abs(a - b) < 1e-9 * b; };
  const auto big = std::count_if(steps.begin(), steps.end(), [&](double x) { return near(x, h); });
  const auto small =
      std::count_if(steps.begin(), steps.end(), [&](double x) { return near(x, 0.5 * hc); });
  CHECK(big >= 10);  // the fall of 0.1 s: the open contact gives no limit
  CHECK(small > 80); // at rest on the contact: half the critical step
  // the rest: the last step, shortened to end at 0.5 s
  CHECK(big + small == static_cast<long>(steps.size()) - 1);
  CHECK(steps.back() <= 0.5 * hc);
  // resting on the contact: m g = k |s|
  CHECK(s.spring_result(0).stroke == approx(-m * g / k).epsilon(1e-6));
  MESSAGE("adaptive: ", big, " steps of h, ", small, " of h_crit / 2, of ", steps.size());
}

TEST_CASE("body system: a zero-length spring acts once its points separate") {
  // a body (m = 2 kg) at a fixed point, tied to it by a point-to-point spring of zero length
  // (k = 1e4 N/m) and launched along x at 1 m/s: no force at the start (the direction is
  // undefined), then x(t) = (v / w) sin(w t), w = sqrt(k / m), along the line of launch
  const double m = 2.0, k = 1e4, v = 1.0, w = std::sqrt(k / m);
  gb::BodySystem s;
  s.add_body(body(m, 1.0, Vec3::Zero(), Vec3(v, 0.0, 0.0)));
  gb::SpringParams p{.spring = linear_table(k, 1.0)};
  s.add_spring(p, 0, Vec3::Zero(), gb::world, Vec3::Zero());
  // the current estimate has no direction; the bound takes the stiffest one (m here)
  CHECK(std::isinf(s.critical()));
  CHECK(s.critical_bound() == approx(gb::critical_step(w, 0.0)).epsilon(1e-12));
  CHECK(s.spring_result(0).force.norm() == 0.0);
  const double h = 1e-3 / w, quarter = 0.5 * pi / w;
  s.run(quarter, h);
  const Vec3 x = s.bodies().position[0];
  // the run ends on a whole step, up to h past the quarter period: an error below (w h)^2
  CHECK(x.x() == approx(v / w).epsilon(1e-5));
  CHECK(std::abs(x.y()) + std::abs(x.z()) == 0.0);
  CHECK(s.spring_result(0).length == approx(v / w).epsilon(1e-5));
  CHECK(s.spring_result(0).total == approx(k * v / w).epsilon(1e-5));
}

TEST_CASE("body system: an unspring rule breaks a spring and the body then falls freely") {
  const double m = 1.0, k = 100.0, g = 9.81;
  gb::BodySystem s(Vec3(0.0, 0.0, -g));
  s.add_body(body(m, 1e-3, Vec3::Zero(), Vec3(0.0, 0.0, -1.0)));
  s.add_spring({.spring = linear_table(k)}, 0, Vec3::Zero(), gb::world, Vec3(0.0, 0.0, 1.0));
  s.add_unspring({.tsprings = {0}, .msprings = {0}, .max = 15.0});
  const double h = 1e-4;
  long fired_at = -1;
  for (int n = 0; n < 5000 && fired_at < 0; ++n) {
    s.step(h);
    if (s.unspring(0).fired()) fired_at = s.step_count();
  }
  REQUIRE(fired_at > 0);
  CHECK(s.spring_result(0).elastic > 15.0);
  CHECK(s.spring_state(0).code == gb::spring_code::inactive);
  // from the next step on only gravity acts: v changes by g h a step
  for (int n = 0; n < 100; ++n) {
    const double v0 = s.bodies().velocity[0].z();
    s.step(h);
    CHECK(s.bodies().velocity[0].z() - v0 == approx(-g * h).epsilon(1e-9));
    CHECK(s.spring_result(0).force.norm() == 0.0);
  }
}

TEST_CASE("body system: bad input raises InputError naming the object, the value and the range") {
  gb::BodySystem s;
  s.add_body(body(1.0, 1.0, Vec3::Zero()));
  s.add_body(body(1.0, 1.0, Vec3(1.0, 0.0, 0.0)));
  const gb::SpringParams p{.spring = linear_table(10.0)};
  std::string e = error_of([&] { s.add_spring(p, 2, Vec3::Zero(), gb::world, Vec3::UnitX()); });
  CHECK(has(e, "SPRING 0: body1 = 2 is invalid; valid range: [0, 2) (a body)"));
  e = error_of([&] { s.add_spring(p, 0, Vec3::Zero(), -2, Vec3::UnitX()); });
  CHECK(has(e, "body2 = -2 is invalid; valid range: [0, 2) or world (-1)"));
  e = error_of([&] { s.add_spring(p, gb::world, Vec3::Zero(), 0, Vec3::UnitX()); });
  CHECK(has(e, "body1 = -1"));
  e = error_of([&] { s.add_spring(p, 0, Vec3::Zero(), 0, Vec3::UnitX()); });
  CHECK(has(e, "body2 = 0 is invalid; valid range: a body other than body1"));
  e = error_of([&] { s.add_spring(p, 0, Vec3::Zero(), gb::world, Vec3::UnitX(), Vec3::UnitZ()); });
  CHECK(has(e, "|normal| = 1 is invalid"));
  gb::SpringParams plane = p;
  plane.geometry = gb::SpringGeometry::point_to_plane;
  e = error_of([&] { s.add_spring(plane, 0, Vec3::Zero(), gb::world, Vec3::UnitX()); });
  CHECK(has(e, "|normal| = 0 is invalid; valid range: (0, inf)"));
  e = error_of([&] { s.add_ball_joint(1, Vec3::Zero(), 1); });
  CHECK(has(e, "BALL_JOINT 0: body2 = 1 is invalid; valid range: a body other than body1 = 1"));
  e = error_of([&] { s.add_ball_joint(5, Vec3::Zero()); });
  CHECK(has(e, "BALL_JOINT 0: body1 = 5 is invalid; valid range: [0, 2) (a body)"));
  e = error_of(
      [&] { s.add_ball_joint(0, Vec3(std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0)); });
  CHECK(has(e, "BALL_JOINT 0: point = (nan"));
  e = error_of([&] { s.add_torsion_spring({}, 1, 1, Vec3::UnitZ(), Vec3::UnitX()); });
  CHECK(has(e, "TORSION_SPRING 0: body2 = 1 is invalid"));
  e = error_of([&] { s.step(0.0); });
  CHECK(has(e, "BodySystem::step: h = 0 is invalid; valid range: (0, inf)"));
  e = error_of([&] { s.run(1.0, -1e-3); });
  CHECK(has(e, "BodySystem::run: h = -0.001 is invalid"));
  e = error_of([&] { s.run(-1.0, 1e-3); });
  CHECK(has(e, "BodySystem::run: duration = -1 is invalid"));
  e = error_of([&] { s.set_adaptive(1.5); });
  CHECK(has(e, "BodySystem: adaptive factor = 1.5 is invalid; valid range: [0, 1]"));
  e = error_of([&] { s.add_unspring({.tsprings = {0}, .msprings = {0}, .max = 1.0}); });
  CHECK(has(e, "UNSPRING 0: tsprings[0] = 0 is invalid; valid range: [0, 0)"));
  {
    // the springs a rule activates: dormant ones, not those it undoes
    gb::BodySystem u;
    u.add_body(body(1.0, 1.0, Vec3::Zero()));
    u.add_spring(p, 0, Vec3::Zero(), gb::world, Vec3::UnitX());
    gb::SpringParams dormant = p;
    dormant.inactive = true;
    u.add_spring(dormant, 0, Vec3::Zero(), gb::world, Vec3::UnitY());
    e = error_of(
        [&] { u.add_unspring({.tsprings = {0}, .msprings = {0}, .max = 1.0, .activate = {0}}); });
    CHECK(has(e, "UNSPRING 0: activate[0] = 0 is invalid; valid range: a dormant spring"));
    u.add_spring(dormant, 0, Vec3::Zero(), gb::world, Vec3::UnitZ());
    e = error_of([&] {
      u.add_unspring({.tsprings = {0}, .msprings = {0, 1}, .max = 1.0, .activate = {2, 1}});
    });
    CHECK(has(e, "activate[1] = 1 is invalid; valid range: a spring not in msprings"));
    CHECK(u.add_unspring({.tsprings = {0}, .msprings = {0}, .max = 1.0, .activate = {1, 2}}) == 0);
    // loads on bodies added through bodies() (the arrays grow with them)
    u.bodies().add(body(2.0, 1.0, Vec3(0, 0, 5)));
    u.set_external_load(1, Vec3(0, 0, 3), Vec3(0, 1, 0));
    CHECK(u.external_load(1).first == Vec3(0, 0, 3));
    u.bodies().add(body(2.0, 1.0, Vec3(0, 0, 9)));
    CHECK(u.external_load(2).first == Vec3::Zero());
    CHECK(has(error_of([&] { (void)u.external_load(3); }), "body = 3"));
  }
  e = error_of([&] { s.set_damping(Vec3(-1.0, 0.0, 0.0), Vec3(Vec3::Zero())); });
  CHECK(
      has(e, "BodySystem damping: coefficient = -1 at t = 0 s is invalid; valid range: [0, inf)"));
  e = error_of([&] { s.steps(-1, 1e-3); });
  CHECK(has(e, "BodySystem::steps: n = -1 is invalid; valid range: [0, inf) steps"));
  s.joint_tolerance = -1.0;
  e = error_of([&] { s.step(1e-3); });
  CHECK(has(e, "BodySystem: joint_tolerance = -1 is invalid; valid range: (0, inf)"));
  s.joint_tolerance = 1e-12;
  // nothing was added by the failed calls
  CHECK(s.spring_count() == 0);
  CHECK(s.joint_count() == 0);
  CHECK(s.torsion_spring_count() == 0);
}

TEST_CASE("body system: histories of bodies, springs, torsion springs and joints as CSV") {
  namespace io = grain::io;
  const auto dir = std::filesystem::temp_directory_path() / "grain_body_system_history";
  std::filesystem::remove_all(dir);
  gb::BodySystem s(Vec3(0.0, 0.0, -9.81));
  s.add_body(body(1.0, 0.01, Vec3(0.0, 0.0, -0.5)));
  s.add_body(body(2.0, 0.02, Vec3(1.0, 0.0, 0.0), Vec3(0.0, 0.1, 0.0)));
  s.add_ball_joint(0, Vec3::Zero());
  s.add_spring({.spring = linear_table(50.0), .damping_ratio = 0.1}, 1, Vec3(1.0, 0.0, 0.0),
               gb::world, Vec3(2.0, 0.0, 0.0));
  gb::TorsionSpringParams tp;
  tp.yaw.spring = linear_table(3.0);
  s.add_torsion_spring(tp, 1, 0, Vec3::UnitZ(), Vec3::UnitX());
  const std::string path = (dir / "h.csv").string();
  s.run(0.01, 1e-3,
        io::every_steps(
            5, io::csv(path, gb::body_history({1}, {"PX", "DY", "|V|", "FX"}),
                       gb::spring_history({0}, {"LENGTH", "STROKE", "F", "SF", "FF", "SS"}),
                       gb::torsion_history({0}, {"YAW", "TRQTOT_Y", "ZDIR_Z"}),
                       gb::joint_history({0}, {"JREAC_Z", "|JREAC|"}))));
  std::ifstream in(path);
  std::string header, row, last;
  std::getline(in, header);
  int rows = 0;
  while (std::getline(in, row)) {
    ++rows;
    last = row;
  }
  CHECK(header == "time [s],step,PX_body1 [m],DY_body1 [m],|V|_body1 [m/s],FX_body1 [N],"
                  "LENGTH_spring0 [m],STROKE_spring0 [m],F_spring0 [N],SF_spring0 [N],"
                  "FF_spring0 [N],SS_spring0,YAW_torsion0 [rad],TRQTOT_Y_torsion0 [N m],"
                  "ZDIR_Z_torsion0,JREAC_Z_joint0 [N],|JREAC|_joint0 [N]");
  CHECK(rows == 3); // steps 0, 5, 10
  std::vector<double> v;
  std::stringstream ss(last);
  for (std::string cell; std::getline(ss, cell, ',');)
    v.push_back(std::stod(cell));
  REQUIRE(v.size() == 17);
  const auto& B = s.bodies();
  CHECK(v[0] == approx(0.01).epsilon(1e-14));
  CHECK(v[1] == 10);
  CHECK(v[2] == B.position[1].x());
  CHECK(v[3] == approx(B.position[1].y()).epsilon(1e-15)); // y0 = 0
  CHECK(v[4] == B.velocity[1].norm());
  CHECK(v[5] == B.force[1].x());
  CHECK(v[6] == s.spring_result(0).length);
  CHECK(v[8] == s.spring_result(0).total);
  CHECK(v[11] == gb::spring_code::regular);
  CHECK(v[12] == s.torsion_result(0).angles.z());
  CHECK(v[13] == s.torsion_result(0).total_torque.z());
  CHECK(v[14] == s.torsion_result(0).z.z());
  CHECK(v[15] == s.joint_result(0).reaction.z());
  CHECK(v[16] == s.joint_result(0).reaction.norm());
  // unknown entities and items are InputErrors naming the valid ones, before the file is made
  std::string e = error_of([&] {
    s.run(0.001, 1e-3,
          io::every_steps(1,
                          io::csv((dir / "bad.csv").string(), gb::spring_history({0}, {"FORCE"}))));
  });
  CHECK(has(e, "grain::bodies::spring_history: entity = 'FORCE' is invalid; valid values: "
               "LENGTH, STROKE, F, SF, FF, SS"));
  e = error_of([&] {
    s.run(0.001, 1e-3,
          io::every_steps(
              1, io::csv((dir / "bad.csv").string(), gb::joint_history({3}, {"JREAC_X"}))));
  });
  CHECK(has(e, "grain::bodies::joint_history: item = 3 is invalid; valid range: [0, 1)"));
  CHECK(!std::filesystem::exists(dir / "bad.csv"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("body system: VTK files of bodies, springs and joints") {
  namespace io = grain::io;
  const auto dir = std::filesystem::temp_directory_path() / "grain_body_system_vtk";
  std::filesystem::remove_all(dir);
  gb::BodySystem s(Vec3(0.0, 0.0, -9.81));
  s.add_body(body(1.0, 0.01, Vec3(0.0, 0.0, -0.5)));
  s.add_ball_joint(0, Vec3::Zero());
  s.add_spring({.spring = Table({-1.0, 0.0, 1.0}, {-100.0, 0.0, 0.0}),
                .geometry = gb::SpringGeometry::point_to_plane},
               0, Vec3(0.0, 0.0, -0.5), gb::world, Vec3(3.0, 1.0, -1.0), Vec3::UnitZ());
  s.run(0.003, 1e-3, io::every_steps(1, gb::body_vtk((dir / "sys").string())));
  for (const char* kind : {"bodies", "springs", "joints"}) {
    CAPTURE(kind);
    CHECK(std::filesystem::exists(dir / (std::string("sys_") + kind + "_000003.vtk")));
    CHECK(!std::filesystem::exists(dir / (std::string("sys_") + kind + "_000004.vtk")));
    CHECK(std::filesystem::exists(dir / (std::string("sys_") + kind + ".vtk.series")));
  }
  CHECK(!std::filesystem::exists(dir / "sys_meshes_000000.vtk")); // no mesh bodies
  // the spring is drawn from point 1 to its foot on the plane z = -1
  const auto [p1, p2] = gb::spring_line(s, 0);
  CHECK((p2 - Vec3(p1.x(), p1.y(), -1.0)).norm() < 1e-15);
  std::ifstream in(dir / "sys_springs_000003.vtk");
  std::stringstream text;
  text << in.rdbuf();
  CHECK(has(text.str(), "grain springs t = 0.003"));
  CHECK(has(text.str(), "LINES 1 3\n2 0 1\n"));
  CHECK(has(text.str(), "SCALARS state int 1"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("body system: a mesh body keeps its surface and colours") {
  // a unit cube (hexahedron) and a pyramid on its top face, with the cube's bottom in colour 4
  const gb::Mesh mesh{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0), Vec3(0, 0, 1),
                       Vec3(1, 0, 1), Vec3(1, 1, 1), Vec3(0, 1, 1), Vec3(0.5, 0.4, 1.5)},
                      {{{0, 1, 2, 3, 4, 5, 6, 7}, 1000.0}, {{4, 5, 6, 7, 8}, 500.0}}};
  const gb::FaceColors colors{2, {{{3, 2, 1, 0}, 4}}};
  gb::BodySystem s;
  s.add_body(body(1.0, 0.01, Vec3(0.0, 0.0, -0.5)));
  // a bad colour list adds nothing
  CHECK(has(error_of([&] {
              s.add_mesh_body(mesh, {2, {{{0, 1, 2}, 4}}}, Vec3::Zero(), Vec3::Zero(), "block");
            }),
            "block face colour 0: nodes = (0, 1, 2) is invalid"));
  CHECK(s.bodies().size() == 1);
  CHECK(s.mesh_count() == 0);
  const auto i = s.add_mesh_body(mesh, colors, Vec3(0.1, 0, 0), Vec3(0, 0, 2), "block");
  CHECK(i == 1);
  CHECK(s.mesh_count() == 1);
  CHECK(s.mesh_body_index(0) == 1);
  const auto want = gb::mesh_surface(mesh, colors, "block");
  const auto& got = s.mesh_surface(0);
  CHECK(got.faces == want.faces);
  CHECK(got.colors == want.colors);
  CHECK(got.faces.size() == 9); // 5 faces of the cube and 4 of the pyramid: the top is shared
  CHECK(std::count(got.colors.begin(), got.colors.end(), 4) == 1);
  const auto b = gb::mesh_body(mesh);
  CHECK(s.bodies().mass[i] == b.mass);
  CHECK(s.bodies().position[i] == b.position);
  CHECK(s.bodies().velocity[i] == Vec3(0.1, 0, 0));
  CHECK(s.bodies().radius[i] == 0.0);
  // the surface nodes sit at the mesh's nodes: world = position + rotation * local
  for (const Vec3& x : got.nodes) {
    bool found = false;
    for (const Vec3& n : mesh.nodes)
      found = found || (gb::to_world(s.bodies(), i, x) - n).norm() < 1e-14;
    CHECK(found);
  }
  CHECK_THROWS_AS((void)s.mesh_surface(1), std::out_of_range);
}

TEST_CASE("body system: global damping slows a free body as exp(-d t)") {
  // F = -m d_v v and T = -J d_w omega (per world axis): v(t) = v0 exp(-d_v t) and, for a spin
  // about a principal axis, omega(t) = omega0 exp(-d_w t)
  gb::BodySystem s;
  gb::RigidBody b = body(2.0, 0.0, Vec3::Zero(), Vec3(1.0, -2.0, 0.5));
  b.inertia = gb::inertia_tensor(0.1, 0.2, 0.3, 0.0, 0.0, 0.0);
  b.omega = Vec3(0.0, 0.0, 3.0);
  s.add_body(b);
  s.set_damping(Vec3(0.5, 1.0, 2.0), Vec3(0.0, 0.0, 1.5));
  const double h = 1e-3;
  s.run(1.0, h);
  const Vec3 v = s.bodies().velocity[0];
  // The loads see the half-step velocity w = v(t + h/2): w decays by (1 - d h) a step and
  // v(t) = v0 (1 - d h/2)^2 (1 - d h)^(n-1) after n steps, exp(-d t) to a relative
  // -d^2 h t / 2 (first order in h: -1.25e-4, -5e-4, -2e-3 for d = 0.5, 1, 2 here).
  const auto discrete = [&](double d) {
    return std::pow(1.0 - 0.5 * d * h, 2) * std::pow(1.0 - d * h, 999.0);
  };
  CHECK(v.x() == approx(discrete(0.5)).epsilon(1e-12));
  CHECK(v.y() == approx(-2.0 * discrete(1.0)).epsilon(1e-12));
  CHECK(v.z() == approx(0.5 * discrete(2.0)).epsilon(1e-12));
  CHECK(s.bodies().omega[0].z() == approx(3.0 * discrete(1.5)).epsilon(1e-12));
  for (const double d : {0.5, 2.0})
    CHECK(discrete(d) / std::exp(-d) - 1.0 == approx(-0.5 * d * d * h).epsilon(2e-3));
}

TEST_CASE("body system: attachment points and the plane normal move with the bodies") {
  gb::BodySystem s;
  s.add_body(body(1.0, 0.1, Vec3(0.0, 0.0, 1.0)));
  s.add_body(body(1.0, 0.1, Vec3(2.0, 0.0, 0.0)));
  const gb::SpringParams p{.spring = Table({-1.0, 0.0, 1.0}, {-10.0, 0.0, 0.0}),
                           .geometry = gb::SpringGeometry::point_to_plane};
  s.add_spring(p, 0, Vec3(0.0, 0.0, 1.0), 1, Vec3(2.0, 0.0, 0.5), Vec3::UnitZ());
  s.initialize();
  CHECK((s.spring_result(0).direction - Vec3(0.0, 0.0, -1.0)).norm() < 1e-15);
  CHECK(s.spring_result(0).length == approx(0.5).epsilon(1e-15));
  // turn body 2 by 90 degrees about x and move it: the plane turns and moves with it
  const Eigen::Quaterniond r(Eigen::AngleAxisd(pi / 2, Vec3::UnitX()));
  auto& B = s.bodies();
  B.orientation[1] = r * B.orientation[1];
  B.position[1] += Vec3(0.0, 0.0, 0.25);
  s.initialize();
  const Vec3 n = r * Vec3::UnitZ(); // (0, -1, 0)
  const Vec3 plane_point = B.position[1] + r * Vec3(0.0, 0.0, 0.5);
  CHECK((s.spring_points(0).second - plane_point).norm() < 1e-15);
  CHECK((s.spring_result(0).direction + n).norm() < 1e-15);
  CHECK(s.spring_result(0).length ==
        approx(n.dot(Vec3(0.0, 0.0, 1.0) - plane_point)).scale(1.0).epsilon(1e-15));
  // the body-2 reaction acts at point 1 (the contact point)
  const Vec3 p1 = s.spring_points(0).first, f1 = s.spring_result(0).force;
  REQUIRE(f1.norm() > 1.0);
  CHECK((B.torque[1] - (p1 - B.position[1]).cross(-f1)).norm() <= 1e-12 * f1.norm());
}

TEST_CASE("body system: anisotropic global damping never adds rotational energy") {
  // J = R diag(1, 10, 10) R^T with R a turn about z and d_w = (1, 0, 1): J diag(d_w) has a
  // negative symmetric part, so a torque -J (d_w w) would feed the rotation along its
  // eigenvector; the damping torque -S J S w (S = diag(sqrt(d_w))) cannot.
  gb::BodySystem s;
  gb::RigidBody b = body(1.0, 1.0, Vec3::Zero());
  b.inertia = Eigen::Vector3d(1.0, 10.0, 10.0).asDiagonal();
  b.rotation = Eigen::AngleAxisd(0.7, Vec3::UnitZ()).toRotationMatrix();
  const Vec3 dw(1.0, 0.0, 1.0);
  const Eigen::Matrix3d J = b.rotation * b.inertia * b.rotation.transpose();
  const Eigen::Matrix3d JD = J * dw.asDiagonal();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(0.5 * (JD + JD.transpose()));
  REQUIRE(eig.eigenvalues()(0) < -0.5); // the old form would add energy along this axis
  b.omega = eig.eigenvectors().col(0);
  s.add_body(b);
  s.set_damping(Vec3(Vec3::Zero()), dw);
  double e0 = s.kinetic_energy();
  for (int n = 0; n < 2000; ++n) {
    s.step(1e-4);
    const double e = s.kinetic_energy();
    CHECK(e <= e0 * (1.0 + 1e-12));
    e0 = e;
  }
  // and the critical step knows the damping: v <- (1 - d h) v is stable for h < 2 / d
  CHECK(s.critical() == approx(2.0 / 1.0).epsilon(1e-15));
}

TEST_CASE("body system: a heavy body's joint holds as firmly as a light body's") {
  // a body of 1e8 kg pinned to the world next to a 1 kg body pinned to the world: with a
  // regularisation taken from the largest diagonal entry of the joint system (the light body's),
  // the heavy body's joint would keep about 1e-12 x 1e8 = 1e-4 of its relative velocity
  gb::BodySystem s;
  s.add_body(body(1e8, 1e8, Vec3::Zero(), Vec3(1.0, 0.0, 0.0)));
  s.add_body(body(1.0, 1e-2, Vec3(5.0, 0.0, 0.0)));
  s.add_ball_joint(0, Vec3(0.0, 0.0, 1.0));
  s.add_ball_joint(1, Vec3(5.0, 0.0, 1.0));
  s.step(1e-3);
  const auto& B = s.bodies();
  const Vec3 arm = s.joint_points(0).first - B.position[0];
  const Vec3 v_pin = B.velocity[0] + B.omega[0].cross(arm);
  CHECK(v_pin.norm() < 1e-9);
  CHECK(s.joint_result(0).gap < 1e-12);
}
