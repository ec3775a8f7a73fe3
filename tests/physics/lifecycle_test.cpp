// Lifecycle of particles: sinks, bounding boxes, creation and destruction times, and what a
// removal or an activation does to the rest of the simulation (ids, neighbour list, contact
// histories), against closed forms.
//
// Semantics under test (include/grain/simulation.hpp, step 7): at the start of a run (bounding
// box and sinks) and at the end of every step, after time advanced to t = n dt, particles whose centre is outside an active bounding box or inside an
// active sink, or whose destruction time is <= t, are removed with their contacts; particles
// whose creation time is <= t are activated. A region is active while t_begin <= t <= t_end.
//
// Free flight is integrated exactly: with no force velocity Verlet moves x by v dt per step
// (round-off only), and under constant gravity from rest it gives z_n = z0 - g (n dt)^2/2 to
// round-off (the scheme is exact for constant accelerations). So "the first step at which the
// centre is outside / inside" is a closed form: wherever a step number is checked exactly, the
// crossing was placed between two step times with a margin of at least 5 % of a step (checked by
// a REQUIRE), so round-off cannot move it.
#include "../approx.hpp"
#include "../errors.hpp"
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <doctest/doctest.h>
#include <grain/grain.hpp>
#include <limits>
#include <numbers>
#include <set>
#include <string>
#include <utility>
#include <vector>

using namespace grain;

namespace {

using Sim3 = Simulation<Sphere, search::CellList, presets::HertzMindlin>;
using Sim2 = Simulation<Disk, search::CellList, presets::HertzMindlin>;

constexpr double g0 = 9.81; // [m/s^2]
constexpr double dt = 1e-5; // [s], far below the Rayleigh time (~4e-4 s) of these particles
constexpr double inf = std::numeric_limits<double>::infinity();

Material soft() {
  return Material{.name = "soft", .density = 2500, .young = 1e7, .poisson = 0.3, .friction = 0.5};
}

template <class Sim>
typename Sim::Params params(const Vec<Sim::dimension>& gravity) {
  typename Sim::Params p;
  p.time_step = dt;
  p.gravity = gravity;
  return p;
}

template <class Sim>
std::set<std::int64_t> active_ids(const Sim& sim) {
  const auto& id = sim.particles().id;
  return {id.begin(), id.end()};
}

template <class Sim>
std::set<std::int64_t> removed_set(const Sim& sim) {
  return {sim.removed_ids().begin(), sim.removed_ids().end()};
}

/// Times [t1, t2] during which x0 + v t lies in the ball (empty: t1 > t2).
std::pair<double, double> inside_times(const regions::Ball<3>& b, const Vec3& x0, const Vec3& v) {
  const Vec3 p = x0 - b.center;
  const double a = v.squaredNorm(), h = p.dot(v), c = p.squaredNorm() - b.radius * b.radius;
  if (a == 0.0) return c <= 0.0 ? std::pair{-inf, inf} : std::pair{inf, -inf};
  const double disc = h * h - a * c;
  if (disc < 0.0) return {inf, -inf};
  return {(-h - std::sqrt(disc)) / a, (-h + std::sqrt(disc)) / a};
}

/// Times [t1, t2] during which x0 + v t lies in the box (slab method; empty: t1 > t2).
std::pair<double, double> inside_times(const regions::Box<3>& b, const Vec3& x0, const Vec3& v) {
  double t1 = -inf, t2 = inf;
  for (int d = 0; d < 3; ++d) {
    if (v[d] == 0.0) {
      if (x0[d] < b.lo[d] || x0[d] > b.hi[d]) return {inf, -inf};
      continue;
    }
    const double a = (b.lo[d] - x0[d]) / v[d], c = (b.hi[d] - x0[d]) / v[d];
    t1 = std::max(t1, std::min(a, c));
    t2 = std::min(t2, std::max(a, c));
  }
  return {t1, t2};
}

/// Smallest distance between x1 + v1 t and x2 + v2 t over [0, T].
double closest(const Vec3& x1, const Vec3& v1, const Vec3& x2, const Vec3& v2, double T) {
  const Vec3 p = x2 - x1, w = v2 - v1;
  const double t = w.squaredNorm() > 0 ? std::clamp(-p.dot(w) / w.squaredNorm(), 0.0, T) : 0.0;
  return (p + w * t).norm();
}

/// Step number n* at which a particle falling from rest under g0 has dropped more than h for
/// the first time (z0 - g0 (n dt)^2/2 < z0 - h); the crossing must lie between step times with
/// a margin of 5 % of a step on either side.
long exit_step(double h) {
  const double s = std::sqrt(2.0 * h / g0) / dt;
  const double frac = s - std::floor(s);
  REQUIRE(frac > 0.05);
  REQUIRE(frac < 0.95);
  return static_cast<long>(std::floor(s)) + 1;
}

/// A particle (id 1) falls from rest at x0 inside the bounding box `region`; its centre leaves
/// the region after a drop of h. A fixed particle (id 0) rests inside, the fixed particles
/// `outside` (ids 2, 3, ...) rest outside. Checks that the fixed outside particles go at the
/// start of the run (before the first step), that the falling one goes exactly at step n* (exit_step) and the one inside
/// never.
template <class Sim, class R>
void check_bounding_box(const R& region, const Vec<Sim::dimension>& x0, double h,
                        const Vec<Sim::dimension>& inside,
                        const std::vector<Vec<Sim::dimension>>& outside) {
  constexpr int D = Sim::dimension;
  using V = Vec<D>;
  const V gravity = -g0 * V::Unit(D - 1);
  Sim sim(params<Sim>(gravity));
  const auto k = sim.add_material(soft());
  const double r = 2e-3;
  sim.add_particle({.position = inside, .radius = r, .material = k, .fixed = true, .id = 0});
  sim.add_particle({.position = x0, .radius = r, .material = k, .id = 1});
  std::set<std::int64_t> out_ids;
  for (std::size_t q = 0; q < outside.size(); ++q) {
    const auto id = static_cast<std::int64_t>(2 + q);
    sim.add_particle({.position = outside[q], .radius = r, .material = k, .fixed = true, .id = id});
    out_ids.insert(id);
  }
  sim.set_bounding_box(region);
  const long n = exit_step(h);

  sim.steps(0); // the particles that start outside go at the start, before the first step
  CHECK(removed_set(sim) == out_ids);
  CHECK(sim.size() == 2);
  sim.steps(1);
  CHECK(removed_set(sim) == out_ids);

  sim.steps(n - 2); // step n* - 1: the falling centre is still inside
  CHECK(removed_set(sim) == out_ids);
  REQUIRE(sim.is_active(1));
  // premise: the fall is the exact free fall (round-off only), 1e-12 relative
  const double t = sim.time();
  const double z = sim.particles().position[sim.index_of(1)][D - 1];
  CHECK(z == test::approx(x0[D - 1] - 0.5 * g0 * t * t).scale(h).epsilon(1e-12));
  MESSAGE("bounding box: exit at step " << n << ", fall error before it "
                                        << z - (x0[D - 1] - 0.5 * g0 * t * t) << " m");

  sim.steps(1); // step n*: it is outside
  auto expected = out_ids;
  expected.insert(1);
  CHECK(removed_set(sim) == expected);
  CHECK(sim.removed_ids().size() == expected.size()); // each id once
  CHECK(!sim.is_active(1));
  CHECK(sim.is_active(0));
  CHECK(sim.size() == 1);

  sim.steps(10); // nothing else goes: the fixed particle inside stays
  CHECK(removed_set(sim) == expected);
  CHECK(sim.is_active(0));
}

/// The tangential force on particle `id` at its contact with a particle (wall = false) or with a
/// wall (wall = true), the normal force, the sliding state, and the force a reset spring would
/// give one step later (K_t |v_t| dt, K_t = 8 G* sqrt(R* delta), tangent damping 0).
struct Tangent {
  Vec3 force = Vec3::Zero();
  double normal = 0.0;
  bool sliding = false;
  double reset = 0.0;
  int found = 0;
};
template <class Sim>
Tangent tangent_of(const Sim& sim, std::int64_t id, bool wall) {
  Tangent t;
  const std::size_t i = sim.index_of(id);
  sim.for_each_contact(
      [&](std::size_t a, std::size_t b, bool is_wall, const auto& geo, const auto& res) {
        if (is_wall != wall || (a != i && (wall || b != i))) return;
        t.force = a == i ? Vec3(res.tangent.force) : Vec3(-res.tangent.force);
        t.normal = res.normal.force;
        t.sliding = res.tangent.sliding;
        const double kt =
            8.0 * sim.pair_properties(0, 0).shear_eff * std::sqrt(geo.r_eff * geo.overlap);
        t.reset = kt * geo.tangential_velocity.norm() * dt;
        ++t.found;
      });
  return t;
}

} // namespace

