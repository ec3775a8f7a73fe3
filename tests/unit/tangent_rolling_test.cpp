// Tangential-force and rolling-resistance models in isolation: history layout, zero force out of
// contact, action and reaction, dissipation over closed cycles, the wall as the large-radius limit
// of a particle, the closed forms of each model, static and dynamic friction, parameter checks.
#include "../approx.hpp"
#include <cmath>
#include <doctest/doctest.h>
#include <functional>
#include <grain/grain.hpp>
#include <grain/models/rolling/constant.hpp>
#include <grain/models/rolling/epsd.hpp>
#include <grain/models/rolling/viscous.hpp>
#include <grain/models/tangent/dashpot.hpp>
#include <grain/models/tangent/dashpot_slider.hpp>
#include <grain/models/tangent/di_renzo_di_maio.hpp>
#include <grain/models/tangent/langston_tuzun_heyes.hpp>
#include <grain/models/tangent/mindlin.hpp>
#include <grain/models/tangent/slider.hpp>
#include <grain/models/tangent/spring.hpp>
#include <grain/models/tangent/spring_slider.hpp>
#include <grain/models/tangent/tsuji.hpp>
#include <grain/models/tangent/zheng_zhu_yu.hpp>
#include <initializer_list>
#include <limits>
#include <numbers>
#include <string>
#include <type_traits>

using namespace grain;

namespace {

// ---- every model fills its slot; histories are trivially copyable and only as large as needed
template <class... T>
constexpr bool all_tangent = (TangentModel<T> && ...);
template <class... T>
constexpr bool all_rolling = (RollingModel<T> && ...);
static_assert(all_tangent<tangent::Spring, tangent::Dashpot, tangent::Slider, tangent::SpringSlider,
                          tangent::DashpotSlider, tangent::SpringDashpotSlider, tangent::Mindlin,
                          tangent::DiRenzoDiMaio, tangent::Tsuji, tangent::LangstonTuzunHeyes,
                          tangent::ZhengZhuYu>);
static_assert(all_rolling<rolling::Constant, rolling::Viscous, rolling::EPSD>);
static_assert(!TangentModel<rolling::EPSD> && !RollingModel<tangent::Mindlin>);

using Hz = normal::Hertz<>;
static_assert(Interaction<Hz, tangent::Slider, rolling::Constant>::stateless<3>);
static_assert(Interaction<Hz, tangent::Dashpot, rolling::Viscous>::stateless<2>);
static_assert(sizeof(Interaction<Hz, tangent::DashpotSlider>::History<3>) == sizeof(bool));
static_assert(sizeof(Interaction<Hz, tangent::Spring>::History<3>) == sizeof(PlainVec<3>));
static_assert(sizeof(Interaction<Hz, tangent::Mindlin>::History<2>) ==
              sizeof(tangent::SpringDashpotSlider::History<2>));
static_assert(sizeof(Interaction<Hz, tangent::None, rolling::EPSD>::History<2>) == sizeof(double));
static_assert(sizeof(Interaction<Hz, tangent::None, rolling::EPSD>::History<3>) ==
              sizeof(PlainVec<3>));
static_assert(
    std::is_trivially_copyable_v<Interaction<Hz, tangent::ZhengZhuYu, rolling::EPSD>::History<3>>);
static_assert(std::is_trivially_copyable_v<
              Interaction<Hz, tangent::LangstonTuzunHeyes, rolling::EPSD>::History<2>>);
static_assert(Interaction<Hz, tangent::None, rolling::Constant>::has_torque);

PairProperties pair_of(double mu, double mu_s = -1.0, double mu_r = 0.0, double e = 0.5,
                       double young = 1e7, double poisson = 0.3) {
  const Material m{.density = 2500,
                   .young = young,
                   .poisson = poisson,
                   .restitution = e,
                   .friction = mu,
                   .friction_static = mu_s,
                   .rolling_friction = mu_r};
  return PairProperties::mix(m, m);
}

// Coefficients used by the generic tests: defaults, plus dashpots for the models whose default
// has none, so that every term is exercised.
template <class M>
typename M::Params params_for() {
  if constexpr (std::is_same_v<M, tangent::LangstonTuzunHeyes>)
    return {.damping = 0.3};
  else if constexpr (std::is_same_v<M, tangent::ZhengZhuYu>)
    return {.viscosity = 50.0};
  else if constexpr (std::is_same_v<M, tangent::DiRenzoDiMaio>)
    return {.damping = 0.05};
  else if constexpr (std::is_same_v<M, rolling::Constant> || std::is_same_v<M, rolling::EPSD>)
    return {.coefficient = 0.1};
  else if constexpr (std::is_same_v<M, rolling::Viscous>)
    return {.coefficient = 0.5};
  else
    return {};
}

template <class C>
typename C::Params contact_params() {
  typename C::Params p;
  p.tangent = params_for<typename C::tangent_model>();
  p.rolling = params_for<typename C::rolling_model>();
  return p;
}

template <int D>
Vec<D> unit(std::initializer_list<double> c) {
  Vec<D> v;
  int k = 0;
  for (double x : c)
    if (k < D) v[k++] = x;
  return v.normalized();
}

template <int D>
Angular<D> spin(double x, double y, double z) {
  if constexpr (D == 2)
    return z;
  else
    return Vec3(x, y, z);
}

double moment_norm(double m) { return std::abs(m); }
double moment_norm(const Vec3& m) { return m.norm(); }

/// True if f() throws InputError whose message names every word of `words`.
bool rejects(const std::function<void()>& f, std::initializer_list<std::string> words) {
  try {
    f();
  } catch (const InputError& e) {
    const std::string msg = e.what();
    for (const auto& w : words)
      if (msg.find(w) == std::string::npos) return false;
    return true;
  }
  return false;
}

} // namespace

// ------------------------------------------------------------------ generic properties
TEST_CASE_TEMPLATE("tangential and rolling models: zero force and torque at zero overlap", T,
                   tangent::Spring, tangent::Dashpot, tangent::Slider, tangent::SpringSlider,
                   tangent::DashpotSlider, tangent::SpringDashpotSlider, tangent::Mindlin,
                   tangent::DiRenzoDiMaio, tangent::Tsuji, tangent::LangstonTuzunHeyes,
                   tangent::ZhengZhuYu) {
  using C = Interaction<Hz, T, rolling::EPSD>;
  const auto pair = pair_of(0.5, 0.6, 0.1);
  auto p = contact_params<C>();
  SUBCASE("3D") {
    ContactGeometry<3> g;
    pair_geometry<3>(g, Vec3::Zero(), Vec3::UnitX(), 2e-3, 1e-3, 1e-3, 1e-5, 1e-5,
                     Vec3(0, 0.3, 0.1), Vec3(0, -0.1, 0), Vec3(10, 20, 30), Vec3(-5, 0, 1));
    REQUIRE(g.overlap == 0.0);
    typename C::template History<3> h{};
    for (int k = 0; k < 3; ++k) {
      auto r = C::template evaluate<3>(g, pair, p, h, 1e-6);
      CHECK(r.force.norm() == 0.0);
      CHECK(r.torque_i.norm() == 0.0);
      CHECK(r.torque_j.norm() == 0.0);
      CHECK(r.tangent.elastic_energy == 0.0);
    }
    // given stiffness or damping does not produce a force out of contact either
    if constexpr (requires { p.tangent.stiffness; }) p.tangent.stiffness = 1e3;
    if constexpr (requires { p.tangent.damping; }) p.tangent.damping = 1.0;
    p.rolling.stiffness = 1e-3;
    auto r = C::template evaluate<3>(g, pair, p, h, 1e-6);
    CHECK(r.force.norm() == 0.0);
    CHECK(r.torque_i.norm() == 0.0);
  }
  SUBCASE("2D") {
    ContactGeometry<2> g;
    pair_geometry<2>(g, Vec2::Zero(), Vec2::UnitX(), 2e-3, 1e-3, 1e-3, 1e-5, 1e-5, Vec2(0, 0.3),
                     Vec2(0, -0.1), 30.0, -5.0);
    typename C::template History<2> h{};
    auto r = C::template evaluate<2>(g, pair, p, h, 1e-6);
    CHECK(r.force.norm() == 0.0);
    CHECK(r.torque_i == 0.0);
    CHECK(r.torque_j == 0.0);
  }
}

