// The normal contact models one by one: formulas, history, the properties every option must
// have (no force at rest, no energy created over a closed cycle, a wall is the limit of a large
// particle, action equals reaction) and the errors raised for bad parameters.
#include "../approx.hpp"
#include "../errors.hpp"
#include <algorithm>
#include <cmath>
#include <doctest/doctest.h>
#include <grain/grain.hpp>
#include <grain/models/normal/hertz.hpp>
#include <grain/models/normal/hertz_damping.hpp>
#include <grain/models/normal/hertz_equivalent.hpp>
#include <grain/models/normal/linear_spring_dashpot.hpp>
#include <grain/models/normal/walton_braun.hpp>
#include <limits>
#include <numbers>
#include <string>
#include <type_traits>

using namespace grain;

// ---- every model and option is a normal model; history costs nothing unless it is needed
static_assert(NormalModel<normal::LinearSpringDashpot>);
static_assert(NormalModel<normal::LinearSpringDashpotPerContact>);
static_assert(NormalModel<normal::Hertz<normal::TsujiDamping>>);
static_assert(NormalModel<normal::Hertz<normal::CriticalRatioDamping>>);
static_assert(NormalModel<normal::Hertz<normal::KuwabaraKonoDamping>>);
static_assert(NormalModel<normal::Hertz<normal::LeeHerrmannDamping>>);
static_assert(NormalModel<normal::WaltonBraun> && NormalModel<normal::WaltonBraunPerContact>);
static_assert(std::is_same_v<normal::Hertz<>, normal::Hertz<normal::TsujiDamping>>);
static_assert(std::is_same_v<normal::LinearSpringDashpot,
                             normal::BasicLinearSpringDashpot<normal::ReferenceVelocity>>);
static_assert(std::is_empty_v<normal::LinearSpringDashpot::History<2>> &&
              std::is_empty_v<normal::LinearSpringDashpot::History<3>>);
static_assert(Interaction<normal::LinearSpringDashpot>::stateless<3> &&
              Interaction<normal::Hertz<normal::KuwabaraKonoDamping>>::stateless<3> &&
              Interaction<normal::Hertz<normal::LeeHerrmannDamping>>::stateless<2> &&
              Interaction<normal::Hertz<normal::CriticalRatioDamping>>::stateless<2>);
static_assert(sizeof(normal::LinearSpringDashpotPerContact::History<3>) == sizeof(double));
static_assert(sizeof(normal::WaltonBraun::History<3>) == 2 * sizeof(double));
static_assert(sizeof(normal::WaltonBraunPerContact::History<2>) == 3 * sizeof(double));
static_assert(sizeof(Interaction<normal::WaltonBraun, tangent::SpringDashpotSlider>::History<3>) ==
              sizeof(normal::WaltonBraun::History<3>) +
                  sizeof(tangent::SpringDashpotSlider::History<3>));
static_assert(std::is_trivially_copyable_v<normal::LinearSpringDashpotPerContact::History<3>>);
static_assert(std::is_trivially_copyable_v<normal::WaltonBraun::History<2>>);
static_assert(std::is_trivially_copyable_v<normal::WaltonBraunPerContact::History<3>>);
static_assert(std::is_trivially_copyable_v<Interaction<normal::WaltonBraunPerContact>::History<3>>);