// ------------------------------------------------------------------------------------------ 1
// Sinks. No gravity, particles far apart in straight flight x0 + v t (the REQUIREs check that no
// two trajectories come within 2 r over the run, so no force ever acts). A ball sink (always
// active) and a box sink active only during [0.02, 0.03] s. A particle is removed iff its
// centre is inside an active sink at some step time t_n <= T: the interval of t during which the
// centre is inside (closed form: roots of a quadratic for the ball, slabs for the box),
// intersected with the activity interval and [0, T], is either longer than 10 steps or empty
// with 10 steps to spare (REQUIRE), so the set is unambiguous. The survivors keep their ids and
// sit at x0 + v T: the round-off of 5000 additions x += v dt is below 5000 ulp(0.2 m) ~ 1.4e-13
// m, so 1e-12 m; their velocities are never touched (exact up to 1e-15 relative).
TEST_CASE(
    "lifecycle: a sink removes exactly the particles whose centres enter it while it is active") {
  const double r = 1e-3, T = 0.05, tb = 0.02, te = 0.03;
  const regions::Ball<3> ball{Vec3::Zero(), 0.02};
  const regions::Box<3> box{Vec3(0.10, -0.02, -0.02), Vec3(0.14, 0.02, 0.02)};
  struct Flight {
    Vec3 x0, v;
  };
  const std::vector<Flight> flights = {
      {Vec3(-0.1, 0, 0), Vec3(2, 0, 0)},                // enters the ball at 0.04 s
      {Vec3(-0.1, 0.019, 0), Vec3(2, 0, 0)},            // grazes inside (0.95 R), enters at 0.047 s
      {Vec3(-0.11, 0.021, 0), Vec3(2, 0, 0)},           // grazes outside (1.05 R): stays
      {Vec3(-0.1, 0, 0.005), Vec3(1, 0, 0)},            // would enter after T (0.08 s): stays
      {Vec3(0, -0.1, 0), Vec3(0, 1.5, 0)},              // would enter at 0.053 s > T: stays
      {Vec3(0.05, 0.05, 0.05), Vec3(-1.2, -1.2, -1.2)}, // along a diagonal, enters at 0.032 s
      {Vec3(0, 0.004, 0.1), Vec3(0, 0, -5)},            // fast, enters at 0.016 s
      {Vec3(0.12, -0.05, 0), Vec3(0, 5, 0)},       // through the box at 0.006-0.014 s: inactive
      {Vec3(0.12, -0.05, 0.01), Vec3(0, 2, 0)},    // in the box 0.015-0.035 s: removed
      {Vec3(0.12, -0.05, -0.01), Vec3(0, 0.9, 0)}, // reaches the box at 0.033 s > t_end: stays
      {Vec3(0.15, 0, 0.008), Vec3(-3, 0, 0)},      // through the inactive box, then the ball
      {Vec3(0.13, 0.015, -0.015), Vec3(0, 0, 0)},  // at rest in the box: removed at t_begin
  };
  const std::size_t n = flights.size();
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b)
      REQUIRE(closest(flights[a].x0, flights[a].v, flights[b].x0, flights[b].v, T) > 2.0 * r);

  std::set<std::int64_t> expected, survivors;
  for (std::size_t a = 0; a < n; ++a) {
    bool removed = false;
    auto [b1, b2] = inside_times(ball, flights[a].x0, flights[a].v);
    auto [x1, x2] = inside_times(box, flights[a].x0, flights[a].v);
    const std::pair<double, double> windows[2] = {{std::max(b1, 0.0), std::min(b2, T)},
                                                  {std::max({x1, tb, 0.0}), std::min({x2, te, T})}};
    for (const auto& [lo, hi] : windows) {
      REQUIRE(std::abs(hi - lo) > 10 * dt); // unambiguous at step resolution
      removed = removed || hi > lo;
    }
    (removed ? expected : survivors).insert(static_cast<std::int64_t>(100 + 7 * a));
  }
  REQUIRE(expected.size() == 7); // the design: 7 removed, 5 survivors

  Sim3 sim(params<Sim3>(Vec3::Zero()));
  const auto k = sim.add_material(soft());
  for (std::size_t a = 0; a < n; ++a)
    sim.add_particle({.position = flights[a].x0,
                      .radius = r,
                      .material = k,
                      .velocity = flights[a].v,
                      .id = static_cast<std::int64_t>(100 + 7 * a)});
  sim.add_sink(ball);
  sim.add_sink(box, tb, te);
  sim.run(T);
  REQUIRE(sim.time() == test::approx(T).epsilon(1e-12));

  CHECK(removed_set(sim) == expected);
  CHECK(sim.removed_ids().size() == expected.size());
  CHECK(active_ids(sim) == survivors);
  CHECK(sim.size() == survivors.size());
  double worst = 0.0;
  for (const auto id : survivors) {
    const auto& f = flights[static_cast<std::size_t>((id - 100) / 7)];
    const std::size_t i = sim.index_of(id);
    const Vec3 x = f.x0 + f.v * sim.time();
    worst = std::max(worst, (sim.particles().position[i] - x).norm());
    CHECK((sim.particles().position[i] - x).norm() <= 1e-12);
    CHECK((sim.particles().velocity[i] - f.v).norm() <= 1e-15 * (1.0 + f.v.norm()));
  }
  MESSAGE("sink: worst survivor position error " << worst << " m");
}

