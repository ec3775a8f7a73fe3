// Restrained and prescribed bodies (Parmec's RESTRAIN and PRESCRIBE): a body restrained to a
// plane oscillates on a zero-length spring as the planar closed form; a body restrained to turn
// about one axis spins steadily and oscillates on a torsion spring at sqrt(k / J_zz) (the
// constraint's reaction, not a plain projection); prescribed velocities and accelerations are
// followed exactly or to the scheme's order; a pendulum on a support whose acceleration is
// prescribed swings to twice the angle atan(a / g); bad input.
#include "../approx.hpp"
#include "../errors.hpp"
#include "../support/tables.hpp"
#include <cmath>
#include <doctest/doctest.h>
#include <grain/bodies/system.hpp>
#include <numbers>
#include <optional>
#include <vector>

using grain::TimeFunction;
using grain::Vec3;
using grain::VectorTimeFunction;
using grain::test::approx;
using grain::test::error_of;
using grain::test::has;
using grain::test::linear_table;
namespace gb = grain::bodies;

namespace {

constexpr double pi = std::numbers::pi;

gb::RigidBody body(double m, const Eigen::Matrix3d& j, const Vec3& x,
                   const Vec3& v = Vec3::Zero()) {
  gb::RigidBody b;
  b.mass = m;
  b.inertia = j;
  b.position = x;
  b.velocity = v;
  return b;
}

/// The rotation angle of q about z, assuming q turns about z only.
double yaw(const Eigen::Quaterniond& q) { return 2.0 * std::atan2(q.z(), q.w()); }

} // namespace

TEST_CASE("body control: a body restrained to a plane oscillates on a zero-length spring") {
  // m = 1000 kg on a zero-length spring k = 1e5 N/m to its start point, restrained along z and in
  // rotation, under gravity along -z, started at v0 = (0.5, 1, 0): x = v0x / w sin(w t), y = 2 x,
  // z = 0, w = 10 rad/s (Parmec's spring_planar deck without its dashpot)
  const double m = 1000.0, k = 1e5, w = std::sqrt(k / m), T = 2.0 * pi / w, h = T / 2000.0;
  gb::BodySystem s(Vec3(0.0, 0.0, -9.81));
  s.add_body(body(m, Eigen::Matrix3d::Identity() * m / 6.0, Vec3::Zero(), Vec3(0.5, 1.0, 0.0)));
  s.add_spring(gb::SpringParams{.spring = linear_table(k)}, 0, Vec3::Zero(), gb::world,
               Vec3::Zero());
  s.restrain(0, {Vec3(0.0, 0.0, 2.0)}, {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()});
  double worst = 0.0, worst_z = 0.0, worst_w = 0.0;
  for (int n = 0; n < 2 * 2000; ++n) {
    s.step(h);
    const double t = s.time();
    const Vec3 x = s.bodies().position[0];
    const double exact = 0.5 / w * std::sin(w * t);
    worst = std::max({worst, std::abs(x.x() - exact), std::abs(x.y() - 2.0 * exact)});
    worst_z = std::max(worst_z, std::abs(x.z()));
    worst_w = std::max(worst_w, s.bodies().omega[0].norm());
  }
  // amplitudes 0.05 m (x) and 0.1 m (y); velocity Verlet's phase error over two periods:
  // 4 pi (w h)^2 / 24 = 5.2e-6 of the amplitude (measured 5.2e-7 m along y)
  CHECK(worst < 1e-5 * 0.1);
  CHECK(worst_z == 0.0);
  CHECK(worst_w == 0.0);
  MESSAGE("restrained planar oscillator: largest error ", worst, " m");
  const auto [lin, ang] = s.restraints(0);
  CHECK(lin.size() == 1);
  CHECK(lin[0].z() == 1.0);
  CHECK(ang.size() == 3);
}