namespace {

constexpr double pi = std::numbers::pi;
constexpr double R = 1e-3;  // particle radius [m]
constexpr double M = 1e-5;  // particle mass [kg]
constexpr double big = 1e6; // partner/particle ratio of radius and mass for the wall limit

PairProperties pair_with(double e) {
  const Material m{.density = 2500, .young = 1e7, .poisson = 0.3, .restitution = e};
  return PairProperties::mix(m, m);
}

/// Head-on contact of particle i (radius ri, mass mi, at the origin, moving at `rate` along +x)
/// with particle j (rj, mj, at rest) at overlap `delta`.
template <int D>
ContactGeometry<D> pair_contact(double delta, double rate, double ri = R, double mi = M,
                                double rj = R, double mj = M) {
  ContactGeometry<D> g;
  const Vec<D> x = Vec<D>::UnitX();
  pair_geometry<D>(g, Vec<D>::Zero(), x, ri + rj - delta, ri, rj, mi, mj, Vec<D>(rate * x),
                   Vec<D>::Zero(), zero<Angular<D>>(), zero<Angular<D>>());
  return g;
}

/// The same contact seen from j: normal reversed, roles swapped.
template <int D>
ContactGeometry<D> pair_contact_from_j(double delta, double rate, double ri, double mi, double rj,
                                       double mj) {
  ContactGeometry<D> g;
  const Vec<D> x = Vec<D>::UnitX();
  const double dist = ri + rj - delta;
  pair_geometry<D>(g, Vec<D>(dist * x), Vec<D>(-x), dist, rj, ri, mj, mi, Vec<D>::Zero(),
                   Vec<D>(rate * x), zero<Angular<D>>(), zero<Angular<D>>());
  return g;
}

/// Particle i (radius R, mass M, at the origin, moving at `rate` along +x) touching a flat wall
/// (a plane in 3D, a segment in 2D) at overlap `delta`.
template <int D>
ContactGeometry<D> wall_contact(double delta, double rate) {
  Wall<D> w;
  const double x = R - delta;
  if constexpr (D == 3)
    w.geometry = walls::Plane{Vec3(x, 0, 0), Vec3(-1, 0, 0)};
  else
    w.geometry = walls::Segment{Vec2(x, -1), Vec2(x, 1)};
  ContactGeometry<D> g;
  const Vec<D> origin = Vec<D>::Zero();
  wall_geometry<D>(g, w, w.proximity(origin), origin, R, M, Vec<D>(rate * Vec<D>::UnitX()),
                   zero<Angular<D>>());
  return g;
}

/// A closed loading path: delta(t) = d0 sin(pi t/T) (1 + a sin(4 pi t/T)), t in [0, T]; with
/// a > 0.25 it unloads part-way and re-loads in the middle.
struct Cycle {
  double d0, T, a;
  double delta(double t) const {
    return d0 * std::sin(pi * t / T) * (1 + a * std::sin(4 * pi * t / T));
  }
  double rate(double t) const {
    const double s = std::sin(pi * t / T), c = std::cos(pi * t / T);
    return d0 * (pi / T) *
           (c * (1 + a * std::sin(4 * pi * t / T)) + s * a * 4 * std::cos(4 * pi * t / T));
  }
};

/// Work done on the contact along a cycle, W = int F d(delta) (midpoint rule), and the largest
/// elastic energy met on the way.
template <class Model, class Geometry>
std::pair<double, double> cycle_work(const typename Model::Params& p, const PairProperties& pair,
                                     const Cycle& c, Geometry geometry) {
  typename Model::template History<3> h{};
  const int n = 20000;
  const double dt = c.T / n;
  double w = 0.0, peak = 0.0;
  for (int k = 0; k < n; ++k) {
    const double t = (k + 0.5) * dt;
    const auto r = Model::force(geometry(c.delta(t), c.rate(t)), pair, p, h);
    w += r.force * c.rate(t) * dt;
    peak = std::max(peak, r.elastic_energy);
  }
  return {w, peak};
}

/// One entry of the catalogue: a model, its parameters, the pair's restitution, and whether the
/// option is elastic (dissipates nothing).
template <class Model>
struct Entry {
  using model = Model;
  const char* label;
  typename Model::Params params;
  double restitution;
  bool elastic;
};

/// Calls f(entry) for every model and option.
template <class F>
void for_each_option(F&& f) {
  using namespace normal;
  using LSD = LinearSpringDashpot;
  using LSDC = LinearSpringDashpotPerContact;
  const double kk = 0.2 * std::pow(4.0 / 3.0 * pair_with(1).young_eff * std::sqrt(0.5 * R), 0.6) *
                    std::pow(0.5 * M, 0.4) / std::pow(0.1, 0.2); // kappa ~ 0.2 at 0.1 m/s
  f(Entry<LSD>{"linear, K given", {.stiffness = 500.0}, 0.5, false});
  f(Entry<LSD>{"linear, K given, e = 1", {.stiffness = 500.0}, 1.0, true});
  f(Entry<LSD>{"linear, K and eta given", {.stiffness = 500.0, .damping = 0.01}, 1.0, false});
  f(Entry<LSD>{"linear, no cohesion", {.stiffness = 500.0, .no_cohesion = true}, 0.3, false});
  f(Entry<LSD>{"linear, energy", {.equivalence = Equivalence::energy}, 0.5, false});
  f(Entry<LSD>{"linear, overlap", {.equivalence = Equivalence::overlap}, 0.5, false});
  f(Entry<LSD>{"linear, time", {.equivalence = Equivalence::time}, 0.5, false});
  f(Entry<LSDC>{"linear per contact, energy", {.reference_velocity = 0.2}, 0.5, false});
  f(Entry<LSDC>{"linear per contact, time, no cohesion",
                {.no_cohesion = true, .equivalence = Equivalence::time},
                0.2,
                false});
  f(Entry<LSDC>{"linear per contact, K given", {.stiffness = 500.0}, 0.5, false});
  f(Entry<Hertz<>>{"Hertz-Tsuji, exact map", {}, 0.5, false});
  f(Entry<Hertz<>>{"Hertz-Tsuji, e = 1", {}, 1.0, true});
  f(Entry<Hertz<>>{"Hertz-Tsuji, Norouzi", {.damping = {.map = TsujiMap::norouzi}}, 0.2, false});
  f(Entry<Hertz<>>{"Hertz-Tsuji, alpha given", {.damping = {.alpha = 0.3}}, 1.0, false});
  f(Entry<Hertz<>>{"Hertz-Tsuji, no cohesion", {.no_cohesion = true}, 0.1, false});
  f(Entry<Hertz<CriticalRatioDamping>>{
      "Hertz-critical ratio", {.damping = {.ratio = 0.2}}, 1.0, false});
  f(Entry<Hertz<CriticalRatioDamping>>{
      "Hertz-critical ratio 0", {.damping = {.ratio = 0.0}}, 1.0, true});
  f(Entry<Hertz<CriticalRatioDamping>>{"Hertz-critical ratio, no cohesion",
                                       {.no_cohesion = true, .damping = {.ratio = 0.5}},
                                       1.0,
                                       false});
  f(Entry<Hertz<KuwabaraKonoDamping>>{
      "Hertz-Kuwabara-Kono", {.damping = {.coefficient = kk}}, 1.0, false});
  f(Entry<Hertz<KuwabaraKonoDamping>>{"Hertz-Kuwabara-Kono, no cohesion",
                                      {.no_cohesion = true, .damping = {.coefficient = kk}},
                                      1.0,
                                      false});
  f(Entry<Hertz<LeeHerrmannDamping>>{
      "Hertz-Lee-Herrmann", {.damping = {.coefficient = 2000}}, 1.0, false});
  f(Entry<Hertz<LeeHerrmannDamping>>{"Hertz-Lee-Herrmann, no cohesion",
                                     {.no_cohesion = true, .damping = {.coefficient = 2000}},
                                     1.0,
                                     false});
  f(Entry<WaltonBraun>{"Walton-Braun, K_L given", {.stiffness = 1e3}, 0.5, false});
  f(Entry<WaltonBraun>{"Walton-Braun, e = 1", {.stiffness = 1e3}, 1.0, true});
  f(Entry<WaltonBraun>{"Walton-Braun, energy", {}, 0.5, false});
  f(Entry<WaltonBraun>{"Walton-Braun, time", {.equivalence = Equivalence::time}, 0.5, false});
  f(Entry<WaltonBraun>{"Walton-Braun, variable",
                       {.stiffness = 1e3, .unloading = Unloading::variable, .unloading_slope = 1e5},
                       0.5,
                       false});
  f(Entry<WaltonBraun>{
      "Walton-Braun, variable, time",
      {.equivalence = Equivalence::time, .unloading = Unloading::variable, .unloading_slope = 1e5},
      0.5,
      false});
  f(Entry<WaltonBraun>{"Walton-Braun, capped", {.stiffness = 1e3, .max_force = 4e-3}, 0.5, false});
  f(Entry<WaltonBraunPerContact>{
      "Walton-Braun per contact", {.reference_velocity = 0.2}, 0.5, false});
}

double rel(double a, double b) {
  const double s = std::max(std::abs(a), std::abs(b));
  return s > 0 ? std::abs(a - b) / s : 0.0;
}

using grain::test::error_of;

} // namespace