// ------------------------------------------------------------------------------------------ 2
// Bounding boxes. A particle falls from rest inside the region; it must be removed exactly at
// the first step n* with z0 - g (n dt)^2/2 below the exit level (see exit_step: the crossing is
// at least 5 % of a step away from a step time; the fall itself is checked against the closed
// form to 1e-12 of the drop). Fixed particles inside stay, fixed particles outside go at the
// first step. 3D: box (exit through the floor) and ball (x = 12 mm off the centre of a 20 mm
// ball: exit at z = -16 mm). 2D: rectangle, circle, a clockwise triangle with a slanted edge
// y = -x (exit at y = -x0), and an L-shaped hexagon (a non-convex polygon: a particle in its
// notch is outside, one in its foot falls out through the bottom edge).
TEST_CASE("lifecycle: a bounding box removes a falling particle at the step its centre leaves it") {
  SUBCASE("3D box") {
    check_bounding_box<Sim3>(regions::Box<3>{Vec3(-0.05, -0.05, -0.0123), Vec3(0.05, 0.05, 0.05)},
                             Vec3(0.01, 0.02, 0.0), 0.0123, Vec3(-0.02, 0.0, 0.01),
                             {Vec3(0.0, 0.0, 0.053), Vec3(-0.052, 0.0, 0.0)});
  }
  SUBCASE("3D ball") {
    check_bounding_box<Sim3>(regions::Ball<3>{Vec3::Zero(), 0.02}, Vec3(0.012, 0.0, 0.0), 0.016,
                             Vec3(-0.01, 0.0, 0.0), {Vec3(0.0, 0.015, 0.0135)});
  }
  SUBCASE("2D rectangle") {
    check_bounding_box<Sim2>(regions::Box<2>{Vec2(-0.05, -0.0123), Vec2(0.05, 0.05)},
                             Vec2(0.01, 0.0), 0.0123, Vec2(-0.02, 0.01), {Vec2(0.0, 0.053)});
  }
  SUBCASE("2D circle") {
    check_bounding_box<Sim2>(regions::Ball<2>{Vec2::Zero(), 0.02}, Vec2(0.012, 0.0), 0.016,
                             Vec2(-0.01, 0.0), {Vec2(0.015, 0.0135)});
  }
  SUBCASE("2D triangle (clockwise, slanted edge)") {
    check_bounding_box<Sim2>(
        regions::Polygon{{Vec2(-0.05, 0.05), Vec2(0.05, 0.05), Vec2(0.05, -0.05)}}, Vec2(0.02, 0.0),
        0.02, Vec2(0.03, 0.04), {Vec2(-0.01, -0.0005), Vec2(0.0, 0.051)});
  }
  SUBCASE("2D L-shape (non-convex)") {
    check_bounding_box<Sim2>(regions::Polygon{{Vec2(0, 0), Vec2(0.04, 0), Vec2(0.04, 0.01),
                                               Vec2(0.01, 0.01), Vec2(0.01, 0.04), Vec2(0, 0.04)}},
                             Vec2(0.03, 0.0071), 0.0071, Vec2(0.005, 0.03),
                             {Vec2(0.03, 0.02), Vec2(0.02, 0.03), Vec2(0.011, 0.011)});
  }
}

// An activity interval: a bounding box active from t_b on leaves a particle outside alone until
// t_b (first step time >= t_b, t_b placed mid-step), then removes it.
TEST_CASE("lifecycle: a bounding box acts only during its activity interval") {
  Sim3 sim(params<Sim3>(Vec3::Zero()));
  const auto k = sim.add_material(soft());
  sim.add_particle(
      {.position = Vec3(0.2, 0, 0), .radius = 1e-3, .material = k, .fixed = true, .id = 4});
  sim.add_particle(
      {.position = Vec3(0, 0, 0), .radius = 1e-3, .material = k, .fixed = true, .id = 5});
  const long nb = 300;
  sim.set_bounding_box(regions::Ball<3>{Vec3::Zero(), 0.1}, (nb - 0.5) * dt, inf);
  sim.steps(nb - 1);
  CHECK(sim.removed_ids().empty());
  CHECK(sim.size() == 2);
  sim.steps(1);
  CHECK(removed_set(sim) == std::set<std::int64_t>{4});
  CHECK(sim.size() == 1);
  CHECK(sim.is_active(5));
}

// ------------------------------------------------------------------------------------------ 3
// Creation time. Gravity -g z. P (id 1) falls from rest at the origin from t = 0. Q (id 2) is
// created at t_q = 1000.5 dt, so activated at the end of step 1001 (t_q' = 1001 dt), at the
// position beside P's position at that time (centre distance 9.9 mm, r = 5 mm: 0.1 mm overlap;
// the distance is below 2r during the whole wait). F (id 3) is created at 2000.3 dt (t_f' =
// 2001 dt) far away.
// - Before its activation Q is invisible: size() = 1, inactive_count() = 2, is_active false,
//   index_of throws, no contact, and P's fall is the exact free fall (z, and v_x = 0 exactly;
//   1e-12 relative): P feels no force from Q.
// - After it, the contact exists, and P is pushed along -x within the next step by the Hertz
//   force at the 0.1 mm overlap: v_x = -(dt/2) F/m (velocity Verlet's second half kick; the
//   first uses the force of the previous step). The overlap changes by < 1e-8 m in that step and
//   the normal relative speed is ~1e-5 m/s (Tsuji damping ~1e-5 N against F ~ 0.36 N): 1 %.
// - F falls freely after its activation: z = z0 - g (t - t_f')^2/2 and v = -g (t - t_f') with a
//   tolerance of one step of activation time: |dz| <= g tau dt, |dv| <= g dt.
TEST_CASE("lifecycle: a particle is invisible until its creation time, then falls freely") {
  const double r = 5e-3;
  Sim3 sim(params<Sim3>(Vec3(0, 0, -g0)));
  const auto k = sim.add_material(soft());
  const long nq = 1001, nf = 2001;
  const double tq = (nq - 0.5) * dt, tf = (nf - 0.7) * dt;
  const double zq = -0.5 * g0 * (nq * dt) * (nq * dt); // P's height at Q's activation
  sim.add_particle({.position = Vec3::Zero(), .radius = r, .material = k, .id = 1});
  sim.add_particle(
      {.position = Vec3(0.0099, 0, zq), .radius = r, .material = k, .creation_time = tq, .id = 2});
  const Vec3 xf(0.1, 0.05, 0.02);
  sim.add_particle({.position = xf, .radius = r, .material = k, .creation_time = tf, .id = 3});
  CHECK(sim.size() == 1);
  CHECK(sim.inactive_count() == 2);
  CHECK(!sim.is_active(2));
  CHECK_THROWS_AS((void)sim.index_of(2), InputError);

  sim.steps(nq - 1);
  CHECK(sim.size() == 1);
  CHECK(sim.inactive_count() == 2);
  CHECK(!sim.is_active(2));
  CHECK(sim.contact_counts() == std::pair<std::size_t, std::size_t>{0, 0});
  {
    const std::size_t p = sim.index_of(1);
    const double t = sim.time();
    CHECK(sim.particles().position[p].z() == test::approx(-0.5 * g0 * t * t).epsilon(1e-12));
    CHECK(sim.particles().velocity[p].z() == test::approx(-g0 * t).epsilon(1e-12));
    CHECK(sim.particles().velocity[p].x() == 0.0);
    CHECK(sim.particles().position[p].x() == 0.0);
  }

  sim.steps(1); // t = t_q': Q appears, overlapping P
  CHECK(sim.time() == test::approx(nq * dt).epsilon(1e-12));
  CHECK(sim.size() == 2);
  CHECK(sim.inactive_count() == 1);
  CHECK(sim.is_active(2));
  CHECK(!sim.is_active(3));
  CHECK(sim.contact_counts().first == 1);
  CHECK(sim.particles().position[sim.index_of(2)].z() == zq); // it did not move while waiting

  sim.steps(1);
  {
    const auto& pp = sim.pair_properties(0, 0);
    const double mass = soft().density * Sphere{}.volume(r);
    const double delta = 2 * r - 0.0099;
    const double force = 4.0 / 3.0 * pp.young_eff * std::sqrt(0.5 * r) * std::pow(delta, 1.5);
    const double vx = sim.particles().velocity[sim.index_of(1)].x();
    CHECK(vx == test::approx(-0.5 * dt * force / mass).epsilon(0.01));
    MESSAGE("creation: P's v_x after the activation " << vx << " m/s, closed form "
                                                      << -0.5 * dt * force / mass);
  }

  sim.steps(nf - nq - 2); // step nf - 1: F still waits
  CHECK(!sim.is_active(3));
  CHECK(sim.inactive_count() == 1);
  sim.steps(1);
  CHECK(sim.is_active(3));
  CHECK(sim.inactive_count() == 0);
  CHECK(sim.particles().position[sim.index_of(3)] == xf);
  sim.steps(1000);
  const double tau = sim.time() - nf * dt;
  REQUIRE(tau == test::approx(1000 * dt).epsilon(1e-9));
  const std::size_t i = sim.index_of(3);
  const double dz = sim.particles().position[i].z() - (xf.z() - 0.5 * g0 * tau * tau);
  const double dv = sim.particles().velocity[i].z() + g0 * tau;
  CHECK(std::abs(dz) <= g0 * tau * dt);
  CHECK(std::abs(dv) <= g0 * dt);
  CHECK(sim.particles().position[i].x() == xf.x());
  MESSAGE("creation: free fall after activation: dz = " << dz << " m (bound " << g0 * tau * dt
                                                        << "), dv = " << dv << " m/s");
}