namespace {
/// Drives an oblique contact of unequal particles for some steps and checks, at every step, the
/// angular-momentum balance of the pair and that the same contact seen from j (with the history
/// reversed) gives the opposite force and the swapped torques.
template <int D, class C>
void check_action_reaction() {
  const auto pair = pair_of(0.4, 0.5, 0.2);
  const auto p = contact_params<C>();
  const Vec<D> n = unit<D>({0.6, -0.48, 0.64});
  const double ri = 1.0e-3, rj = 1.6e-3, mi = 1e-5, mj = 4e-5;
  const Vec<D> xi = Vec<D>::Constant(0.3e-3);
  Vec<D> vi = Vec<D>::Zero(), vj = Vec<D>::Zero();
  vi[0] = 0.02;
  vi[1] = 0.15;
  vj[D - 1] = -0.08;
  const Angular<D> wi = spin<D>(40, -25, 90), wj = spin<D>(-10, 60, -35);
  typename C::template History<D> h{};
  double worst = 0.0, worst_swap = 0.0;
  for (int k = 0; k < 60; ++k) {
    const double dist = ri + rj - 2e-6 * (1 + std::sin(0.1 * k));
    const Vec<D> xj = xi + dist * n;
    ContactGeometry<D> g, gs;
    pair_geometry<D>(g, xi, n, dist, ri, rj, mi, mj, vi, vj, wi, wj);
    pair_geometry<D>(gs, xj, Vec<D>(-n), dist, rj, ri, mj, mi, vj, vi, wj, wi);
    auto hs = h;
    C::template reverse<D>(hs);
    const auto r = C::template evaluate<D>(g, pair, p, h, 1e-6);
    const auto rs = C::template evaluate<D>(gs, pair, p, hs, 1e-6);
    // angular momentum about the origin: x_i x F + x_j x (-F) + T_i + T_j = 0
    const Angular<D> total =
        cross(xi, r.force) + cross(xj, Vec<D>(-r.force)) + r.torque_i + r.torque_j;
    const double scale = r.force.norm() * xj.norm() + moment_norm(r.torque_i) + 1e-300;
    worst = std::max(worst, moment_norm(total) / scale);
    // the rolling torques alone are equal and opposite
    const Angular<D> roll_i = r.torque_i - cross(g.arm_i, r.tangent.force);
    const Angular<D> roll_j = r.torque_j - cross(g.arm_j, Vec<D>(-r.tangent.force));
    worst = std::max(worst, moment_norm(Angular<D>(roll_i + roll_j)) / scale);
    // seen from j
    const double fs = (r.force + rs.force).norm() / (r.force.norm() + 1e-300);
    const double ts = (moment_norm(Angular<D>(r.torque_i - rs.torque_j)) +
                       moment_norm(Angular<D>(r.torque_j - rs.torque_i))) /
                      (moment_norm(r.torque_i) + moment_norm(r.torque_j) + 1e-300);
    worst_swap = std::max({worst_swap, fs, ts});
    CHECK(r.force.norm() > 0.0);
  }
  CHECK(worst < 1e-12);
  CHECK(worst_swap < 1e-9);
}
} // namespace

TEST_CASE_TEMPLATE("tangential models: action equals reaction, angular momentum of the pair", T,
                   tangent::Spring, tangent::Dashpot, tangent::Slider, tangent::SpringSlider,
                   tangent::DashpotSlider, tangent::SpringDashpotSlider, tangent::Mindlin,
                   tangent::DiRenzoDiMaio, tangent::Tsuji, tangent::LangstonTuzunHeyes,
                   tangent::ZhengZhuYu) {
  check_action_reaction<3, Interaction<Hz, T, rolling::EPSD>>();
  check_action_reaction<2, Interaction<Hz, T, rolling::EPSD>>();
  check_action_reaction<3, Interaction<normal::LinearSpringDashpot, T, rolling::Constant>>();
  check_action_reaction<2, Interaction<normal::LinearSpringDashpot, T, rolling::Viscous>>();
}

TEST_CASE_TEMPLATE("rolling models: equal and opposite torques, angular momentum of the pair", R,
                   rolling::Constant, rolling::Viscous, rolling::EPSD) {
  check_action_reaction<3, Interaction<Hz, tangent::SpringDashpotSlider, R>>();
  check_action_reaction<2, Interaction<Hz, tangent::SpringDashpotSlider, R>>();
  check_action_reaction<3, Interaction<Hz, tangent::None, R>>();
  // a pure twist (w_rel along n) is not resisted
  const auto pair = pair_of(0.5, 0.5, 0.1);
  ContactGeometry<3> g;
  pair_geometry<3>(g, Vec3::Zero(), Vec3::UnitX(), 1.99e-3, 1e-3, 1e-3, 1e-5, 1e-5, Vec3::Zero(),
                   Vec3::Zero(), Vec3(5, 0, 0), Vec3(-5, 0, 0));
  typename R::template History<3> h{};
  typename Hz::template History<3> hn{};
  const auto n = Hz::force(g, pair, {}, hn);
  Vec3 ti = Vec3::Zero(), tj = Vec3::Zero();
  R::torque(g, pair, n, params_for<R>(), h, 1e-6, ti, tj);
  CHECK(ti.norm() == 0.0);
  CHECK(tj.norm() == 0.0);
}