TEST_CASE("normal models: no force at zero overlap and zero rate") {
  for_each_option([](const auto& entry) {
    using Model = typename std::decay_t<decltype(entry)>::model;
    INFO(std::string(entry.label));
    const auto pair = pair_with(entry.restitution);
    typename Model::template History<3> h3{}, w3{};
    typename Model::template History<2> h2{}, w2{};
    const auto r3 = Model::force(pair_contact<3>(0.0, 0.0), pair, entry.params, h3);
    const auto r2 = Model::force(pair_contact<2>(0.0, 0.0), pair, entry.params, h2);
    const auto rw3 = Model::force(wall_contact<3>(0.0, 0.0), pair, entry.params, w3);
    const auto rw2 = Model::force(wall_contact<2>(0.0, 0.0), pair, entry.params, w2);
    for (const auto& r : {r3, r2, rw3, rw2}) {
      CHECK(r.force == 0.0);
      CHECK(r.elastic_energy == 0.0);
    }
  });
}

TEST_CASE("normal models: no energy is created over a closed loading/unloading cycle") {
  for_each_option([](const auto& entry) {
    using Model = typename std::decay_t<decltype(entry)>::model;
    const auto pair = pair_with(entry.restitution);
    auto on_pair = [](double d, double v) { return pair_contact<3>(d, v); };
    auto on_wall = [](double d, double v) { return wall_contact<3>(d, v); };
    // a simple cycle and one that unloads part-way and re-loads; slow and fast
    for (const Cycle c : {Cycle{1e-5, 3e-4, 0.0}, Cycle{1e-5, 3e-4, 0.4}, Cycle{2e-5, 2e-5, 0.4}}) {
      INFO(std::string(entry.label));
      CAPTURE(c.T);
      CAPTURE(c.a);
      for (bool wall : {false, true}) {
        CAPTURE(wall);
        const auto [w, peak] = wall ? cycle_work<Model>(entry.params, pair, c, on_wall)
                                    : cycle_work<Model>(entry.params, pair, c, on_pair);
        REQUIRE(peak > 0.0);
        // the path ends at zero overlap, where no energy is stored: W is the dissipated energy
        CHECK(w >= -1e-6 * peak);
        if (entry.elastic)
          CHECK(std::abs(w) <= 1e-6 * peak);
        else
          CHECK(w > 1e-3 * peak);
      }
    }
  });
}

TEST_CASE("normal models: a wall is the limit of a large, heavy particle") {
  for_each_option([](const auto& entry) {
    using Model = typename std::decay_t<decltype(entry)>::model;
    INFO(std::string(entry.label));
    const auto pair = pair_with(entry.restitution);
    const Cycle c{1e-5, 3e-4, 0.4};
    typename Model::template History<3> hp{}, hw{};
    typename Model::template History<2> hp2{}, hw2{};
    for (int k = 0; k < 200; ++k) {
      const double t = (k + 0.5) * c.T / 200;
      const double d = c.delta(t), v = c.rate(t);
      const auto rp =
          Model::force(pair_contact<3>(d, v, R, M, big * R, big * M), pair, entry.params, hp);
      const auto rw = Model::force(wall_contact<3>(d, v), pair, entry.params, hw);
      const auto rp2 =
          Model::force(pair_contact<2>(d, v, R, M, big * R, big * M), pair, entry.params, hp2);
      const auto rw2 = Model::force(wall_contact<2>(d, v), pair, entry.params, hw2);
      // forces relative to the size of their elastic and viscous parts (they may cancel)
      const double scale = rw.stiffness * d + std::abs(rw.damping * v) + std::abs(rw.force);
      CHECK(std::abs(rp.force - rw.force) <= 1e-5 * scale);
      CHECK(rel(rp.stiffness, rw.stiffness) < 1e-5);
      CHECK(rel(rp.damping, rw.damping) < 1e-5);
      CHECK(rel(rp.elastic_energy, rw.elastic_energy) < 1e-5);
      CHECK(std::abs(rp2.force - rw2.force) <= 1e-5 * scale);
      CHECK(std::abs(rw2.force - rw.force) <= 1e-12 * scale); // 2D and 3D agree
    }
  });
}