TEST_CASE("body control: a body restrained to turn about z spins steadily and oscillates at "
          "sqrt(k / J_zz)") {
  // principal axes not aligned with z: a free body spun about z would wobble
  const Eigen::Matrix3d J = gb::inertia_tensor(0.3, 0.4, 0.5, 0.05, 0.02, 0.03);
  REQUIRE(std::abs(J.inverse()(2, 2) * J(2, 2) - 1.0) > 1e-3); // a projection would differ
  SUBCASE("steady spin") {
    gb::BodySystem s;
    gb::RigidBody b = body(2.0, J, Vec3::Zero());
    b.omega = Vec3(0.0, 0.0, 1.0);
    s.add_body(b);
    s.restrain(0, {}, {Vec3::UnitX(), Vec3::UnitY()});
    const double h = 1e-3;
    for (int n = 0; n < 3000; ++n)
      s.step(h);
    CHECK((s.bodies().omega[0] - Vec3(0.0, 0.0, 1.0)).norm() < 1e-12);
    const Eigen::Matrix3d R = gb::rotation(s.bodies(), 0);
    const Eigen::Matrix3d Rz = Eigen::AngleAxisd(3.0, Vec3::UnitZ()).toRotationMatrix();
    CHECK((R - Rz).norm() < 1e-10);
  }
  SUBCASE("torsion spring about z") {
    const double k = 8.0, wn = std::sqrt(k / J(2, 2)), T = 2.0 * pi / wn, h = T / 2000.0;
    gb::BodySystem s;
    gb::RigidBody b = body(2.0, J, Vec3::Zero());
    b.omega = Vec3(0.0, 0.0, 0.2);
    s.add_body(b);
    s.restrain(0, {}, {Vec3::UnitX(), Vec3::UnitY()});
    gb::TorsionSpringParams p;
    p.yaw.spring = linear_table(k);
    s.add_torsion_spring(p, 0, gb::world, Vec3::UnitZ(), Vec3::UnitX());
    double worst = 0.0, worst_xy = 0.0;
    for (int n = 0; n < 5 * 2000; ++n) {
      s.step(h);
      const Vec3 om = s.bodies().omega[0];
      worst = std::max(worst, std::abs(om.z() - 0.2 * std::cos(wn * s.time())));
      worst_xy = std::max(worst_xy, std::hypot(om.x(), om.y()));
    }
    // phase error over five periods 10 pi (wn h)^2 / 24 = 1.3e-5 of the amplitude 0.2 rad/s
    CHECK(worst < 2e-5 * 0.2);
    CHECK(worst_xy < 1e-15);
    MESSAGE("restrained torsion: largest error of omega_z ", worst, " rad/s");
  }
}

TEST_CASE("body control: prescribed velocities are followed exactly, accelerations to O(h^2)") {
  SUBCASE("velocities from callables ('vv')") {
    gb::BodySystem s(Vec3(0.0, 0.0, -9.81));
    s.add_body(body(3.0, Eigen::Matrix3d::Identity(), Vec3::Zero()));
    int calls = 0;
    auto lin = VectorTimeFunction<3>::callable([&calls](double t) {
      ++calls;
      return Vec3(t, 0.0, 0.0);
    });
    auto ang = VectorTimeFunction<3>(TimeFunction(0.0), TimeFunction(0.0),
                                     TimeFunction::callable([](double t) { return t; }));
    s.prescribe_motion(0, lin, ang);
    const double h = 0.01;
    s.run(1.0, h);
    // the midpoint rule integrates the linear histories exactly; gravity does not move z
    CHECK(s.bodies().position[0].x() == approx(0.5).epsilon(1e-12));
    CHECK(std::abs(s.bodies().position[0].z()) == 0.0);
    CHECK(s.bodies().velocity[0].x() == approx(1.0).epsilon(1e-12));
    CHECK(s.bodies().omega[0].z() == approx(1.0).epsilon(1e-12));
    CHECK(yaw(s.bodies().orientation[0]) == approx(0.5).epsilon(1e-12));
    // one call per time the vector is needed (mid-step, end of step, and at set-up), not per
    // component
    CHECK(calls <= 2 * 100 + 3);
  }
  SUBCASE("linear acceleration ('av')") {
    gb::BodySystem s;
    s.add_body(body(3.0, Eigen::Matrix3d::Identity(), Vec3::Zero()));
    s.prescribe_motion(
        0,
        VectorTimeFunction<3>(TimeFunction::callable([](double t) { return std::cos(t); }),
                              TimeFunction(0.0), TimeFunction(0.0)),
        std::nullopt, "av");
    s.run(2.0, 1e-3);
    // v = sin t, x = 1 - cos t; midpoint accelerations: errors of order h^2
    CHECK(std::abs(s.bodies().velocity[0].x() - std::sin(2.0)) < 1e-6);
    CHECK(std::abs(s.bodies().position[0].x() - (1.0 - std::cos(2.0))) < 1e-6);
  }
}