// ------------------------------------------------------------------ dissipation over cycles
namespace {
/// Drives the tangential displacement of a fixed-overlap contact around a closed path (a circle
/// in the tangent plane in 3D, out and back along the tangent in 2D) and returns the dissipated
/// energy -W - E_elastic(end) [J] (W: work of the contact force on i along the relative motion).
template <int D, class T>
double tangential_cycle(double amplitude, const PairProperties& pair, const typename T::Params& p,
                        double* peak = nullptr) {
  ContactGeometry<D> g;
  const double r = 1e-3, m = 1e-5, delta = 1e-5;
  pair_geometry<D>(g, Vec<D>::Zero(), Vec<D>::UnitX(), 2 * r - delta, r, r, m, m, Vec<D>::Zero(),
                   Vec<D>::Zero(), zero<Angular<D>>(), zero<Angular<D>>());
  typename Hz::template History<D> hn{};
  const NormalResult n = Hz::force(g, pair, {}, hn);
  typename T::template History<D> h{};
  const int steps = 4000;
  const double dt = 1e-5;
  auto path = [&](int k) {
    const double phi = 2 * std::numbers::pi * k / steps;
    Vec<D> u = Vec<D>::Zero();
    u[1] = amplitude * std::sin(phi);
    if constexpr (D == 3) u[2] = amplitude * (1 - std::cos(phi));
    return u;
  };
  double work = 0.0, energy = 0.0, fmax = 0.0;
  for (int k = 0; k < steps; ++k) {
    const Vec<D> v = (path(k + 1) - path(k)) / dt;
    g.velocity = v;
    g.tangential_velocity = g.slip_velocity = v;
    g.normal_velocity = 0.0;
    const auto res = T::force(g, pair, n, p, h, dt);
    work += res.force.dot(v) * dt;
    energy = res.elastic_energy;
    fmax = std::max(fmax, res.force.norm());
  }
  if (peak) *peak = fmax;
  return -work - energy;
}

/// Same for a rolling model driven around a closed path of relative rotation; `quadratic`
/// receives sum |w_r dt|^2 [rad^2].
template <int D, class R>
double rolling_cycle(double amplitude, const PairProperties& pair, const typename R::Params& p,
                     double* quadratic = nullptr, double* kr = nullptr) {
  ContactGeometry<D> g;
  const double r = 1e-3, m = 1e-5, delta = 1e-5;
  pair_geometry<D>(g, Vec<D>::Zero(), Vec<D>::UnitX(), 2 * r - delta, r, r, m, m, Vec<D>::Zero(),
                   Vec<D>::Zero(), zero<Angular<D>>(), zero<Angular<D>>());
  typename Hz::template History<D> hn{};
  const NormalResult n = Hz::force(g, pair, {}, hn);
  typename R::template History<D> h{};
  const int steps = 4000;
  const double dt = 1e-5;
  auto angle = [&](int k) {
    const double phi = 2 * std::numbers::pi * k / steps;
    if constexpr (D == 2)
      return amplitude * std::sin(phi);
    else
      return Vec3(0.0, amplitude * std::sin(phi), amplitude * (1 - std::cos(phi)));
  };
  double work = 0.0, quad = 0.0;
  for (int k = 0; k < steps; ++k) {
    const Angular<D> w = (angle(k + 1) - angle(k)) / dt;
    quad += squared_norm(w) * dt * dt;
    g.omega_rel = g.slip_omega_rel = w;
    Angular<D> ti = zero<Angular<D>>(), tj = zero<Angular<D>>();
    R::torque(g, pair, n, p, h, dt, ti, tj);
    if constexpr (D == 2)
      work += ti * w * dt;
    else
      work += ti.dot(w) * dt;
  }
  double energy = 0.0;
  if constexpr (std::is_same_v<R, rolling::EPSD>) {
    energy = R::elastic_energy(h, R::rolling_stiffness(g, pair, n, p));
    if (kr) *kr = R::rolling_stiffness(g, pair, n, p);
  }
  if (quadratic) *quadratic = quad;
  return -work - energy;
}
} // namespace

TEST_CASE_TEMPLATE("tangential models: dissipated energy >= 0 over a closed displacement cycle", T,
                   tangent::Spring, tangent::Dashpot, tangent::Slider, tangent::SpringSlider,
                   tangent::DashpotSlider, tangent::SpringDashpotSlider, tangent::Mindlin,
                   tangent::DiRenzoDiMaio, tangent::Tsuji, tangent::LangstonTuzunHeyes,
                   tangent::ZhengZhuYu) {
  const auto pair = pair_of(0.5, 0.6);
  const auto p = params_for<T>();
  for (double amplitude : {1e-7, 1e-6, 2e-5}) {
    double peak = 0.0;
    const double d3 = tangential_cycle<3, T>(amplitude, pair, p, &peak);
    const double d2 = tangential_cycle<2, T>(amplitude, pair, p);
    // scale: the largest force times the path length
    const double scale = peak * amplitude * 2 * std::numbers::pi;
    CHECK(d3 >= -1e-12 * scale);
    CHECK(d2 >= -1e-12 * scale);
    if (amplitude == 2e-5 && !std::is_same_v<T, tangent::Spring>) {
      // every model with friction or a dashpot dissipates over a sliding cycle
      CHECK(d3 > 0.05 * scale);
      CHECK(d2 > 0.05 * scale);
    }
  }
}

TEST_CASE_TEMPLATE("rolling models: dissipated energy >= 0 over a closed rotation cycle", R,
                   rolling::Constant, rolling::Viscous, rolling::EPSD) {
  const auto pair = pair_of(0.5, 0.5, 0.1);
  auto p = params_for<R>();
  for (double amplitude : {1e-3, 0.02, 0.3}) {
    const double d3 = rolling_cycle<3, R>(amplitude, pair, p);
    const double d2 = rolling_cycle<2, R>(amplitude, pair, p);
    CHECK(d3 >= 0.0);
    CHECK(d2 >= 0.0);
    if (amplitude == 0.3) {
      CHECK(d3 > 0.0);
      CHECK(d2 > 0.0);
    }
  }
  if constexpr (std::is_same_v<R, rolling::EPSD>) {
    // without damping and below the rolling limit the spring returns the stored work except
    // the dissipation of the explicit update, k_r/2 sum |w_r dt|^2 (exact for a linear spring)
    p.damping_ratio = 0.0;
    double quad = 0.0, kr = 0.0;
    const double d3 = rolling_cycle<3, R>(1e-3, pair, p, &quad, &kr);
    CHECK(d3 == grain::test::approx(0.5 * kr * quad).epsilon(1e-6));
    const double d2 = rolling_cycle<2, R>(1e-3, pair, p, &quad, &kr);
    CHECK(d2 == grain::test::approx(0.5 * kr * quad).epsilon(1e-6));
  }
}

// ------------------------------------------------------------------ wall = large-radius limit
namespace {
template <int D, class C>
void check_wall_limit() {
  const auto pair = pair_of(0.4, 0.5, 0.1);
  const auto p = contact_params<C>();
  const double r = 1e-3, m = 1e-5, delta = 2e-6, big = 1e6;
  Vec<D> x = Vec<D>::Zero();
  x[D - 1] = r - delta;
  Wall<D> wall;
  if constexpr (D == 2)
    wall.geometry = walls::Segment{Vec2(-1, 0), Vec2(1, 0)};
  else
    wall.geometry = walls::Plane{Vec3::Zero(), Vec3::UnitZ()};
  wall.pivot = Wall<D>::default_pivot(wall.geometry);
  const auto prox = wall.proximity(x);
  typename C::template History<D> hw{}, hp{};
  double worst = 0.0;
  for (int k = 0; k < 200; ++k) {
    // sliding first, then slowing down into sticking and reversing
    Vec<D> v = Vec<D>::Zero();
    v[0] = 0.05 * std::cos(0.03 * k);
    if constexpr (D == 3) v[1] = 0.02 * std::sin(0.05 * k);
    const Angular<D> w = spin<D>(3.0 * std::sin(0.02 * k), -20.0 * std::cos(0.04 * k), 7.0);
    ContactGeometry<D> gw, gp;
    wall_geometry<D>(gw, wall, prox, x, r, m, v, w);
    pair_geometry<D>(gp, x, prox.normal, r + big * r - delta, r, big * r, m, big * big * m, v,
                     Vec<D>::Zero(), w, zero<Angular<D>>());
    const auto rw = C::template evaluate<D>(gw, pair, p, hw, 1e-5);
    const auto rp = C::template evaluate<D>(gp, pair, p, hp, 1e-5);
    const double fs = rw.force.norm() + 1e-300;
    worst = std::max(worst, (rw.force - rp.force).norm() / fs);
    worst = std::max(worst, moment_norm(Angular<D>(rw.torque_i - rp.torque_i)) /
                                (moment_norm(rw.torque_i) + fs * r));
  }
  CHECK(worst < 1e-5);
}
} // namespace