// Velocity Verlet is exact for a constant acceleration, and a particle present from the start
// falls as z0 - g t^2/2 to round-off (checked above). A particle activated at t_c' falls as
// z0 - g (t - t_c')^2/2, v = -g (t - t_c') to round-off as well (1e-9 relative after 1000
// steps): on activation it gets its weight as the force of its first half kick.
TEST_CASE("lifecycle: an activated particle falls exactly like one present from the start") {
  Sim3 sim(params<Sim3>(Vec3(0, 0, -g0)));
  const auto k = sim.add_material(soft());
  const long nf = 501;
  sim.add_particle({.position = Vec3::Zero(),
                    .radius = 5e-3,
                    .material = k,
                    .creation_time = (nf - 0.5) * dt,
                    .id = 3});
  sim.steps(nf);
  REQUIRE(sim.is_active(3));
  sim.steps(1000);
  const double tau = sim.time() - nf * dt;
  const std::size_t i = sim.index_of(3);
  CHECK(sim.particles().position[i].z() == test::approx(-0.5 * g0 * tau * tau).epsilon(1e-9));
  CHECK(sim.particles().velocity[i].z() == test::approx(-g0 * tau).epsilon(1e-9));
}

TEST_CASE("lifecycle: a particle activated under a restraint never moves along it") {
  // gravity (1, 0, -g0) with z restrained for all particles: the particle that joins at step 501
  // keeps its z exactly from its first step on (its first half kick sees the restrained weight)
  // and accelerates along x at 1 m/s^2 (1e-9 relative).
  Sim3 sim(params<Sim3>(Vec3(1.0, 0, -g0)));
  const auto k = sim.add_material(soft());
  const long nf = 501;
  sim.add_particle({.position = Vec3(0, 0, 0.25),
                    .radius = 5e-3,
                    .material = k,
                    .creation_time = (nf - 0.5) * dt,
                    .id = 3});
  sim.restrain("all", {Vec3::UnitZ()});
  sim.steps(nf + 1000);
  REQUIRE(sim.is_active(3));
  const double tau = sim.time() - nf * dt;
  const std::size_t i = sim.index_of(3);
  CHECK(sim.particles().position[i].z() == 0.25);
  CHECK(sim.particles().velocity[i].z() == 0.0);
  CHECK(sim.particles().position[i].x() == test::approx(0.5 * tau * tau).epsilon(1e-9));
}

// ------------------------------------------------------------------------------------------ 4
// Destruction time. No gravity, particles far apart in straight flight. A particle is removed at
// the first step time >= its destruction time: id 5 at t_d = 300 dt exactly (the same product
// the simulation computes its time with, so the comparison is exact: removed at step 300, not
// 301), id 6 at 500.5 dt (step 501). Id 8 lives from 200.5 dt to 400.5 dt (steps 201 to 401).
// Id 7 is created at 1000.2 dt and destroyed at 1000.7 dt: both fall due at step 1001, so it
// never appears. Id 9, at rest in a sink that opens at 700.2 dt, also has destruction time
// 700.5 dt: both remove it at step 701, and it is listed once. The others (user ids 100, 50, 3)
// keep their ids and their flights x0 + v t (1e-12 m: round-off of 1000 additions).
TEST_CASE(
    "lifecycle: particles are removed at their destruction time, ids of the others unchanged") {
  Sim3 sim(params<Sim3>(Vec3::Zero()));
  const auto k = sim.add_material(soft());
  const double r = 1e-3;
  struct Flight {
    std::int64_t id;
    Vec3 x0, v;
  };
  const std::vector<Flight> keep = {{100, Vec3(0, 0, 0), Vec3(0.5, 0, 0)},
                                    {50, Vec3(0, 0.05, 0), Vec3(0, -0.3, 0.2)},
                                    {3, Vec3(0.05, 0.05, 0.05), Vec3(0.1, 0.1, -0.4)}};
  for (const auto& f : keep)
    sim.add_particle({.position = f.x0, .radius = r, .material = k, .velocity = f.v, .id = f.id});
  sim.add_particle({.position = Vec3(-0.05, 0, 0),
                    .radius = r,
                    .material = k,
                    .velocity = Vec3(0, 0.1, 0),
                    .destruction_time = 300.0 * dt,
                    .id = 5});
  sim.add_particle({.position = Vec3(-0.05, 0.05, 0),
                    .radius = r,
                    .material = k,
                    .destruction_time = 500.5 * dt,
                    .id = 6});
  sim.add_particle({.position = Vec3(0, -0.05, 0),
                    .radius = r,
                    .material = k,
                    .creation_time = 1000.2 * dt,
                    .destruction_time = 1000.7 * dt,
                    .id = 7});
  sim.add_particle({.position = Vec3(0.05, -0.05, 0),
                    .radius = r,
                    .material = k,
                    .creation_time = 200.5 * dt,
                    .destruction_time = 400.5 * dt,
                    .id = 8});
  sim.add_particle({.position = Vec3(-0.05, -0.05, 0),
                    .radius = r,
                    .material = k,
                    .destruction_time = 700.5 * dt,
                    .id = 9});
  sim.add_sink(regions::Ball<3>{Vec3(-0.05, -0.05, 0), 0.01}, 700.2 * dt);
  CHECK(sim.size() == 6);
  CHECK(sim.inactive_count() == 2);

  auto removed_after = [&](long steps_so_far, long n, const std::set<std::int64_t>& before,
                           const std::set<std::int64_t>& after) {
    sim.steps(n - 1 - steps_so_far);
    CHECK(removed_set(sim) == before);
    sim.steps(1);
    CHECK(removed_set(sim) == after);
  };
  removed_after(0, 201, {}, {});
  CHECK(sim.is_active(8));
  removed_after(201, 300, {}, {5});
  CHECK(!sim.is_active(5));
  removed_after(300, 401, {5}, {5, 8});
  CHECK(!sim.is_active(8));
  removed_after(401, 501, {5, 8}, {5, 8, 6});
  removed_after(501, 701, {5, 8, 6}, {5, 8, 6, 9});
  CHECK(sim.removed_ids().size() == 4); // id 9 once
  CHECK(sim.inactive_count() == 1);     // id 7 still waits
  sim.steps(1000 - 701);
  CHECK(sim.inactive_count() == 1);
  sim.steps(1); // step 1001: id 7's creation and destruction are due
  CHECK(sim.inactive_count() == 0);
  CHECK(!sim.is_active(7));
  CHECK(removed_set(sim) == std::set<std::int64_t>{5, 8, 6, 9, 7}); // listed, never active
  sim.steps(10);
  CHECK(!sim.is_active(7));
  CHECK(sim.size() == 3);
  CHECK(active_ids(sim) == std::set<std::int64_t>{100, 50, 3});
  // an id that was given is not given again, whether its particle ever appeared or not
  for (const std::int64_t id : {7, 9})
    CHECK(grain::test::has(
        grain::test::error_of([&] {
          sim.add_particle({.position = Vec3(0.1, 0.1, 0.1), .radius = r, .material = k, .id = id});
        }),
        "no other particle has or had"));
  for (const auto& f : keep) {
    const Vec3 x = f.x0 + f.v * sim.time();
    CHECK((sim.particles().position[sim.index_of(f.id)] - x).norm() <= 1e-12);
  }
}