TEST_CASE("normal models: action equals reaction at the Interaction level") {
  for_each_option([](const auto& entry) {
    using Model = typename std::decay_t<decltype(entry)>::model;
    using Contact = Interaction<Model>;
    INFO(std::string(entry.label));
    const auto pair = pair_with(entry.restitution);
    typename Contact::Params p;
    p.normal = entry.params;
    const Cycle c{1e-5, 3e-4, 0.4};
    const double ri = R, mi = M, rj = 2.5 * R, mj = 4 * M;
    typename Contact::template History<3> hij{}, hji{};
    for (int k = 0; k < 200; ++k) {
      const double t = (k + 0.5) * c.T / 200;
      const double d = c.delta(t), v = c.rate(t);
      const auto gij = pair_contact<3>(d, v, ri, mi, rj, mj);
      const auto gji = pair_contact_from_j<3>(d, v, ri, mi, rj, mj);
      const auto rij = Contact::evaluate(gij, pair, p, hij, 1e-7);
      const auto rji = Contact::evaluate(gji, pair, p, hji, 1e-7);
      // the force on i computed from i equals minus the force on j computed from j
      CHECK((rij.force + rji.force).norm() <= 1e-12 * rij.force.norm());
      CHECK(rij.normal.force == grain::test::approx(rji.normal.force).epsilon(1e-12));
      // repulsive forces push i away from j (along -x)
      if (rij.normal.force > 0) CHECK(rij.force.x() < 0.0);
    }
  });
}

TEST_CASE("normal models: stiffness is the tangent of the elastic force, energy its integral") {
  // loading from zero at zero rate: F_el(delta), stiffness = dF_el/d delta,
  // elastic energy = int F_el d delta (Walton-Braun: the recoverable part F^2/(2 K_U))
  using namespace normal;
  const auto pair = pair_with(0.5);
  const double d = 1e-5, h = 1e-9;
  auto at = [&](auto model, const auto& prm, double delta) {
    using Model = decltype(model);
    typename Model::template History<3> hist{};
    return Model::force(pair_contact<3>(delta, 0.0), pair, prm, hist);
  };
  {
    const LinearSpringDashpot::Params prm{.equivalence = Equivalence::time};
    const auto r = at(LinearSpringDashpot{}, prm, d);
    const double fd = (at(LinearSpringDashpot{}, prm, d + h).force -
                       at(LinearSpringDashpot{}, prm, d - h).force) /
                      (2 * h);
    CHECK(r.stiffness == grain::test::approx(fd).epsilon(1e-6));
    CHECK(r.elastic_energy == grain::test::approx(0.5 * r.force * d).epsilon(1e-12));
  }
  {
    const auto r = at(Hertz<KuwabaraKonoDamping>{}, Hertz<KuwabaraKonoDamping>::Params{}, d);
    const double fd =
        (at(Hertz<KuwabaraKonoDamping>{}, Hertz<KuwabaraKonoDamping>::Params{}, d + h).force -
         at(Hertz<KuwabaraKonoDamping>{}, Hertz<KuwabaraKonoDamping>::Params{}, d - h).force) /
        (2 * h);
    CHECK(r.stiffness == grain::test::approx(fd).epsilon(1e-6));
    CHECK(r.elastic_energy == grain::test::approx(0.4 * r.force * d).epsilon(1e-12));
  }
  {
    const WaltonBraun::Params prm{.stiffness = 1e3};
    const auto r = at(WaltonBraun{}, prm, d);
    CHECK(r.stiffness == 1e3);
    CHECK(r.force == grain::test::approx(1e3 * d).epsilon(1e-14));
    CHECK(r.elastic_energy ==
          grain::test::approx(r.force * r.force / (2 * 1e3 / 0.25)).epsilon(1e-14));
    CHECK(r.damping == 0.0);
  }
}