TEST_CASE_TEMPLATE("tangential models: a wall is the large-radius limit of a particle", T,
                   tangent::Spring, tangent::Dashpot, tangent::Slider, tangent::SpringSlider,
                   tangent::DashpotSlider, tangent::SpringDashpotSlider, tangent::Mindlin,
                   tangent::DiRenzoDiMaio, tangent::Tsuji, tangent::LangstonTuzunHeyes,
                   tangent::ZhengZhuYu) {
  check_wall_limit<3, Interaction<Hz, T>>();
  check_wall_limit<2, Interaction<Hz, T>>();
}

TEST_CASE_TEMPLATE("rolling models: a wall is the large-radius limit of a particle", R,
                   rolling::Constant, rolling::Viscous, rolling::EPSD) {
  check_wall_limit<3, Interaction<Hz, tangent::SpringDashpotSlider, R>>();
  check_wall_limit<2, Interaction<Hz, tangent::SpringDashpotSlider, R>>();
  check_wall_limit<3, Interaction<normal::LinearSpringDashpot, tangent::Mindlin, R>>();
}

// ------------------------------------------------------------------ closed forms per model
namespace {
/// A head-on contact of two equal particles (r = 1 mm, m = 1e-5 kg) along x with overlap delta.
template <int D>
ContactGeometry<D> contact(double delta, const Vec<D>& vt) {
  ContactGeometry<D> g;
  const double r = 1e-3, m = 1e-5;
  pair_geometry<D>(g, Vec<D>::Zero(), Vec<D>::UnitX(), 2 * r - delta, r, r, m, m, Vec<D>::Zero(),
                   Vec<D>::Zero(), zero<Angular<D>>(), zero<Angular<D>>());
  g.velocity = vt;
  g.tangential_velocity = g.slip_velocity = vt;
  return g;
}
Vec3 along_y(double v) { return Vec3(0, v, 0); }
} // namespace

TEST_CASE("spring-dashpot-slider: damping from the tangential restitution (Deen et al.)") {
  using T = tangent::SpringDashpotSlider;
  const auto pair = pair_of(1e3);
  const NormalResult n{.force = 1.0, .stiffness = 2000.0, .damping = 0.3};
  const double k = 1000.0, v = 1e-3, dt = 1e-7, l = std::log(0.5);
  const double pi2 = std::numbers::pi * std::numbers::pi;
  auto eta_of = [&]<int D>(const ContactGeometry<D>& g, const T::Params& p) {
    T::History<D> h{};
    const auto r = T::force(g, pair, n, p, h, dt);
    return -(r.force[1] + k * v * dt) / v;
  };
  const auto g3 = contact<3>(1e-5, along_y(v));
  const double m = g3.m_eff;
  // spheres: m_t = 2 m*/7
  CHECK(eta_of(g3, {.stiffness = k, .restitution = 0.5}) ==
        grain::test::approx(-2 * l * std::sqrt(2 * m * k / (7 * (l * l + pi2)))).epsilon(1e-12));
  CHECK(eta_of(g3, {.stiffness = k, .restitution = 0.0}) ==
        grain::test::approx(2 * std::sqrt(2 * m * k / 7)).epsilon(1e-12));
  CHECK(std::abs(eta_of(g3, {.stiffness = k, .restitution = 1.0})) <=
        1e-12 * 2 * std::sqrt(2 * m * k / 7)); // zero up to round-off
  // disks: m_t = m*/3; 2D disks with sphere mass set kappa = 7/2
  const auto g2 = contact<2>(1e-5, Vec2(0, v));
  CHECK(eta_of(g2, {.stiffness = k, .restitution = 0.5}) ==
        grain::test::approx(-2 * l * std::sqrt(m * k / (3 * (l * l + pi2)))).epsilon(1e-12));
  CHECK(eta_of(g2, {.stiffness = k, .restitution = 0.0}) ==
        grain::test::approx(2 * std::sqrt(m * k / 3)).epsilon(1e-12));
  CHECK(eta_of(g2, {.stiffness = k, .restitution = 0.5, .kappa = 3.5}) ==
        grain::test::approx(-2 * l * std::sqrt(2 * m * k / (7 * (l * l + pi2)))).epsilon(1e-12));
  // given damping wins; default: the normal damping ratio eta_n sqrt(k_t/k_n)
  CHECK(eta_of(g3, {.stiffness = k, .damping = 0.7, .restitution = 0.5}) ==
        grain::test::approx(0.7).epsilon(1e-9));
  CHECK(eta_of(g3, {.stiffness = k}) ==
        grain::test::approx(0.3 * std::sqrt(k / 2000.0)).epsilon(1e-9));
  // a damping factor: eta_t = f eta_n (the third seed's GRANULAR: f = kskn)
  CHECK(eta_of(g3, {.stiffness = k, .damping_factor = 0.5}) ==
        grain::test::approx(0.5 * 0.3).epsilon(1e-9));
  // the spring integrates the slip velocity that moved the contact; the dashpot sees the
  // tangential velocity of the forces (they differ under velocity Verlet)
  {
    auto gs = g3;
    gs.slip_velocity = along_y(0.5 * v);
    T::History<3> hs{};
    const auto rs = T::force(gs, pair, n, {.stiffness = k, .damping = 0.7}, hs, dt);
    CHECK(rs.force[1] == grain::test::approx(-k * 0.5 * v * dt - 0.7 * v).epsilon(1e-12));
    CHECK(load<3>(hs.spring)[1] == grain::test::approx(0.5 * v * dt).epsilon(1e-12));
  }
  // derived stiffness: stiffness_ratio x k_n, default the Mindlin ratio
  typename T::History<3> h{};
  auto r = T::force(g3, pair, n, {.stiffness_ratio = 0.25, .damping = 0.0}, h, dt);
  CHECK(r.force[1] == grain::test::approx(-0.25 * 2000.0 * v * dt).epsilon(1e-12));
}