// ------------------------------------------------------------------------------------------ 5
// Contact histories of the remaining pairs survive a removal (and an activation in the same
// step). Equal spheres, r = 5 mm, E = 1e7, nu = 0.3, mu = 0.5, tangential damping 0, gravity
// g0 along -n, n = (-1, 0, 1)/sqrt(2):
// - A (id 10) fixed at the origin, B (id 11) resting on it along n, launched at 0.05 m/s along
//   y: a sliding contact (|F_t| = mu F_n) that turns into rolling after ~3 ms;
// - W (id 14) on a plane wall of normal n, launched likewise: a sliding wall contact;
// - D (id 12) fixed far away; N (id 15) fixed far away, created at the removal step;
// - run 1 only: C (id 13) fixed far away, in a ball sink that opens at step 100.
// Run 2 is the same without C. The positions are chosen for the cell list's ordering (x
// fastest, z slowest, from the lower corner of all centres, cells 2 r_max + skin = 11 mm): with C
// (lowest, z = -12 mm) A and B share a cell and B comes first; without C the lowest centre is D
// (z = -5 mm), a cell boundary falls between A and B, and A comes first. So the removal flips
// the pair's index order (the history is carried over reversed), and shifts the indices.
// Checks: right after the removal the tangential forces of both contacts equal run 2's to
// 1e-12 relative, and they are the full mu F_n while the spring of a reset history would give
// only K_t |v_t| dt, less than 1/4 of it; then the trajectories of B and W (x, v, omega) agree
// with run 2 to 1e-12 relative for 600 more steps (through the slide-to-roll transition).
namespace {
Sim3 history_run(bool with_c, long n_rm) {
  const double r = 5e-3, s = std::sqrt(0.5);
  const Vec3 n(-s, 0, s);
  auto prm = params<Sim3>(-g0 * n);
  prm.contact.tangent.damping = 0.0;
  Sim3 sim(prm);
  const auto k = sim.add_material(soft());
  const double gap = 2 * r - 1e-5; // about the static overlap under m g
  sim.add_particle(
      {.position = gap * n, .radius = r, .material = k, .velocity = Vec3(0, 0.05, 0), .id = 11});
  sim.add_particle({.position = Vec3::Zero(), .radius = r, .material = k, .fixed = true, .id = 10});
  sim.add_particle(
      {.position = Vec3(0, 0.03, -0.005), .radius = r, .material = k, .fixed = true, .id = 12});
  const Vec3 w(0.03, 0.08, 0.0);
  sim.add_wall(walls::Plane{w - (r - 1e-5) * n, n}, {.material = k});
  sim.add_particle(
      {.position = w, .radius = r, .material = k, .velocity = Vec3(0, 0.05, 0), .id = 14});
  sim.add_particle({.position = Vec3(0, 0.08, 0),
                    .radius = r,
                    .material = k,
                    .fixed = true,
                    .creation_time = (n_rm - 0.5) * dt,
                    .id = 15});
  if (with_c) {
    const Vec3 c(0, 0.05, -0.012);
    sim.add_particle({.position = c, .radius = r, .material = k, .fixed = true, .id = 13});
    sim.add_sink(regions::Ball<3>{c, 1e-3}, (n_rm - 0.5) * dt);
  }
  return sim;
}
} // namespace

TEST_CASE("lifecycle: a removal keeps the contact histories of the remaining pairs") {
  const long n_rm = 100;
  Sim3 one = history_run(true, n_rm), two = history_run(false, n_rm);
  one.steps(n_rm - 1);
  two.steps(n_rm - 1);
  REQUIRE(one.size() == 5);
  CHECK(one.index_of(11) < one.index_of(10)); // B before A while C exists
  one.steps(1);
  two.steps(1);
  REQUIRE(removed_set(one) == std::set<std::int64_t>{13});
  REQUIRE(one.is_active(15));
  CHECK(one.index_of(10) < one.index_of(11)); // A before B after the removal: order flipped
  CHECK(two.index_of(10) < two.index_of(11));

  for (const bool wall : {false, true}) {
    const std::int64_t id = wall ? 14 : 11;
    const Tangent a = tangent_of(one, id, wall), b = tangent_of(two, id, wall);
    REQUIRE(a.found == 1);
    REQUIRE(b.found == 1);
    CHECK((a.force - b.force).norm() <= 1e-12 * b.force.norm());
    CHECK(a.sliding);
    CHECK(a.force.norm() == test::approx(soft().friction * a.normal).epsilon(1e-12));
    CHECK(a.reset < 0.25 * a.force.norm()); // a reset history would be noticed
    MESSAGE((wall ? "wall" : "pair") << " contact after the removal: |F_t| = " << a.force.norm()
                                     << " N, mu F_n = " << soft().friction * a.normal
                                     << " N, reset spring would give " << a.reset << " N");
  }
  double worst = 0.0;
  bool rolled = false;
  for (int block = 0; block < 6; ++block) {
    one.steps(100);
    two.steps(100);
    for (const std::int64_t id : {11, 14}) {
      const auto i = one.index_of(id), j = two.index_of(id);
      const auto& p = one.particles();
      const auto& q = two.particles();
      const double ex = (p.position[i] - q.position[j]).norm() / q.position[j].norm();
      const double ev = (p.velocity[i] - q.velocity[j]).norm() / q.velocity[j].norm();
      const double ew = (p.omega[i] - q.omega[j]).norm() / q.omega[j].norm();
      CHECK(ex <= 1e-12);
      CHECK(ev <= 1e-12);
      CHECK(ew <= 1e-12);
      worst = std::max({worst, ex, ev, ew});
    }
    rolled = rolled || !tangent_of(one, 11, false).sliding;
  }
  CHECK(rolled); // the comparison covered the sticking (rolling) phase too
  MESSAGE("history: worst relative difference of the trajectories " << worst);
}