TEST_CASE("linear spring-dashpot: Hertz-equivalent stiffness formulations and damping") {
  using normal::Equivalence;
  using M_ = normal::LinearSpringDashpot;
  for (double e : {0.1, 0.5, 0.9, 1.0}) {
    CAPTURE(e);
    const auto pair = pair_with(e);
    const auto g = pair_contact<3>(1e-5, 0.0);
    const double v = 0.7;
    const double x =
        std::pow(v * g.r_eff * pair.young_eff * pair.young_eff * std::sqrt(g.m_eff), 0.4);
    const double beta = std::log(e) / pi; // 1/beta
    const double over = e < 1.0 ? std::exp(-std::atan(1.0 / beta) * beta) : 1.0;
    const double k_energy = std::pow(16.0 / 15.0, 0.8) * x;
    const double k_overlap = k_energy * over * over;
    const double k_time = std::pow(pi / normal::hertz_equivalent::hertz_time_coefficient, 2) * x *
                          (1.0 + beta * beta);
    M_::History<3> h;
    auto k_of = [&](Equivalence q) {
      return M_::force(g, pair, {.reference_velocity = v, .equivalence = q}, h).stiffness;
    };
    CHECK(k_of(Equivalence::energy) == grain::test::approx(k_energy).epsilon(1e-13));
    CHECK(k_of(Equivalence::overlap) == grain::test::approx(k_overlap).epsilon(1e-13));
    CHECK(k_of(Equivalence::time) == grain::test::approx(k_time).epsilon(1e-13));
    // the seed's rounded coefficients 1.053 and 1.198 agree to 0.15 %
    CHECK(k_energy / x == grain::test::approx(1.053).epsilon(1e-4));
    CHECK(k_time / (x * (1.0 + beta * beta)) == grain::test::approx(1.198).epsilon(1.5e-3));
    // damping from restitution: eta = sqrt(4 m* K / (1 + beta^2)) with beta = pi / ln e
    const auto r = M_::force(pair_contact<3>(1e-5, 0.3), pair, {.reference_velocity = v}, h);
    const double eta = e < 1.0 ? std::sqrt(4 * g.m_eff * k_energy / (1 + 1 / (beta * beta))) : 0.0;
    CHECK(r.damping == grain::test::approx(eta).epsilon(1e-12));
    CHECK(r.force == grain::test::approx(k_energy * 1e-5 + eta * 0.3).epsilon(1e-12));
    // stiffness_estimate: K at the reference velocity, whatever the impact speed passed
    CHECK(M_::stiffness_estimate(pair, {.reference_velocity = v}, g.r_eff, g.m_eff, 5.0) ==
          grain::test::approx(k_energy).epsilon(1e-13));
  }
  // given damping; no cohesion clamps only attraction
  const auto pair = pair_with(0.5);
  M_::History<3> h;
  const auto sep = pair_contact<3>(1e-6, -1.0);
  CHECK(M_::force(sep, pair, {.stiffness = 500, .damping = 0.02}, h).force ==
        grain::test::approx(500 * 1e-6 - 0.02).epsilon(1e-12));
  CHECK(M_::force(sep, pair, {.stiffness = 500, .damping = 0.02, .no_cohesion = true}, h).force ==
        0.0);
  const auto push = pair_contact<3>(1e-6, 1.0);
  CHECK(M_::force(push, pair, {.stiffness = 500, .damping = 0.02, .no_cohesion = true}, h).force ==
        grain::test::approx(500 * 1e-6 + 0.02).epsilon(1e-12));
  // a damping ratio: eta = 2 zeta sqrt(m* K) with the contact's own m*; `damping` wins over it
  const auto rz = M_::force(push, pair, {.stiffness = 500, .damping_ratio = 1.5}, h);
  CHECK(rz.damping == grain::test::approx(2 * 1.5 * std::sqrt(push.m_eff * 500)).epsilon(1e-14));
  CHECK(
      M_::force(push, pair, {.stiffness = 500, .damping = 0.02, .damping_ratio = 1.5}, h).damping ==
      0.02);
  CHECK(grain::test::has(
      error_of([] { M_::validate({.stiffness = 500, .damping_ratio = std::nan("")}); }),
      {"damping_ratio", "[0, inf)"}));
}

TEST_CASE("linear spring-dashpot per contact: impact velocity measured once, floor, reset") {
  using M_ = normal::LinearSpringDashpotPerContact;
  using normal::Equivalence;
  const auto pair = pair_with(0.5);
  const M_::Params prm{
      .reference_velocity = 2.0, .equivalence = Equivalence::time, .min_impact_velocity = 0.01};
  auto k_at = [&](double v) { return M_::stiffness(pair, prm, 0.5 * R, 0.5 * M, v); };
  M_::History<3> h;
  CHECK(h.impact_velocity == 0.0);
  // first contact step at 0.3 m/s: recorded and kept while the contact lasts
  auto r = M_::force(pair_contact<3>(1e-7, 0.3), pair, prm, h);
  CHECK(h.impact_velocity == 0.3);
  CHECK(r.stiffness == grain::test::approx(k_at(0.3)).epsilon(1e-14));
  r = M_::force(pair_contact<3>(5e-6, 0.05), pair, prm, h);
  CHECK(h.impact_velocity == 0.3);
  CHECK(r.stiffness == grain::test::approx(k_at(0.3)).epsilon(1e-14));
  r = M_::force(pair_contact<3>(2e-6, -0.2), pair, prm, h);
  CHECK(r.stiffness == grain::test::approx(k_at(0.3)).epsilon(1e-14));
  // K grows as v^(2/5)
  CHECK(k_at(3.0) / k_at(0.3) == grain::test::approx(std::pow(10.0, 0.4)).epsilon(1e-13));
  // a new contact (the simulation resets the history) measures again
  h = {};
  r = M_::force(pair_contact<3>(1e-7, 1.5), pair, prm, h);
  CHECK(r.stiffness == grain::test::approx(k_at(1.5)).epsilon(1e-14));
  // below the floor: the reference velocity, never a vanishing stiffness
  for (double slow : {0.0, 1e-6, 0.00999}) {
    h = {};
    r = M_::force(pair_contact<3>(1e-7, slow), pair, prm, h);
    CHECK(h.impact_velocity == 2.0);
    CHECK(r.stiffness == grain::test::approx(k_at(2.0)).epsilon(1e-14));
  }
  h = {};
  r = M_::force(pair_contact<3>(1e-7, -0.5), pair, prm, h); // separating at first touch
  CHECK(h.impact_velocity == 0.5);
  // a given stiffness needs no velocity
  h = {};
  r = M_::force(pair_contact<3>(1e-7, 0.5), pair, {.stiffness = 700.0}, h);
  CHECK(r.stiffness == 700.0);
  // critical time step: the stiffness at max(v, reference velocity)
  CHECK(M_::stiffness_estimate(pair, prm, 0.5 * R, 0.5 * M, 5.0) ==
        grain::test::approx(k_at(5.0)).epsilon(1e-14));
  CHECK(M_::stiffness_estimate(pair, prm, 0.5 * R, 0.5 * M, 0.1) ==
        grain::test::approx(k_at(2.0)).epsilon(1e-14));
}