TEST_CASE("Mindlin, Di Renzo-Di Maio and Tsuji: stiffness and damping") {
  const auto pair = pair_of(1e3, -1.0, 0.0, 0.5, 1e7, 0.3);
  const double delta = 1e-5, v = 1e-3, dt = 1e-7;
  const auto g = contact<3>(delta, along_y(v));
  typename Hz::History<3> hn{};
  const NormalResult n = Hz::force(g, pair, {}, hn);
  const double a = std::sqrt(g.r_eff * delta);
  const double nu = 0.3;
  auto step = [&](auto model, const auto& p) {
    typename decltype(model)::template History<3> h{};
    return decltype(model)::force(g, pair, n, p, h, dt).force[1];
  };
  // K_t = 8 G* a; for one material this equals the Mindlin ratio (1-nu)/(1-nu/2) x 2 E* a
  const double km = 8 * pair.shear_eff * a;
  CHECK(km == grain::test::approx((1 - nu) / (1 - nu / 2) * n.stiffness).epsilon(1e-12));
  CHECK(step(tangent::Mindlin{}, tangent::Mindlin::Params{.damping = 0.0}) ==
        grain::test::approx(-km * v * dt).epsilon(1e-12));
  // default damping: the normal damping ratio (LIGGGHTS: gamma_t = gamma_n sqrt(S_t/S_n))
  CHECK(step(tangent::Mindlin{}, tangent::Mindlin::Params{}) ==
        grain::test::approx(-km * v * dt - n.damping * std::sqrt(km / n.stiffness) * v)
            .epsilon(1e-12));
  // Di Renzo-Di Maio: 16/3 G* a = 2/3 of Mindlin
  CHECK(step(tangent::DiRenzoDiMaio{}, tangent::DiRenzoDiMaio::Params{}) ==
        grain::test::approx(-2.0 / 3.0 * km * v * dt).epsilon(1e-12));
  CHECK(step(tangent::DiRenzoDiMaio{}, tangent::DiRenzoDiMaio::Params{.damping = 0.2}) ==
        grain::test::approx(-2.0 / 3.0 * km * v * dt - 0.2 * v).epsilon(1e-12));
  // Tsuji: sqrt(2 R*) E* sqrt(delta)/((2 - nu)(1 + nu)), damping = the normal coefficient
  const double kt =
      std::sqrt(2 * g.r_eff) * pair.young_eff * std::sqrt(delta) / ((2 - nu) * (1 + nu));
  CHECK(kt / km == grain::test::approx(1 / (2 * std::sqrt(2.0) * (1 - nu * nu))).epsilon(1e-12));
  CHECK(step(tangent::Tsuji{}, tangent::Tsuji::Params{}) ==
        grain::test::approx(-kt * v * dt - n.damping * v).epsilon(1e-12));
  CHECK(step(tangent::Tsuji{}, tangent::Tsuji::Params{.damping = 0.0}) ==
        grain::test::approx(-kt * v * dt).epsilon(1e-12));
}

TEST_CASE_TEMPLATE("Langston-Tuzun-Heyes and Zheng-Zhu-Yu: Mindlin slope, saturation, truncation",
                   T, tangent::LangstonTuzunHeyes, tangent::ZhengZhuYu) {
  const double mu_s = 0.5, mu_d = 0.3, nu = 0.3, delta = 1e-5;
  const auto pair = pair_of(mu_d, mu_s, 0.0, 1.0, 1e7, nu); // e = 1: no normal damping
  const double v = 1e-3;
  const auto g = contact<3>(delta, along_y(v));
  typename Hz::History<3> hn{};
  const NormalResult n = Hz::force(g, pair, {}, hn);
  const double dmax = mu_s * delta * (2 - nu) / (2 * (1 - nu));
  // slope at zero elongation: 3 mu_s F_n / (2 dmax) = 8 G* a for a Hertz force of one material
  const double k0 = 1.5 * mu_s * n.force / dmax;
  CHECK(k0 == grain::test::approx(8 * pair.shear_eff * std::sqrt(g.r_eff * delta)).epsilon(1e-12));
  typename T::Params p{};
  typename T::template History<3> h{};
  const double dt = 1e-8; // elongation 1e-11 m = 1e-6 dmax
  auto r = T::force(g, pair, n, p, h, dt);
  CHECK(r.force[1] == grain::test::approx(-k0 * v * dt).epsilon(1e-5));
  CHECK(!r.sliding);
  // the dashpot at zero elongation
  if constexpr (std::is_same_v<T, tangent::LangstonTuzunHeyes>) {
    p.damping = 0.4; // a ratio of the critical damping 2 sqrt(m* k0)
    h = {};
    r = T::force(g, pair, n, p, h, dt);
    CHECK(r.force[1] ==
          grain::test::approx(-k0 * v * dt - 0.4 * 2 * std::sqrt(g.m_eff * k0) * v).epsilon(1e-5));
  } else {
    p.viscosity = 20.0;
    const double tau = 20.0 / (2 * pair.shear_eff * dmax);
    h = {};
    r = T::force(g, pair, n, p, h, dt);
    CHECK(r.force[1] ==
          grain::test::approx(-k0 * v * dt - tau * (1 - 0.4 * tau * v) * 1.5 * mu_s * n.force * v)
              .epsilon(1e-5));
    // above the slip rate 2.5/tau the dashpot switches off instead of pushing
    const auto gf = contact<3>(delta, along_y(3.0 / tau));
    h = {};
    r = T::force(gf, pair, n, p, h, 1e-15);
    CHECK(r.force[1] <= 0.0);
    CHECK(std::abs(r.force[1]) < 1e-6 * n.force);
  }
  // pushed far: sticking up to mu_s F_n, then sliding at mu_d F_n with the elongation
  // truncated where the spring holds mu_d F_n
  p = {};
  h = {};
  double fmax = 0.0;
  for (int k = 0; k < 400; ++k) {
    r = T::force(g, pair, n, p, h, 1e-2 * dmax / v); // 4 dmax in all
    fmax = std::max(fmax, r.force.norm());
  }
  CHECK(r.sliding);
  CHECK(r.force.norm() == grain::test::approx(mu_d * n.force).epsilon(1e-12));
  CHECK(fmax <= mu_s * n.force * (1 + 1e-12));
  CHECK(fmax > mu_d * n.force * 1.2);
  const double xd = dmax * (1 - std::pow(1 - mu_d / mu_s, 2.0 / 3.0));
  CHECK(load<3>(h.spring).norm() == grain::test::approx(xd).epsilon(1e-12));
  CHECK(load<3>(h.spring).norm() < dmax);
  // the stored energy is the integral of the spring force: F_s (x + 2/5 d ((1 - x/d)^(5/2) - 1))
  const double fs = mu_s * n.force;
  CHECK(r.elastic_energy ==
        grain::test::approx(fs * (xd + 0.4 * dmax * (std::pow(1 - xd / dmax, 2.5) - 1)))
            .epsilon(1e-12));
}