// remove_particle: between runs it acts as a destruction time that has come (the same pairs as
// the previous test: removing C by hand one step before the sink would keep the histories of the
// other contacts, and B and W move as in the run without C, 1e-12 relative); before the first
// run it removes the particle before anything is computed; an inactive particle never appears.
TEST_CASE("lifecycle: remove_particle removes a particle now and keeps the other histories") {
  const long n_rm = 100;
  Sim3 one = history_run(true, n_rm), two = history_run(false, n_rm);
  one.steps(n_rm - 1);
  two.steps(n_rm - 1);
  one.remove_particle(13);
  CHECK(!one.is_active(13));
  CHECK(removed_set(one) == std::set<std::int64_t>{13});
  one.steps(1);
  two.steps(1);
  REQUIRE(one.is_active(15));
  for (const bool wall : {false, true}) {
    const std::int64_t id = wall ? 14 : 11;
    const Tangent a = tangent_of(one, id, wall), b = tangent_of(two, id, wall);
    REQUIRE(a.found == 1);
    CHECK((a.force - b.force).norm() <= 1e-12 * b.force.norm());
  }
  one.steps(300);
  two.steps(300);
  for (const std::int64_t id : {11, 14}) {
    const Vec3 x = one.particles().position[one.index_of(id)];
    const Vec3 y = two.particles().position[two.index_of(id)];
    CHECK((x - y).norm() <= 1e-12 * y.norm());
  }
  CHECK_THROWS_AS(one.remove_particle(13), InputError); // gone already
  CHECK_THROWS_AS(one.remove_particle(99), InputError); // never was

  // between runs after a set-up change: one particle added and one removed, so that the counts
  // balance; the list rows are renumbered and the sliding contact keeps its history exactly
  {
    Sim3 s3(params<Sim3>(Vec3(0, 0, -g0)));
    const auto m = s3.add_material(soft());
    const double r = 5e-3;
    s3.add_particle(
        {.position = Vec3(-1, 0, 0), .radius = r, .material = m, .fixed = true, .id = 0});
    s3.add_particle(
        {.position = Vec3(0, 0, 0), .radius = r, .material = m, .fixed = true, .id = 1});
    s3.add_particle({.position = Vec3(0, 0, 2 * r - 1e-5),
                     .radius = r,
                     .material = m,
                     .velocity = Vec3(0.01, 0, 0),
                     .id = 2});
    s3.steps(200);
    const Tangent before = tangent_of(s3, 2, false);
    s3.add_particle(
        {.position = Vec3(1, 0, 0), .radius = r, .material = m, .fixed = true, .id = 3});
    s3.remove_particle(0);
    CHECK(!s3.is_active(0));
    s3.initialize();
    const Tangent after = tangent_of(s3, 2, false);
    REQUIRE(before.found == 1);
    REQUIRE(after.found == 1);
    CHECK(before.force.norm() > 0.0);
    CHECK((after.force - before.force).norm() <= 1e-12 * before.force.norm());
  }

  // before the first run, and a particle not yet created
  Sim3 sim(params<Sim3>(Vec3(0, 0, -g0)));
  const auto k = sim.add_material(soft());
  sim.add_particle({.position = Vec3(0, 0, 0), .radius = 1e-3, .material = k, .id = 1});
  sim.add_particle({.position = Vec3(0, 0, 0.0015), .radius = 1e-3, .material = k, .id = 2});
  sim.add_particle(
      {.position = Vec3(0, 0, 0.1), .radius = 1e-3, .material = k, .creation_time = 0.5, .id = 3});
  sim.remove_particle(2); // overlapping particle 1: it would push it
  CHECK_THROWS_AS(sim.remove_particle(2), InputError);
  sim.remove_particle(3);
  CHECK(removed_set(sim) == std::set<std::int64_t>{2, 3});
  sim.steps(100);
  CHECK(sim.size() == 1);
  CHECK(sim.inactive_count() == 0);
  const double t = sim.time();
  CHECK(std::abs(sim.particles().position[0].z() + g0 * t * t / 2) <= 1e-12);
  CHECK_THROWS_AS(
      sim.add_particle({.position = Vec3(1, 0, 0), .radius = 1e-3, .material = k, .id = 2}),
      InputError); // ids are not used again
}

// A particle added with add_particle during a run (not through a creation time) must not reset
// the contact histories of the others either: the old rows keep their indices, and
// initialize() maps them to the old list.
// Tolerance: re-initialising recomputes the forces with the full-step velocities (not velocity
// Verlet's prediction), which changes the damped normal force by ~1e-3, hence 1 % against run
// 2; the sliding contact still carries exactly mu F_n (1e-12).
TEST_CASE("lifecycle: add_particle during a run keeps the contact histories") {
  const long n_rm = 100;
  Sim3 one = history_run(false, 100000), two = history_run(false, 100000);
  one.steps(n_rm - 1);
  two.steps(n_rm - 1);
  one.add_particle(
      {.position = Vec3(0, 0.05, -0.012), .radius = 5e-3, .material = 0, .fixed = true, .id = 13});
  one.steps(1);
  two.steps(1);
  for (const bool wall : {false, true}) {
    const std::int64_t id = wall ? 14 : 11;
    const Tangent a = tangent_of(one, id, wall), b = tangent_of(two, id, wall);
    REQUIRE(a.found == 1);
    CHECK(a.sliding);
    CHECK(a.force.norm() == test::approx(soft().friction * a.normal).epsilon(1e-12));
    CHECK(a.force.norm() == test::approx(b.force.norm()).epsilon(0.01));
  }
}

// ------------------------------------------------------------------------------------------ 6
// Mass removal. 200 polydisperse spheres (r = 4 to 5 mm) dropped at 0.2 m/s from a 5 x 5 x 8
// lattice into a 60 mm square box (five walls::Plane) under gravity; after 0.1 s a ball sink of
// radius 25 mm at a bottom corner opens and removes the particles around it, in the middle of
// the packing and with their contacts. After 0.05 s more: ids unique, active and removed ids
// disjoint and together exactly the 200 ids; no active centre inside the (active) sink; and the
// neighbour list is complete: contact_counts() equals the brute-force O(N^2) count of pairs with
// |x_i - x_j| < r_i + r_j and of particles closer than r_i to a wall (exact integers).
TEST_CASE("lifecycle: mass removal leaves unique ids and a complete neighbour list") {
  auto prm = params<Sim3>(Vec3(0, 0, -g0));
  prm.time_step = 2e-5;
  Sim3 sim(prm);
  const auto k = sim.add_material(soft());
  const double L = 0.06;
  const std::vector<walls::Plane> box = {{Vec3(0, 0, 0), Vec3(0, 0, 1)},
                                         {Vec3(0, 0, 0), Vec3(1, 0, 0)},
                                         {Vec3(L, 0, 0), Vec3(-1, 0, 0)},
                                         {Vec3(0, 0, 0), Vec3(0, 1, 0)},
                                         {Vec3(0, L, 0), Vec3(0, -1, 0)}};
  for (const auto& w : box)
    sim.add_wall(w, {.material = k});
  for (int kz = 0; kz < 8; ++kz)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 5; ++i)
        sim.add_particle(
            {.position = Vec3(0.007 + 0.0115 * i, 0.007 + 0.0115 * j, 0.006 + 0.0115 * kz),
             .radius = 4e-3 + 2.5e-4 * ((i + 2 * j + 3 * kz) % 5),
             .material = k,
             .velocity = Vec3(0, 0, -0.2)});
  const regions::Ball<3> sink{Vec3::Zero(), 0.025};
  sim.add_sink(sink, 0.1 + 0.5 * prm.time_step); // opens at the first step after 0.1 s
  sim.run(0.1);
  REQUIRE(sim.removed_ids().empty());
  const std::size_t contacts_before = sim.contact_counts().first;
  REQUIRE(contacts_before > 100); // a packing: the sink cuts through contacts
  sim.run(0.05);

  const auto& p = sim.particles();
  const std::set<std::int64_t> active = active_ids(sim), removed = removed_set(sim);
  CHECK(active.size() == sim.size());
  CHECK(removed.size() == sim.removed_ids().size());
  CHECK(sim.size() + sim.removed_ids().size() == 200);
  CHECK(removed.size() >= 5);
  std::set<std::int64_t> all = active;
  all.insert(removed.begin(), removed.end());
  CHECK(all.size() == 200);
  CHECK(*all.begin() == 0);
  CHECK(*all.rbegin() == 199);
  for (std::size_t i = 0; i < p.size(); ++i)
    CHECK(!sink.contains(p.position[i]));

  std::size_t pairs = 0, walls = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = i + 1; j < p.size(); ++j)
      pairs += (p.position[i] - p.position[j]).norm() < p.radius[i] + p.radius[j];
    for (const auto& w : box)
      walls += (p.position[i] - w.point).dot(w.normal) < p.radius[i];
  }
  const auto counted = sim.contact_counts();
  CHECK(counted.first == pairs);
  CHECK(counted.second == walls);
  MESSAGE("mass removal: " << removed.size() << " removed, " << pairs << " pair and " << walls
                           << " wall contacts (before the sink: " << contacts_before << ")");
}