TEST_CASE("body control: a pendulum on an accelerated support swings to 2 atan(a / g)") {
  // the support's motion is prescribed (acceleration a along x from rest); the pendulum, a body
  // hanging 1 m below on a ball joint at the support's centre, starts at rest and swings about
  // the tilted effective gravity to twice its angle; the joint must not move the support
  const double a = 2.0, g = 9.81, h = 1e-3;
  gb::BodySystem s(Vec3(0.0, 0.0, -g));
  s.add_body(body(1.0, Eigen::Matrix3d::Identity() * 0.1, Vec3::Zero()));
  s.add_body(body(2.0, Eigen::Matrix3d::Identity() * 0.01, Vec3(0.0, 0.0, -1.0)));
  s.prescribe_motion(0, VectorTimeFunction<3>(Vec3(a, 0.0, 0.0)), VectorTimeFunction<3>(), "aa");
  s.add_ball_joint(1, Vec3::Zero(), 0);
  double largest = 0.0, gap = 0.0;
  for (int n = 0; n < 4000; ++n) {
    s.step(h);
    const Vec3 r = s.bodies().position[1] - s.bodies().position[0];
    largest = std::max(largest, std::atan2(-r.x(), -r.z()));
    gap = std::max(gap, s.joint_result(0).gap);
  }
  const double t = s.time();
  CHECK(s.bodies().velocity[0].x() == approx(a * t).epsilon(1e-12));
  CHECK(s.bodies().position[0].x() == approx(0.5 * a * t * t).epsilon(1e-12));
  CHECK(s.bodies().omega[0].norm() == 0.0);
  CHECK(std::abs(largest - 2.0 * std::atan(a / g)) < 1e-4);
  CHECK(gap < 1e-9);
  MESSAGE("pendulum on an accelerated support: largest angle ", largest, " rad against ",
          2.0 * std::atan(a / g));
}

TEST_CASE("body control: bad input names the body, the value and the valid range") {
  gb::BodySystem s;
  s.add_body(body(1.0, Eigen::Matrix3d::Identity(), Vec3::Zero()));
  CHECK(has(error_of([&] { s.restrain(3, {Vec3::UnitX()}); }), {"restrain", "body", "[0, 1)"}));
  CHECK(has(error_of([&] {
              s.restrain(0, {Vec3::UnitX(), Vec3(2.0, 0.0, 0.0)});
            }),
            {"body 0", "linearly dependent"}));
  CHECK(
      has(error_of([&] { s.restrain(0, {}, {Vec3::Zero()}); }), {"angular direction", "(0, inf)"}));
  CHECK(has(error_of([&] { s.prescribe_motion(0, std::nullopt, std::nullopt); }),
            {"prescribe_motion", "at least one history"}));
  CHECK(has(error_of([&] { s.prescribe_motion(0, VectorTimeFunction<3>(), std::nullopt, "vx"); }),
            {"kind = 'vx'", "'vv', 'va', 'av', 'aa'"}));
  CHECK(has(error_of([] { (void)TimeFunction::callable({}); }), {"callable", "empty"}));
}