TEST_CASE("spring-slider: sticking against mu_s, sliding at mu_d, re-sticking on reversal") {
  using T = tangent::SpringSlider;
  const auto pair = pair_of(0.4, 0.6);
  const NormalResult n{.force = 1.0, .stiffness = 1000.0};
  const T::Params p{.stiffness = 1000.0};
  T::History<3> h{};
  auto g = contact<3>(1e-5, along_y(7e-4));
  const double dt = 1e-3; // the spring force grows by 7e-4 N per step
  double fmax = 0.0;
  int first_slip = -1;
  TangentResult<3> r;
  for (int k = 0; k < 900; ++k) {
    r = T::force(g, pair, n, p, h, dt);
    if (r.sliding && first_slip < 0) first_slip = k;
    if (!r.sliding) fmax = std::max(fmax, r.force.norm());
  }
  CHECK(first_slip == 857); // 858 x 7e-4 = 0.6006 > mu_s |F_n|
  CHECK(fmax == grain::test::approx(857 * 7e-4).epsilon(1e-9));
  CHECK(r.force[1] == grain::test::approx(-0.4).epsilon(1e-12));
  CHECK(load<3>(h.spring)[1] == grain::test::approx(0.4 / 1000.0).epsilon(1e-12));
  CHECK(r.elastic_energy == grain::test::approx(0.5 * 0.4 * 0.4 / 1000.0).epsilon(1e-12));
  // reversal: sticks at once (|F| falls below mu_d |F_n|), unloads, and loads the other way
  // until mu_s |F_n| again
  g = contact<3>(1e-5, along_y(-7e-4));
  first_slip = -1;
  fmax = -1.0;
  for (int k = 0; k < 1500; ++k) {
    r = T::force(g, pair, n, p, h, dt);
    if (r.sliding && first_slip < 0) first_slip = k;
    if (!r.sliding) fmax = std::max(fmax, r.force[1]);
  }
  CHECK(first_slip == 1428); // -0.4 + 1429 x 7e-4 = 0.6003 > mu_s |F_n|
  CHECK(fmax == grain::test::approx(-0.4 + 1428 * 7e-4).epsilon(1e-9));
  CHECK(r.force[1] == grain::test::approx(0.4).epsilon(1e-12));
}

TEST_CASE("slider and dashpot-slider: Coulomb force against the slip, viscous regime") {
  const auto pair = pair_of(0.4, 0.6);
  const NormalResult n{.force = 2.0, .stiffness = 1000.0};
  // slider: -mu_d |F_n| v/|v|, nothing without slip
  tangent::Slider::History<3> hs{};
  const Vec3 v(0, 3e-3, -4e-3);
  auto r = tangent::Slider::force(contact<3>(1e-5, v), pair, n, {}, hs, 1e-6);
  CHECK(r.force.isApprox(-0.4 * 2.0 * v.normalized()));
  CHECK(r.sliding);
  r = tangent::Slider::force(contact<3>(1e-5, Vec3::Zero()), pair, n, {}, hs, 1e-6);
  CHECK(r.force.norm() == 0.0);
  // dashpot-slider: viscous while |eta v| <= mu_s |F_n|, then mu_d |F_n|
  using DS = tangent::DashpotSlider;
  DS::History<3> h{};
  const DS::Params p{.damping = 100.0};
  r = DS::force(contact<3>(1e-5, along_y(0.011)), pair, n, p, h, 1e-6);
  CHECK(!r.sliding);
  CHECK(r.force[1] == grain::test::approx(-1.1));
  r = DS::force(contact<3>(1e-5, along_y(0.013)), pair, n, p, h, 1e-6);
  CHECK(r.sliding);
  CHECK(r.force[1] == grain::test::approx(-0.8));
  // once sliding, it stays so until the viscous force falls below mu_d |F_n|
  r = DS::force(contact<3>(1e-5, along_y(0.011)), pair, n, p, h, 1e-6);
  CHECK(r.sliding);
  r = DS::force(contact<3>(1e-5, along_y(0.007)), pair, n, p, h, 1e-6);
  CHECK(!r.sliding);
  CHECK(r.force[1] == grain::test::approx(-0.7));
  // default damping: zeta_t x 2 sqrt(m* k_n / kappa)
  DS::History<2> h2{};
  const auto g2 = contact<2>(1e-5, Vec2(0, 1e-4));
  const auto r2 = DS::force(g2, pair, n, {}, h2, 1e-6);
  CHECK(r2.force[1] == grain::test::approx(-2 * std::sqrt(g2.m_eff * 1000.0 / 3) * 1e-4));
  tangent::Dashpot::History<3> hd{};
  const auto rd = tangent::Dashpot::force(contact<3>(1e-5, along_y(1e-4)), pair, n,
                                          {.damping_ratio = 0.5}, hd, 1e-6);
  CHECK(rd.force[1] == grain::test::approx(-0.5 * 2 * std::sqrt(0.5e-5 * 1000.0 / 3.5) * 1e-4));
}

TEST_CASE("tangential spring: the history follows the turning contact and mirrors on swap") {
  using T = tangent::Mindlin;
  const auto pair = pair_of(0.5);
  auto g = contact<3>(1e-5, Vec3(0, 1e-3, 2e-3));
  typename Hz::History<3> hn{};
  const NormalResult n = Hz::force(g, pair, {}, hn);
  T::History<3> h{};
  for (int k = 0; k < 5; ++k)
    T::force(g, pair, n, {}, h, 1e-6);
  const double len = load<3>(h.spring).norm();
  CHECK(len > 0.0);
  g.normal = Vec3(std::cos(0.2), std::sin(0.2), 0.0);
  g.tangential_velocity = g.slip_velocity = Vec3::Zero();
  T::force(g, pair, n, {}, h, 1e-6);
  CHECK(std::abs(load<3>(h.spring).dot(g.normal)) < 1e-18);
  CHECK(load<3>(h.spring).norm() == grain::test::approx(len).epsilon(1e-12));
  const Vec3 before = load<3>(h.spring);
  T::reverse(h);
  CHECK(load<3>(h.spring).isApprox(-before));
}

TEST_CASE("rolling::Constant and rolling::Viscous: closed forms") {
  const double mu_r = 0.1;
  const auto pair = pair_of(0.5, 0.5, mu_r);
  ContactGeometry<3> g;
  // relative rotation with a twist part along the normal x, which is ignored
  pair_geometry<3>(g, Vec3::Zero(), Vec3::UnitX(), 1.99e-3, 1e-3, 1.5e-3, 1e-5, 2e-5, Vec3::Zero(),
                   Vec3::Zero(), Vec3(7, 3, 0), Vec3(0, 0, -4));
  typename Hz::History<3> hn{};
  const NormalResult n = Hz::force(g, pair, {}, hn);
  const Vec3 wr(0, 3, 4);
  rolling::Constant::History<3> hc{};
  Vec3 ti = Vec3::Zero(), tj = Vec3::Zero();
  rolling::Constant::torque(g, pair, n, {}, hc, 1e-6, ti, tj);
  CHECK(ti.isApprox(-mu_r * g.r_eff * n.force * wr.normalized()));
  CHECK((ti + tj).norm() == 0.0);
  ti = tj = Vec3::Zero();
  rolling::Constant::torque(g, pair, n, {.coefficient = 0.3}, hc, 1e-6, ti, tj);
  CHECK(ti.isApprox(-0.3 * g.r_eff * n.force * wr.normalized()));
  // viscous: -mu_r R*^2 |F_n| w_r = -mu_r R* |F_n| v_r w_r/|w_r|, mu_r in s/m
  rolling::Viscous::History<3> hv{};
  ti = tj = Vec3::Zero();
  rolling::Viscous::torque(g, pair, n, {.coefficient = 0.5}, hv, 1e-6, ti, tj);
  CHECK(ti.isApprox(-0.5 * g.r_eff * n.force * (g.r_eff * wr.norm()) * wr.normalized()));
  CHECK((ti + tj).norm() == 0.0);
  // 2D: the scalar relative spin
  ContactGeometry<2> g2;
  pair_geometry<2>(g2, Vec2::Zero(), Vec2::UnitX(), 1.99e-3, 1e-3, 1e-3, 1e-5, 1e-5, Vec2::Zero(),
                   Vec2::Zero(), -3.0, 2.0);
  typename Hz::History<2> hn2{};
  const NormalResult n2 = Hz::force(g2, pair, {}, hn2);
  rolling::Constant::History<2> hc2{};
  double si = 0.0, sj = 0.0;
  rolling::Constant::torque(g2, pair, n2, {}, hc2, 1e-6, si, sj);
  CHECK(si == grain::test::approx(mu_r * g2.r_eff * n2.force));
  CHECK(sj == -si);
  // no relative rotation, no torque (a rigidly co-rotating pair)
  pair_geometry<2>(g2, Vec2::Zero(), Vec2::UnitX(), 1.99e-3, 1e-3, 1e-3, 1e-5, 1e-5, Vec2::Zero(),
                   Vec2::Zero(), 2.0, 2.0);
  si = sj = 0.0;
  rolling::Constant::torque(g2, pair, n2, {}, hc2, 1e-6, si, sj);
  rolling::Viscous::History<2> hv2{};
  rolling::Viscous::torque(g2, pair, n2, {}, hv2, 1e-6, si, sj);
  CHECK(si == 0.0);
  CHECK(sj == 0.0);
}