// ------------------------------------------------------------------------------------------ 7
// Bad input: every message names the object and the value.
TEST_CASE("lifecycle: bad input is rejected with a message naming the object and value") {
  Sim3 sim(params<Sim3>(Vec3::Zero()));
  const auto k = sim.add_material(soft());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH_AS(
      sim.add_particle({.radius = 1e-3, .material = k, .creation_time = nan, .id = 4}),
      doctest::Contains("sphere particle 4: creation_time = nan"), InputError);
  CHECK_THROWS_WITH_AS(
      sim.add_particle({.radius = 1e-3, .material = k, .creation_time = inf, .id = 4}),
      doctest::Contains("creation_time = inf"), InputError);
  CHECK_THROWS_WITH_AS(
      sim.add_particle(
          {.radius = 1e-3, .material = k, .creation_time = 0.5, .destruction_time = 0.5, .id = 4}),
      doctest::Contains("sphere particle 4: destruction_time = 0.5"), InputError);
  CHECK_THROWS_WITH_AS(
      sim.add_particle(
          {.radius = 1e-3, .material = k, .creation_time = 0.5, .destruction_time = 0.2, .id = 4}),
      doctest::Contains("destruction_time = 0.2"), InputError);
  CHECK_THROWS_WITH_AS(
      sim.add_particle({.radius = 1e-3, .material = k, .destruction_time = nan, .id = 4}),
      doctest::Contains("destruction_time = nan"), InputError);
  CHECK(sim.size() == 0);
  CHECK(sim.inactive_count() == 0);

  CHECK_THROWS_WITH_AS(sim.set_bounding_box(regions::Box<3>{Vec3(0, 0, 0), Vec3(1, 0, 1)}),
                       doctest::Contains("Simulation::set_bounding_box (Box): hi component = 0"),
                       InputError);
  CHECK_THROWS_WITH_AS(sim.add_sink(regions::Box<3>{Vec3(0, 0, 0), Vec3(1, 1, -1)}),
                       doctest::Contains("Simulation::add_sink 0 (Box): hi component = -1"),
                       InputError);
  CHECK_THROWS_WITH_AS(sim.add_sink(regions::Box<3>{Vec3(0, nan, 0), Vec3(1, 1, 1)}),
                       doctest::Contains("(Box): lo component = nan"), InputError);
  CHECK_THROWS_WITH_AS(sim.add_sink(regions::Ball<3>{Vec3::Zero(), 0.0}),
                       doctest::Contains("Simulation::add_sink 0 (Ball): radius = 0"), InputError);
  CHECK_THROWS_WITH_AS(sim.set_bounding_box(regions::Ball<3>{Vec3::Zero(), -2.0}),
                       doctest::Contains("(Ball): radius = -2"), InputError);
  CHECK_THROWS_WITH_AS(sim.add_sink(regions::Ball<3>{Vec3::Zero(), 1.0}, 2.0, 1.0),
                       doctest::Contains("Simulation::add_sink 0: t_end = 1"), InputError);
  CHECK_THROWS_WITH_AS(sim.set_bounding_box(regions::Ball<3>{Vec3::Zero(), 1.0}, nan),
                       doctest::Contains("Simulation::set_bounding_box: t_begin = nan"),
                       InputError);
  CHECK_THROWS_WITH_AS(sim.add_sink(regions::Ball<3>{Vec3::Zero(), 1.0}, 0.0, nan),
                       doctest::Contains("t_end = nan"), InputError);

  Sim2 sim2(params<Sim2>(Vec2::Zero()));
  sim2.add_material(soft());
  CHECK_THROWS_WITH_AS(sim2.add_sink(regions::Polygon{{Vec2(0, 0), Vec2(1, 0)}}),
                       doctest::Contains("Simulation::add_sink 0 (Polygon): vertices = 2"),
                       InputError);
  CHECK_THROWS_WITH_AS(
      sim2.set_bounding_box(regions::Polygon{{Vec2(0, 0), Vec2(1, 1), Vec2(2, 2)}}),
      doctest::Contains("Simulation::set_bounding_box (Polygon): area = 0"), InputError);
  // collinear vertices whose shoelace sum is not exactly zero in floating point (~2e-17 m^2)
  CHECK_THROWS_WITH_AS(
      sim2.set_bounding_box(regions::Polygon{{Vec2(0.1, 0.2), Vec2(0.4, 0.5), Vec2(0.7, 0.8)}}),
      doctest::Contains("(Polygon): area ="), InputError);
  CHECK_THROWS_WITH_AS(sim2.add_sink(regions::Polygon{{Vec2(0, 0), Vec2(nan, 0), Vec2(0, 1)}}),
                       doctest::Contains("(Polygon): vertex"), InputError);
  CHECK_THROWS_WITH_AS(sim2.add_sink(regions::Box<2>{Vec2(0, 0), Vec2(0, 1)}),
                       doctest::Contains("(Box): hi component = 0"), InputError);
  CHECK_THROWS_WITH_AS(sim2.add_sink(regions::Ball<2>{Vec2::Zero(), nan}),
                       doctest::Contains("(Ball): radius = nan"), InputError);
  // valid input is accepted (including a degenerate-looking but valid thin triangle)
  CHECK_NOTHROW(
      sim2.add_sink(regions::Polygon{{Vec2(0, 0), Vec2(1, 0), Vec2(0.5, 1e-3)}}, 0.0, 0.0));
}

// Ids identify particles for life (removal by destruction time, index_of, is_active, groups), so
// an id already in use by an active or a waiting particle is rejected.
TEST_CASE("lifecycle: an id already in use is rejected") {
  Sim3 sim(params<Sim3>(Vec3::Zero()));
  const auto k = sim.add_material(soft());
  const auto a = sim.add_particle({.position = Vec3::Zero(), .radius = 1e-3, .material = k});
  sim.add_particle(
      {.position = Vec3(0.1, 0, 0), .radius = 1e-3, .material = k, .creation_time = 1.0, .id = 8});
  CHECK_THROWS_WITH_AS(
      sim.add_particle({.position = Vec3(0.2, 0, 0), .radius = 1e-3, .material = k, .id = a}),
      doctest::Contains("id = 0"), InputError);
  CHECK_THROWS_WITH_AS(
      sim.add_particle({.position = Vec3(0.3, 0, 0), .radius = 1e-3, .material = k, .id = 8}),
      doctest::Contains("id = 8"), InputError);
  CHECK(sim.size() == 1);
  CHECK(sim.inactive_count() == 1);
}

// A particle that starts outside the bounding box or inside a sink is removed at the start of the
// run, before the start-overlap check and the first step: two particles overlapping by half a
// radius (the check refuses more than max_start_overlap = 5 % of the radius) outside the box, and
// two inside a sink, do not stop the run, and no force ever acts on the particle inside (it keeps
// its velocity exactly).
TEST_CASE(
    "lifecycle: particles outside the bounding box or inside a sink go before the first step") {
  Sim3 sim(params<Sim3>(Vec3::Zero()));
  const auto k = sim.add_material(soft());
  const double r = 1e-3;
  const Vec3 v(0.01, 0, 0);
  sim.add_particle({.position = Vec3::Zero(), .radius = r, .material = k, .velocity = v, .id = 0});
  sim.add_particle({.position = Vec3(0.1, 0, 0), .radius = r, .material = k, .id = 1});
  sim.add_particle({.position = Vec3(0.1 + 1.5 * r, 0, 0), .radius = r, .material = k, .id = 2});
  sim.add_particle({.position = Vec3(0, 0.02, 0), .radius = r, .material = k, .id = 3});
  sim.add_particle({.position = Vec3(0, 0.02 + 1.5 * r, 0), .radius = r, .material = k, .id = 4});
  sim.set_bounding_box(regions::Box<3>{Vec3(-0.05, -0.05, -0.05), Vec3(0.05, 0.05, 0.05)});
  sim.add_sink(regions::Ball<3>{Vec3(0, 0.021, 0), 0.005});
  CHECK(sim.size() == 5);
  REQUIRE_NOTHROW(sim.steps(0));
  CHECK(sim.size() == 1);
  CHECK(removed_set(sim) == std::set<std::int64_t>{1, 2, 3, 4});
  CHECK(sim.contact_counts().first == 0);
  sim.steps(100);
  CHECK(sim.particles().velocity[0] == v);
  CHECK(sim.particles().position[0][0] == test::approx(100 * dt * v[0]).epsilon(1e-12));
}