TEST_CASE("Hertz damping policies: coefficients") {
  using namespace normal;
  // Tsuji: the exact map and the Norouzi fit against the table of alpha(e)
  struct Row {
    double e, exact, norouzi;
  };
  for (const Row& row :
       {Row{0.1, 1.3219, 1.3282}, Row{0.2, 1.0195, 1.0225}, Row{0.3, 0.8002, 0.8017},
        Row{0.5, 0.4818, 0.4822}, Row{0.7, 0.2522, 0.2523}, Row{0.9, 0.0749, 0.0750}}) {
    const auto pair = pair_with(row.e);
    // the table is printed to 4 decimals: half a unit of the last digit
    CHECK(std::abs(TsujiDamping::alpha(pair, {}) - row.exact) <= 5e-5);
    CHECK(std::abs(TsujiDamping::alpha(pair, {.map = TsujiMap::norouzi}) - row.norouzi) <= 5e-5);
    CHECK(TsujiDamping::alpha(pair, {.map = TsujiMap::norouzi, .alpha = 0.7}) == 0.7);
    CHECK(TsujiDamping::alpha(pair) == TsujiDamping::alpha(pair, {}));
  }
  const auto pair = pair_with(0.4);
  const double delta = 2e-5, rate = 0.3;
  const auto g = pair_contact<3>(delta, rate);
  const double kh = 4.0 / 3.0 * pair.young_eff * std::sqrt(g.r_eff);
  const double fe = kh * std::pow(delta, 1.5);
  {
    Hertz<>::History<3> h;
    const auto r = Hertz<>::force(g, pair, {.damping = {.alpha = 0.9}}, h);
    const double eta = 0.9 * std::sqrt(g.m_eff * kh) * std::pow(delta, 0.25);
    CHECK(r.damping == grain::test::approx(eta).epsilon(1e-13));
    CHECK(r.force == grain::test::approx(fe + eta * rate).epsilon(1e-13));
    CHECK(r.stiffness == grain::test::approx(1.5 * kh * std::sqrt(delta)).epsilon(1e-13));
  }
  {
    using H = Hertz<CriticalRatioDamping>;
    H::History<3> h;
    const auto r = H::force(g, pair, {.damping = {.ratio = 0.3}}, h);
    const double eta =
        0.3 * std::sqrt(8 * pair.young_eff * g.m_eff * std::sqrt(g.r_eff)) * std::pow(delta, 0.25);
    CHECK(r.damping == grain::test::approx(eta).epsilon(1e-13));
    // = 2 xi sqrt(m* k(delta)) with the tangent stiffness k; = Tsuji with alpha = sqrt(6) xi
    CHECK(r.damping ==
          grain::test::approx(2 * 0.3 * std::sqrt(g.m_eff * r.stiffness)).epsilon(1e-13));
    Hertz<>::History<3> ht;
    CHECK(Hertz<>::force(g, pair, {.damping = {.alpha = std::sqrt(6.0) * 0.3}}, ht).force ==
          grain::test::approx(r.force).epsilon(1e-13));
  }
  {
    using H = Hertz<KuwabaraKonoDamping>;
    H::History<3> h;
    const auto r = H::force(g, pair, {.damping = {.coefficient = 40.0}}, h);
    CHECK(r.damping == grain::test::approx(40.0 * std::sqrt(delta)).epsilon(1e-13));
    CHECK(r.force == grain::test::approx(fe + 40.0 * std::sqrt(delta) * rate).epsilon(1e-13));
  }
  {
    using H = Hertz<LeeHerrmannDamping>;
    H::History<3> h;
    const auto r = H::force(g, pair, {.damping = {.coefficient = 3000.0}}, h);
    CHECK(r.damping == grain::test::approx(3000.0 * g.m_eff).epsilon(1e-13));
    CHECK(r.force == grain::test::approx(fe + 3000.0 * g.m_eff * rate).epsilon(1e-13));
    // separating fast: attractive unless no_cohesion
    const auto gs = pair_contact<3>(1e-9, -1.0);
    CHECK(H::force(gs, pair, {.damping = {.coefficient = 3000.0}}, h).force < 0.0);
    CHECK(H::force(gs, pair, {.no_cohesion = true, .damping = {.coefficient = 3000.0}}, h).force ==
          0.0);
  }
}