TEST_CASE("rolling::EPSD: stiffness, damping, full mobilisation, history") {
  using R = rolling::EPSD;
  const double mu_r = 0.1;
  const auto pair = pair_of(0.5, 0.5, mu_r);
  ContactGeometry<3> g;
  pair_geometry<3>(g, Vec3::Zero(), Vec3::UnitX(), 1.99e-3, 1e-3, 1e-3, 1e-5, 1e-5, Vec3::Zero(),
                   Vec3::Zero(), Vec3(0, 2, 0), Vec3::Zero());
  typename Hz::History<3> hn{};
  const NormalResult n = Hz::force(g, pair, {}, hn);
  const double kr = 2.25 * n.stiffness * mu_r * mu_r * g.r_eff * g.r_eff;
  const double ir = 1.4 * g.m_eff * g.r_eff * g.r_eff;
  const double cr = 2 * 0.3 * std::sqrt(ir * kr);
  const double limit = mu_r * g.r_eff * n.force;
  const double dt = 1e-5;
  CHECK(R::rolling_stiffness(g, pair, n, {}) == grain::test::approx(kr).epsilon(1e-14));
  R::History<3> h{};
  Vec3 ti = Vec3::Zero(), tj = Vec3::Zero();
  R::torque(g, pair, n, {}, h, dt, ti, tj);
  CHECK(ti.y() == grain::test::approx(-kr * 2 * dt - cr * 2).epsilon(1e-12));
  CHECK((ti + tj).norm() == 0.0);
  CHECK(load<3>(h.torque).y() == grain::test::approx(-kr * 2 * dt).epsilon(1e-12));
  // keep rolling: the spring torque saturates at mu_r R* |F_n|, without damping (f = 0)
  for (int k = 0; k < 20000; ++k) {
    ti = tj = Vec3::Zero();
    R::torque(g, pair, n, {}, h, dt, ti, tj);
  }
  CHECK(ti.y() == grain::test::approx(-limit).epsilon(1e-12));
  CHECK(R::elastic_energy(h, kr) == grain::test::approx(limit * limit / (2 * kr)).epsilon(1e-12));
  ti = tj = Vec3::Zero();
  auto h1 = h;
  R::torque(g, pair, n, {.damping_at_limit = true}, h1, dt, ti, tj);
  CHECK(ti.y() == grain::test::approx(-limit - cr * 2).epsilon(1e-12));
  // given stiffness and coefficient
  ti = tj = Vec3::Zero();
  R::History<3> h2{};
  R::torque(g, pair, n, {.coefficient = 0.2, .stiffness = 1e-3, .damping_ratio = 0.0}, h2, dt, ti,
            tj);
  CHECK(ti.y() == grain::test::approx(-1e-3 * 2 * dt).epsilon(1e-12));
  // reverse and rotation with the contact
  const Vec3 before = load<3>(h.torque);
  R::reverse(h);
  CHECK(load<3>(h.torque).isApprox(-before));
  g.normal = Vec3(std::cos(0.3), 0.0, std::sin(0.3));
  g.omega_rel = g.slip_omega_rel = Vec3::Zero();
  ti = tj = Vec3::Zero();
  R::torque(g, pair, n, {}, h, dt, ti, tj);
  CHECK(std::abs(load<3>(h.torque).dot(g.normal)) < 1e-20);
  CHECK(load<3>(h.torque).norm() == grain::test::approx(before.norm()).epsilon(1e-12));
  // 2D: scalar history, 1/2 m R^2 disks
  ContactGeometry<2> g2;
  pair_geometry<2>(g2, Vec2::Zero(), Vec2::UnitX(), 1.99e-3, 1e-3, 1e-3, 1e-5, 1e-5, Vec2::Zero(),
                   Vec2::Zero(), 2.0, 0.0);
  typename Hz::History<2> hn2{};
  const NormalResult n2 = Hz::force(g2, pair, {}, hn2);
  R::History<2> h3{};
  double si = 0.0, sj = 0.0;
  R::torque(g2, pair, n2, {}, h3, dt, si, sj);
  const double cr2 = 2 * 0.3 * std::sqrt(1.5 * g2.m_eff * g2.r_eff * g2.r_eff * kr);
  CHECK(si == grain::test::approx(-kr * 2 * dt - cr2 * 2).epsilon(1e-12));
  CHECK(sj == -si);
  R::reverse(h3);
  CHECK(h3.torque == grain::test::approx(kr * 2 * dt).epsilon(1e-12));
}