// ------------------------------------------------------------------------------------------ walls
// Wall lifecycle (WallOptions::active, creation_time, destruction_time; set_wall_active,
// remove_wall): a wall takes part in the forces evaluated at times t with creation_time <= t <
// destruction_time. A sphere rests on a floor (z = 0) destroyed at t_d (placed mid-step): the
// forces of the first step whose end time is >= t_d have no contact, so from the end of that step
// the sphere falls freely from its state (z_d, v_d) there; velocity Verlet under constant gravity
// gives exactly z = z_d + v_d s - g s^2/2 (s the time since), round-off only (1e-12 m). A second
// floor at z = -5 mm, created at t_c = 0.02 s (before the sphere reaches it: the drop of 5 mm
// from rest takes 0.032 s), catches it; the sphere then comes to rest on it at the Hertz
// equilibrium overlap delta = (m g / (4/3 E* sqrt(r)))^(2/3) = 1.84 um (2 % with what remains of
// the bounces after 0.3 s at e = 0.3).
TEST_CASE("lifecycle: a wall takes part in contacts only between its creation and destruction") {
  Sim3 sim(params<Sim3>(Vec3(0, 0, -g0)));
  Material m = soft();
  m.restitution = 0.3;
  const auto k = sim.add_material(m);
  const double r = 2e-3, td = 0.0100005, tc = 0.02;
  WallOptions<3> first;
  first.material = k;
  first.destruction_time = td;
  WallOptions<3> second;
  second.material = k;
  second.creation_time = tc;
  const auto w0 = sim.add_wall(walls::Plane{Vec3::Zero(), Vec3::UnitZ()}, first);
  const auto w1 = sim.add_wall(walls::Plane{Vec3(0, 0, -5e-3), Vec3::UnitZ()}, second);
  sim.add_particle({.position = Vec3(0, 0, r), .radius = r, .material = k, .id = 0});
  sim.steps(0);
  CHECK(sim.wall_present(w0));
  CHECK(!sim.wall_present(w1));
  const long nd = static_cast<long>(std::ceil(td / dt));
  REQUIRE(static_cast<double>(nd) * dt > td);
  sim.steps(nd - 1);
  CHECK(sim.contact_counts().second == 1);
  CHECK(sim.wall_present(w0));
  sim.steps(1); // the forces at t = nd dt >= t_d: the floor is gone
  CHECK(!sim.wall_present(w0));
  CHECK(sim.contact_counts().second == 0);
  const double zd = sim.particles().position[0][2], vd = sim.particles().velocity[0][2];
  const double t_d = sim.time();
  const long nc = static_cast<long>(std::ceil(tc / dt)) - nd;
  sim.steps(nc - 1);
  CHECK(!sim.wall_present(w1));
  const double s = sim.time() - t_d;
  const double z_free = zd + vd * s - 0.5 * g0 * s * s;
  CHECK(std::abs(sim.particles().position[0][2] - z_free) < 1e-12);
  MESSAGE("free fall after the destruction: error " << sim.particles().position[0][2] - z_free
                                                    << " m");
  sim.steps(1);
  CHECK(sim.wall_present(w1));
  sim.run(0.3);
  const double mass = m.density * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  const double estar = m.young / (2.0 * (1.0 - m.poisson * m.poisson));
  const double delta = std::pow(mass * g0 / (4.0 / 3.0 * estar * std::sqrt(r)), 2.0 / 3.0);
  const double z = sim.particles().position[0][2];
  CHECK(std::abs(z - (-5e-3 + r - delta)) < 0.02 * delta);
  MESSAGE("rest on the created floor: overlap " << -5e-3 + r - z << " m, Hertz " << delta << " m");
  CHECK(sim.contact_counts().second == 1);
}

// set_wall_active and remove_wall between runs: a sphere resting on a floor has no contact from
// the forces of the first step after the floor is switched off, and then falls freely (its
// velocity changes by exactly -g dt per step, round-off only, 1e-12 relative); switched on again
// the wall is present, removed it cannot come back, and the sphere, falling 1 cm, rests on the
// floor below at the same overlap as on the first (2 % of the Hertz overlap). The flag and the
// removal are kept by a checkpoint.
TEST_CASE("lifecycle: walls switched off, on and removed between runs") {
  auto make = [](Sim3& sim) {
    Material m = soft();
    m.restitution = 0.3;
    const auto k = sim.add_material(m);
    WallOptions<3> o;
    o.material = k;
    sim.add_wall(walls::Plane{Vec3::Zero(), Vec3::UnitZ()}, o);
    sim.add_wall(walls::Plane{Vec3(0, 0, -0.01), Vec3::UnitZ()}, o);
    sim.add_particle({.position = Vec3(0, 0, 2e-3), .radius = 2e-3, .material = k, .id = 0});
  };
  Sim3 sim(params<Sim3>(Vec3(0, 0, -g0)));
  make(sim);
  sim.run(0.1); // at rest on the floor
  const double z_rest = sim.particles().position[0][2];
  const double overlap = 2e-3 - z_rest;
  REQUIRE(overlap > 0.0);
  CHECK(sim.contact_counts().second == 1);
  sim.set_wall_active(0, false);
  sim.steps(1);
  CHECK(!sim.wall_present(0));
  CHECK(sim.contact_counts().second == 0);
  const double v1 = sim.particles().velocity[0][2];
  sim.steps(99);
  CHECK(sim.particles().velocity[0][2] == test::approx(v1 - 99 * dt * g0).epsilon(1e-12));
  sim.set_wall_active(0, true);
  sim.steps(1);
  CHECK(sim.wall_present(0));
  sim.remove_wall(0);
  sim.set_wall_active(0, true);
  sim.steps(1);
  CHECK(!sim.wall_present(0)); // removed for good
  sim.run(0.15);
  // it fell to the lower floor and rests there
  CHECK(std::abs(sim.particles().position[0][2] - (z_rest - 0.01)) < 0.02 * overlap);
  CHECK(sim.contact_counts().second == 1);
  CHECK_THROWS_WITH_AS(sim.set_wall_active(2, false),
                       doctest::Contains("Simulation::set_wall_active: wall index 2 is invalid"),
                       InputError);
  CHECK_THROWS_WITH_AS(sim.remove_wall(7), doctest::Contains("wall index 7"), InputError);
  // a checkpoint keeps the removal
  const std::string path = "lifecycle_walls.ckpt";
  io::save_checkpoint(sim, path);
  Sim3 again(params<Sim3>(Vec3(0, 0, -g0)));
  make(again);
  io::load_checkpoint(again, path);
  std::remove(path.c_str());
  CHECK(!again.wall_present(0));
  CHECK(again.wall_present(1));
  again.set_wall_active(0, true);
  again.steps(1);
  CHECK(!again.wall_present(0));
  CHECK(again.contact_counts().second == 1);
}

TEST_CASE("lifecycle: a wall's creation and destruction times are checked") {
  Sim3 sim(params<Sim3>(Vec3::Zero()));
  const auto k = sim.add_material(soft());
  WallOptions<3> o;
  o.name = "gate";
  o.material = k;
  o.creation_time = 2.0;
  o.destruction_time = 1.0;
  CHECK_THROWS_WITH_AS(sim.add_wall(walls::Plane{}, o),
                       doctest::Contains("Wall 'gate': destruction_time = 1"), InputError);
  o.creation_time = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH_AS(sim.add_wall(walls::Plane{}, o),
                       doctest::Contains("Wall 'gate': creation_time = nan"), InputError);
  o.creation_time = inf;
  o.destruction_time = inf;
  CHECK_THROWS_WITH_AS(sim.add_wall(walls::Plane{}, o), doctest::Contains("creation_time = inf"),
                       InputError);
  CHECK(sim.walls().empty());
}