TEST_CASE("Walton-Braun: loading, unloading, residual overlap, re-loading and cap") {
  using namespace normal;
  const auto pair = pair_with(0.5); // K_U = K_L / e^2 = 4 K_L
  const double kl = 1e3;
  auto f_at = [&](const WaltonBraun::Params& p, WaltonBraun::History<3>& h, double d, double v) {
    return WaltonBraun::force(pair_contact<3>(d, v), pair, p, h);
  };
  {
    const WaltonBraun::Params p{.stiffness = kl};
    WaltonBraun::History<3> h;
    CHECK(f_at(p, h, 1e-5, 0.1).force == grain::test::approx(1e-2));
    CHECK(f_at(p, h, 2e-5, 0.1).force == grain::test::approx(2e-2));
    CHECK(h.max_overlap == grain::test::approx(2e-5).epsilon(1e-12));
    CHECK(h.max_force == grain::test::approx(2e-2));
    // unloading: K_U (delta - delta_res), delta_res = 2e-5 (1 - 1/4) = 1.5e-5
    auto r = f_at(p, h, 1.8e-5, -0.1);
    CHECK(r.force == grain::test::approx(4e3 * (1.8e-5 - 1.5e-5)));
    CHECK(r.stiffness == kl); // the scale of the tangential spring stays K_L
    CHECK(WaltonBraun::residual_overlap(pair, p, kl, h) == grain::test::approx(1.5e-5));
    // re-loading before full unloading climbs the unloading line, whatever the rate sign
    r = f_at(p, h, 1.9e-5, 0.1);
    CHECK(r.force == grain::test::approx(4e3 * (1.9e-5 - 1.5e-5)));
    // past the previous maximum it continues on the loading line
    r = f_at(p, h, 2.5e-5, 0.1);
    CHECK(r.force == grain::test::approx(2.5e-2));
    CHECK(r.stiffness == kl);
    // below the residual overlap: no force, never attractive
    r = f_at(p, h, 1.0e-5, -5.0);
    CHECK(r.force == 0.0);
    CHECK(r.stiffness == 0.0);
    CHECK(r.elastic_energy == 0.0);
  }
  {
    // variable unloading: K_U = K_L + S F_max; the residual follows the actual maximum
    const double s = 2e5;
    const WaltonBraun::Params p{
        .stiffness = kl, .unloading = Unloading::variable, .unloading_slope = s};
    WaltonBraun::History<3> h;
    f_at(p, h, 3e-5, 0.1);
    const double fmax = kl * 3e-5, ku = kl + s * fmax;
    CHECK(WaltonBraun::unloading_stiffness(pair, p, kl, fmax) == grain::test::approx(ku));
    CHECK(WaltonBraun::residual_overlap(pair, p, kl, h) ==
          grain::test::approx(3e-5 * (1 - kl / ku)).epsilon(1e-12));
    CHECK(f_at(p, h, 2.9e-5, -0.1).force ==
          grain::test::approx(ku * (2.9e-5 - 3e-5 * (1 - kl / ku))).epsilon(1e-12));
  }
  {
    // cap: perfectly plastic at max_force, unloading from (delta_max, cap) with K_U
    const WaltonBraun::Params p{.stiffness = kl, .max_force = 1.5e-2};
    WaltonBraun::History<3> h;
    CHECK(f_at(p, h, 1e-5, 0.1).force == grain::test::approx(1e-2));
    auto r = f_at(p, h, 3e-5, 0.1);
    CHECK(r.force == 1.5e-2);
    CHECK(r.stiffness == kl); // the scale of the tangential spring stays K_L
    CHECK(h.max_force == 1.5e-2);
    r = f_at(p, h, 2.9e-5, -0.1);
    CHECK(r.force == grain::test::approx(1.5e-2 - 4e3 * 1e-6).epsilon(1e-12));
    CHECK(WaltonBraun::residual_overlap(pair, p, kl, h) ==
          grain::test::approx(3e-5 - 1.5e-2 / 4e3).epsilon(1e-12));
  }
  {
    // time formulation, variable unloading: K_L makes the force contact last the Hertz t_c
    namespace he = hertz_equivalent;
    const auto pv = pair_with(0.5);
    const double re = 0.5 * R, me = 0.5 * M, v = 0.8, s = 3e5;
    const WaltonBraun::Params p{
        .equivalence = Equivalence::time, .unloading = Unloading::variable, .unloading_slope = s};
    const double k = WaltonBraun::loading_stiffness(pv, p, re, me, v);
    const double e = 1.0 / std::sqrt(1.0 + s * v * std::sqrt(me / k));
    CHECK(0.5 * pi * std::sqrt(me / k) * (1 + e) ==
          grain::test::approx(he::hertz_contact_time(pv, re, me, v)).epsilon(1e-12));
    // constant unloading: closed form, e from the pair
    const WaltonBraun::Params pc{.equivalence = Equivalence::time};
    const double kc = WaltonBraun::loading_stiffness(pv, pc, re, me, v);
    CHECK(0.5 * pi * std::sqrt(me / kc) * 1.5 ==
          grain::test::approx(he::hertz_contact_time(pv, re, me, v)).epsilon(1e-12));
    // energy and overlap: the Hertz maximum overlap
    for (auto q : {Equivalence::energy, Equivalence::overlap}) {
      const double ke = WaltonBraun::loading_stiffness(pv, {.equivalence = q}, re, me, v);
      CHECK(v * std::sqrt(me / ke) ==
            grain::test::approx(he::hertz_max_overlap(pv, re, me, v)).epsilon(1e-12));
    }
    // critical time step: the unloading stiffness of an impact at v
    const double kl2 = 2e3;
    CHECK(WaltonBraun::stiffness_estimate(pv, {.stiffness = kl2}, re, me, v) ==
          grain::test::approx(4 * kl2));
    CHECK(WaltonBraun::stiffness_estimate(
              pv, {.stiffness = kl2, .unloading = Unloading::variable, .unloading_slope = s}, re,
              me, v) == grain::test::approx(kl2 + s * v * std::sqrt(me * kl2)));
  }
  {
    // per contact: the loading stiffness from the first-step impact velocity
    using W = WaltonBraunPerContact;
    W::History<3> h;
    const W::Params p{.reference_velocity = 1.0};
    const auto r = W::force(pair_contact<3>(1e-7, 0.25), pair, p, h);
    CHECK(h.impact_velocity == 0.25);
    CHECK(
        r.stiffness ==
        grain::test::approx(W::loading_stiffness(pair, p, 0.5 * R, 0.5 * M, 0.25)).epsilon(1e-14));
  }
}