// ------------------------------------------------------------------ parameter checks
TEST_CASE("tangential and rolling models: bad parameters name the model, value and range") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  CHECK(rejects([] { tangent::Spring::validate({.stiffness = -1.0}); },
                {"tangent::Spring", "stiffness", "-1", "[0, inf)"}));
  CHECK(rejects([] { tangent::Spring::validate({.stiffness_ratio = -2.0}); },
                {"tangent::Spring", "stiffness_ratio", "-2", "valid range"}));
  CHECK(rejects([] { tangent::SpringSlider::validate({.stiffness = -5.0}); },
                {"tangent::SpringSlider", "stiffness", "-5", "[0, inf)"}));
  CHECK(rejects([&] { tangent::SpringDashpotSlider::validate({.damping = nan}); },
                {"tangent::SpringDashpotSlider", "damping", "nan", "valid range"}));
  CHECK(rejects([] { tangent::SpringDashpotSlider::validate({.restitution = 1.5}); },
                {"tangent::SpringDashpotSlider", "restitution", "1.5", "[0, 1]"}));
  CHECK(rejects([] { tangent::SpringDashpotSlider::validate({.kappa = 0.5}); },
                {"tangent::SpringDashpotSlider", "kappa", "0.5", "(1, inf)"}));
  CHECK(rejects([] { tangent::Dashpot::validate({.damping = -1.0}); },
                {"tangent::Dashpot", "damping", "-1", "[0, inf)"}));
  CHECK(rejects([] { tangent::Dashpot::validate({.damping_ratio = -0.5}); },
                {"tangent::Dashpot", "damping_ratio", "-0.5", "[0, inf)"}));
  CHECK(rejects([] { tangent::DashpotSlider::validate({.kappa = 0.9}); },
                {"tangent::DashpotSlider", "kappa", "0.9", "(1, inf)"}));
  CHECK(rejects([&] { tangent::Mindlin::validate({.damping = inf}); },
                {"tangent::Mindlin", "damping", "inf", "valid range"}));
  CHECK(rejects([] { tangent::DiRenzoDiMaio::validate({.damping = -0.1}); },
                {"tangent::DiRenzoDiMaio", "damping", "-0.1", "[0, inf)"}));
  CHECK(rejects([&] { tangent::Tsuji::validate({.damping = nan}); },
                {"tangent::Tsuji", "damping", "nan", "valid range"}));
  CHECK(rejects([] { tangent::LangstonTuzunHeyes::validate({.damping = -0.3}); },
                {"tangent::LangstonTuzunHeyes", "damping", "-0.3", "[0, inf)"}));
  CHECK(rejects([] { tangent::ZhengZhuYu::validate({.viscosity = -2.0}); },
                {"tangent::ZhengZhuYu", "viscosity", "-2", "[0, inf)"}));
  CHECK(rejects([&] { rolling::Constant::validate({.coefficient = nan}); },
                {"rolling::Constant", "coefficient", "nan", "valid range"}));
  CHECK(rejects([&] { rolling::Viscous::validate({.coefficient = inf}); },
                {"rolling::Viscous", "coefficient", "inf", "valid range"}));
  CHECK(rejects([] { rolling::EPSD::validate({.damping_ratio = -1.0}); },
                {"rolling::EPSD", "damping_ratio", "-1", "[0, inf)"}));
  CHECK(rejects([] { rolling::EPSD::validate({.stiffness = -1.0}); },
                {"rolling::EPSD", "stiffness", "-1", "[0, inf)"}));
  CHECK(rejects([] { rolling::EPSD::validate({.inertia_factor = 2.0}); },
                {"rolling::EPSD", "inertia_factor", "2", "(0, 1]"}));
  // through a simulation: the constructor validates the contact models
  using C = Interaction<Hz, tangent::Mindlin, rolling::EPSD>;
  using Sim = Simulation<Sphere, search::AllPairs, C>;
  CHECK(rejects(
      [] {
        Sim::Params p;
        p.contact.rolling.damping_ratio = -0.2;
        Sim sim(p);
      },
      {"rolling::EPSD", "damping_ratio", "-0.2"}));
  // good defaults pass
  CHECK_NOTHROW(C::validate({}));
  CHECK_NOTHROW((Interaction<Hz, tangent::SpringDashpotSlider, rolling::Constant>::validate({})));
}

// The saturating springs (Langston-Tuzun-Heyes, Zheng-Zhu-Yu) with mu_s = mu_d: a contact
// driven 2 mm along the tangent plane (about 300 delta_t,max; F_n = 1 N, mu = 0.5) slides with
// its elongation held at delta_t,max (|xi| <= delta_t,max (1 + 1e-12)), and when the motion
// reverses the spring unloads: the work the tangential force does along the motion is at most
// the elastic energy stored at the reversal (1e-9 relative); an elongation left growing gave
// 0.5 N x 1 mm, 300 times that energy.
TEST_CASE("tangent: a saturated Mindlin-Deresiewicz spring slides and unloads on reversal") {
  auto drive = [](auto model, auto prm) {
    using M = decltype(model);
    ContactGeometry<2> g;
    g.normal = Vec2(1, 0);
    g.overlap = 1e-5;
    g.r_eff = 1e-3;
    g.m_eff = 1e-3;
    g.radius_i = g.radius_j = 2e-3;
    PairProperties pair;
    pair.friction = pair.friction_static = 0.5;
    pair.poisson_avg = 0.3;
    pair.shear_eff = pair.young_eff = 1e9;
    NormalResult n;
    n.force = 1.0;
    n.stiffness = 1e5;
    typename M::template History<2> h{};
    const double dt = 1e-6, v = 1.0;
    TangentResult<2> r;
    double largest = 0.0;
    for (int s = 0; s < 2000; ++s) {
      g.slip_velocity = g.tangential_velocity = Vec2(0, v);
      r = M::force(g, pair, n, prm, h, dt);
      largest = std::max(largest, std::abs(h.spring[1]));
    }
    CHECK(r.sliding);
    CHECK(r.force.y() == grain::test::approx(-0.5).epsilon(1e-12));
    const double stored = r.elastic_energy;
    CHECK(stored > 0.0);
    double work = 0.0;
    for (int s = 0; s < 1000; ++s) {
      g.slip_velocity = g.tangential_velocity = Vec2(0, -v);
      r = M::force(g, pair, n, prm, h, dt);
      work += std::max(0.0, r.force.y() * -v * dt);
    }
    CHECK(work <= stored * (1 + 1e-9));
    return largest;
  };
  const double dmax = 0.5 * 1e-5 * (2 - 0.3) / (2 * (1 - 0.3)); // mu_s delta (2 - nu)/(2 (1 - nu))
  CHECK(drive(tangent::LangstonTuzunHeyes{}, tangent::LangstonTuzunHeyes::Params{.damping = 0.3}) <=
        dmax * (1 + 1e-12));
  CHECK(drive(tangent::ZhengZhuYu{}, tangent::ZhengZhuYu::Params{}) <= dmax * (1 + 1e-12));
}

TEST_CASE("Walton-Braun with a linear tangential spring: no force jump where loading turns to "
          "unloading") {
  // A stuck spring keeps F_t = -k_t xi while the contact turns from loading to unloading, with no
  // tangential motion. k_t = ratio x the normal model's stiffness; were that the unloading slope
  // K_U = K_L / e^2, |F_t| would be multiplied by 1/e^2 = 4 here without any work done on it.
  using C = Interaction<normal::WaltonBraun, tangent::SpringSlider>;
  const auto pair = pair_of(0.5);
  const C::Params p = C::resolve(C::Params{.normal = {.stiffness = 1e3}}, pair);
  C::History<3> h{};
  const double r = 1e-3, m = 1e-5, dt = 1e-7;
  auto at = [&](double delta, double vn, double vt) {
    ContactGeometry<3> g;
    pair_geometry<3>(g, Vec3::Zero(), Vec3::UnitX(), 2 * r - delta, r, r, m, m, Vec3(vn, vt, 0),
                     Vec3::Zero(), Vec3::Zero(), Vec3::Zero());
    return C::evaluate(g, pair, p, h, dt);
  };
  // load to 2e-5 m while sliding 1e-8 m sideways (mu F_n = 1e-2 N at the end: the spring sticks)
  for (int k = 1; k <= 100; ++k)
    at(2e-7 * k, 2e-7 / dt, 1e-10 / dt);
  const auto loaded = at(2e-5, 0.0, 0.0);
  CHECK_FALSE(loaded.tangent.sliding);
  CHECK(loaded.tangent.force.norm() > 0.0);
  // unload by 1 % of the overlap with no tangential motion: the normal force drops along K_U,
  // the tangential force stays (up to the carried spring's rounding)
  const auto unloaded = at(1.98e-5, -2e-7 / dt, 0.0);
  CHECK(unloaded.normal.force < loaded.normal.force);
  CHECK_FALSE(unloaded.tangent.sliding);
  CHECK(unloaded.tangent.force.norm() ==
        grain::test::approx(loaded.tangent.force.norm()).epsilon(1e-12));
}