TEST_CASE("normal models: bad parameters raise InputError naming model, value and range") {
  using namespace normal;
  auto has = [](const std::string& s, std::initializer_list<const char*> parts) {
    for (const char* p : parts)
      if (s.find(p) == std::string::npos) return false;
    return true;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  using LSD = LinearSpringDashpot;
  CHECK(error_of([] { LSD::validate({}); }).empty());
  CHECK(error_of([] { LSD::validate({.stiffness = -1.0}); }) ==
        "normal::LinearSpringDashpot: stiffness = -1 is invalid; valid range: [0, inf)");
  CHECK(has(error_of([] { LSD::validate({.reference_velocity = 0.0}); }),
            {"normal::LinearSpringDashpot", "reference_velocity = 0", "(0, inf)"}));
  CHECK(has(error_of([&] { LSD::validate({.damping = nan}); }),
            {"normal::LinearSpringDashpot", "damping = nan", "[0, inf) N s/m"}));
  CHECK(has(error_of([] { LSD::validate({.equivalence = static_cast<Equivalence>(7)}); }),
            {"normal::LinearSpringDashpot", "equivalence = 7", "Equivalence::energy"}));
  CHECK(has(error_of([] { LinearSpringDashpotPerContact::validate({.min_impact_velocity = 0.0}); }),
            {"normal::LinearSpringDashpotPerContact", "min_impact_velocity = 0", "(0, inf)"}));

  CHECK(error_of([] { Hertz<>::validate({}); }).empty());
  CHECK(has(error_of([&] { Hertz<>::validate({.damping = {.alpha = inf}}); }),
            {"normal::Hertz<normal::TsujiDamping>", "damping.alpha = inf", "[0, inf)"}));
  CHECK(has(error_of([] { Hertz<>::validate({.damping = {.map = static_cast<TsujiMap>(5)}}); }),
            {"normal::Hertz<normal::TsujiDamping>", "damping.map = 5", "TsujiMap::exact"}));
  // coefficients without a default must be given
  CHECK(error_of([] { Hertz<CriticalRatioDamping>::validate({}); }) ==
        "normal::Hertz<normal::CriticalRatioDamping>: damping.ratio = -1 is invalid; valid "
        "range: [0, inf) (the critical damping ratio must be given)");
  CHECK(has(error_of([] { Hertz<KuwabaraKonoDamping>::validate({}); }),
            {"normal::Hertz<normal::KuwabaraKonoDamping>", "damping.coefficient = -1",
             "[0, inf) N s/m^1.5", "must be given"}));
  CHECK(has(
      error_of([] { Hertz<LeeHerrmannDamping>::validate({.damping = {.coefficient = -3}}); }),
      {"normal::Hertz<normal::LeeHerrmannDamping>", "damping.coefficient = -3", "[0, inf) 1/s"}));
  CHECK(error_of([] {
          Hertz<KuwabaraKonoDamping>::validate({.damping = {.coefficient = 0}});
        }).empty());

  CHECK(error_of([] { WaltonBraun::validate({}); }).empty());
  CHECK(has(error_of([] { WaltonBraun::validate({.stiffness = -5.0}); }),
            {"normal::WaltonBraun", "stiffness = -5", "[0, inf)"}));
  CHECK(error_of([] { WaltonBraun::validate({.unloading = Unloading::variable}); }) ==
        "normal::WaltonBraun: unloading_slope = 0 is invalid; valid range: (0, inf) 1/m "
        "(required by Unloading::variable)");
  CHECK(has(error_of([] { WaltonBraun::validate({.max_force = -1.0}); }),
            {"normal::WaltonBraun", "max_force = -1", "[0, inf)"}));
  CHECK(has(error_of([] { WaltonBraun::validate({.unloading = static_cast<Unloading>(3)}); }),
            {"normal::WaltonBraun", "unloading = 3",
             "Unloading::constant, Unloading::variable or Unloading::given"}));
  CHECK(has(error_of([] { WaltonBraunPerContact::validate({.reference_velocity = -1.0}); }),
            {"normal::WaltonBraunPerContact", "reference_velocity = -1", "(0, inf)"}));

  // a simulation checks the coefficients when it is built
  using Sim = Simulation<Sphere, search::AllPairs, Interaction<Hertz<KuwabaraKonoDamping>>>;
  CHECK(has(error_of([] { Sim sim; }),
            {"normal::Hertz<normal::KuwabaraKonoDamping>", "damping.coefficient"}));
  CHECK(error_of([] {
          Sim sim({.contact = {.normal = {.damping = {.coefficient = 1.0}}}});
        }).empty());
}
