// Contact models in isolation and the composition of per-contact history.
#include "../approx.hpp"
#include <cmath>
#include <doctest/doctest.h>
#include <grain/grain.hpp>
#include <numbers>
#include <type_traits>

using namespace grain;

// ---- history composition costs nothing for models without history
using HertzOnly = Interaction<normal::Hertz<>>;
using LinearOnly = Interaction<normal::LinearSpringDashpot>;
using HertzSDS = Interaction<normal::Hertz<>, tangent::SpringDashpotSlider>;
static_assert(std::is_empty_v<HertzOnly::History<2>> && std::is_empty_v<HertzOnly::History<3>>);
static_assert(HertzOnly::stateless<3> && LinearOnly::stateless<2>);
static_assert(sizeof(HertzSDS::History<3>) == sizeof(tangent::SpringDashpotSlider::History<3>));
static_assert(sizeof(HertzSDS::History<2>) == sizeof(tangent::SpringDashpotSlider::History<2>));
static_assert(std::is_trivially_copyable_v<HertzSDS::History<3>>);
static_assert(std::is_trivially_copyable_v<HertzSDS::History<2>>);
static_assert(!HertzOnly::has_torque && HertzSDS::has_torque);
static_assert(NormalModel<normal::Hertz<>> && NormalModel<normal::LinearSpringDashpot>);
static_assert(TangentModel<tangent::SpringDashpotSlider> &&
              !NormalModel<tangent::SpringDashpotSlider>);
static_assert(!TangentModel<normal::Hertz<>>);

namespace {
PairProperties pair_of(double young, double poisson, double e, double mu) {
  const Material m{
      .density = 1000, .young = young, .poisson = poisson, .restitution = e, .friction = mu};
  return PairProperties::mix(m, m);
}
ContactGeometry<3> head_on(double overlap, double rate, double r = 1e-3, double m = 1e-5) {
  ContactGeometry<3> g;
  const double dist = 2 * r - overlap;
  pair_geometry<3>(g, Vec3::Zero(), Vec3::UnitX(), dist, r, r, m, m, Vec3(rate, 0, 0), Vec3::Zero(),
                   Vec3::Zero(), Vec3::Zero());
  return g;
}
} // namespace

TEST_CASE("Hertz: force, stiffness, energy and damping") {
  const auto pair = pair_of(1e7, 0.3, 0.5, 0.5);
  normal::Hertz<>::History<3> h;
  // zero force at zero overlap and zero rate
  auto r0 = normal::Hertz<>::force(head_on(0.0, 0.0), pair, {}, h);
  CHECK(r0.force == 0.0);
  const double delta = 1e-5;
  auto g = head_on(delta, 0.0);
  auto r = normal::Hertz<>::force(g, pair, {}, h);
  const double kh = 4.0 / 3.0 * pair.young_eff * std::sqrt(g.r_eff);
  CHECK(r.force == grain::test::approx(kh * std::pow(delta, 1.5)).epsilon(1e-13));
  CHECK(r.stiffness == grain::test::approx(2.0 * pair.young_eff * std::sqrt(g.r_eff * delta)));
  CHECK(r.elastic_energy == grain::test::approx(0.4 * kh * std::pow(delta, 2.5)));
  // Tsuji damping with alpha = sqrt(5) |ln e| / sqrt(ln^2 e + pi^2) equals LIGGGHTS' form
  // gamma_n = -2 sqrt(5/6) beta sqrt(S_n m*), S_n = 2 E* sqrt(R* delta)
  auto gv = head_on(delta, 0.1);
  auto rv = normal::Hertz<>::force(gv, pair, {}, h);
  const double beta =
      std::log(0.5) / std::sqrt(std::pow(std::log(0.5), 2) + std::pow(std::numbers::pi, 2));
  const double sn = 2.0 * pair.young_eff * std::sqrt(g.r_eff * delta);
  const double gn = -2.0 * std::sqrt(5.0 / 6.0) * beta * std::sqrt(sn * gv.m_eff);
  CHECK(rv.damping == grain::test::approx(gn).epsilon(1e-12));
  CHECK(rv.force - r.force == grain::test::approx(gn * 0.1).epsilon(1e-12));
  // no cohesion: separating fast, the force would be attractive
  auto gs = head_on(1e-9, -1.0);
  CHECK(normal::Hertz<>::force(gs, pair, {}, h).force < 0.0);
  CHECK(normal::Hertz<>::force(gs, pair, {.no_cohesion = true}, h).force == 0.0);
}

TEST_CASE("linear spring-dashpot: given and Hertz-equivalent stiffness") {
  const auto pair = pair_of(1e7, 0.3, 0.5, 0.5);
  normal::LinearSpringDashpot::History<3> h;
  auto g = head_on(1e-5, 0.2);
  auto r = normal::LinearSpringDashpot::force(g, pair, {.stiffness = 500.0}, h);
  const double eta = 2.0 * pair.damping_ratio() * std::sqrt(g.m_eff * 500.0);
  CHECK(r.force == grain::test::approx(500.0 * 1e-5 + eta * 0.2));
  CHECK(r.elastic_energy == grain::test::approx(0.5 * 500.0 * 1e-10));
  CHECK(normal::LinearSpringDashpot::force(head_on(0, 0), pair, {.stiffness = 500.0}, h).force ==
        0.0);
  // Hertz equivalence reproduces the bench table (pack2d disk-disk: kn = 591.4824333 N/m,
  // gn = 0.01038376737 N s/m for m* = 9.817477042e-7 kg, R* = 2.5e-4 m, Y* = 5.494505495e6 Pa)
  ContactGeometry<2> d;
  const double m = 1.963495408e-6;
  pair_geometry<2>(d, Vec2::Zero(), Vec2::UnitX(), 1e-3 - 1e-6, 5e-4, 5e-4, m, m, Vec2::Zero(),
                   Vec2::Zero(), 0.0, 0.0);
  normal::LinearSpringDashpot::History<2> h2;
  auto rd = normal::LinearSpringDashpot::force(d, pair, {.reference_velocity = 1.0}, h2);
  CHECK(rd.stiffness == grain::test::approx(591.4824333).epsilon(1e-9));
  CHECK(rd.damping == grain::test::approx(0.01038376737).epsilon(1e-9));
}

TEST_CASE("spring-dashpot-slider: stick, Coulomb truncation, rotation, reverse") {
  const auto pair = pair_of(1e7, 0.3, 1.0, 0.5);
  using T = tangent::SpringDashpotSlider;
  T::History<3> h;
  NormalResult n{.force = 1.0, .stiffness = 1000.0, .damping = 0.0};
  ContactGeometry<3> g = head_on(1e-5, 0.0);
  g.tangential_velocity = g.slip_velocity = Vec3(0, 1e-3, 0);
  const double dt = 1e-3;
  const double kt = (1 - 0.3) / (1 - 0.15) * 1000.0; // Mindlin ratio of the normal stiffness
  auto r = T::force(g, pair, n, {}, h, dt);
  CHECK(!r.sliding);
  CHECK(r.force.isApprox(Vec3(0, -kt * 1e-6, 0)));
  // many steps: the force saturates at mu Fn and the spring is truncated there
  for (int k = 0; k < 2000; ++k)
    r = T::force(g, pair, n, {}, h, dt);
  CHECK(r.sliding);
  CHECK(r.force.norm() == grain::test::approx(0.5).epsilon(1e-12));
  CHECK(load<3>(h.spring).norm() == grain::test::approx(0.5 / kt).epsilon(1e-12));
  CHECK(r.force.dot(g.tangential_velocity) < 0.0);
  // the contact turns by 90 degrees about z: the spring follows into the new tangent plane
  // with its length kept
  const double len = load<3>(h.spring).norm();
  g.normal = Vec3(std::cos(0.3), std::sin(0.3), 0.0);
  g.tangential_velocity = g.slip_velocity = Vec3::Zero();
  r = T::force(g, pair, n, {}, h, dt);
  CHECK(std::abs(load<3>(h.spring).dot(g.normal)) < 1e-15);
  CHECK(load<3>(h.spring).norm() == grain::test::approx(len).epsilon(1e-12));
  // swapping the partners mirrors the spring
  auto before = load<3>(h.spring);
  HertzSDS::History<3> full;
  full.tangent.spring = h.spring;
  HertzSDS::reverse<3>(full);
  CHECK(load<3>(full.tangent.spring).isApprox(-before));
}

TEST_CASE("interaction: action equals reaction and torques from the contact point") {
  const auto pair = pair_of(1e7, 0.3, 0.5, 0.5);
  HertzSDS::History<3> h;
  ContactGeometry<3> g;
  pair_geometry<3>(g, Vec3::Zero(), Vec3::UnitX(), 1.99e-3, 1e-3, 1e-3, 1e-5, 1e-5,
                   Vec3(0.1, 0.05, 0), Vec3::Zero(), Vec3(0, 0, 3), Vec3(1, 0, 0));
  auto r = HertzSDS::evaluate<3>(g, pair, {}, h, 1e-6);
  // force on i is repulsive along -n and has a tangential part
  CHECK(r.force.x() < 0.0);
  CHECK(std::abs(r.force.y()) > 0.0);
  // torques: arm x F_t for i and arm_j x (-F_t) for j; both arms are along the normal, so the
  // torques are equal for equal radii and balance the moment of the pair force about any point
  const Vec3 ft = r.tangent.force;
  CHECK(r.torque_i.isApprox(g.arm_i.cross(ft)));
  CHECK(r.torque_j.isApprox(g.arm_j.cross(-ft)));
  // angular momentum balance about the origin: x_i x F_i + x_j x F_j + T_i + T_j = 0
  const Vec3 xi = Vec3::Zero(), xj(1.99e-3, 0, 0);
  const Vec3 total = xi.cross(r.force) + xj.cross(-r.force) + r.torque_i + r.torque_j;
  CHECK(total.norm() < 1e-12 * r.force.norm() * 1e-3);
}

namespace {
/// Evaluates a sliding-and-sticking sequence of contacts with `p` and with Contact::resolve(p):
/// the resolved parameters must give the same bits.
template <class Contact>
void check_resolved_same_bits(const typename Contact::Params& p, const PairProperties& pair) {
  const auto q = Contact::resolve(p, pair);
  typename Contact::template History<3> h1{}, h2{};
  for (int k = 0; k < 40; ++k) {
    ContactGeometry<3> g;
    const double overlap = 1e-6 * (1 + k % 7);
    const Vec3 n = Vec3(1.0, 0.02 * k, -0.01 * k).normalized();
    pair_geometry<3>(g, Vec3::Zero(), n, 2e-3 - overlap, 1e-3, 1e-3, 1e-5, 2e-5,
                     Vec3(0.1 - 0.01 * k, 0.05, 0.002 * k), Vec3::Zero(), Vec3(0, 0, 3 - 0.3 * k),
                     Vec3(1, 0, 0));
    const auto r1 = Contact::template evaluate<3>(g, pair, p, h1, 1e-6);
    const auto r2 = Contact::template evaluate<3>(g, pair, q, h2, 1e-6);
    REQUIRE(r1.force == r2.force);
    REQUIRE(r1.torque_i == r2.torque_i);
    REQUIRE(r1.torque_j == r2.torque_j);
    REQUIRE(r1.normal.damping == r2.normal.damping);
  }
}
} // namespace

TEST_CASE("interaction: resolved pair constants give the same bits, worked out once") {
  const auto pair = pair_of(1e7, 0.3, 0.5, 0.5);
  // Tsuji alpha from the restitution and the Mindlin stiffness ratio are filled in
  const auto q = HertzSDS::resolve({}, pair);
  CHECK(q.normal.damping.alpha ==
        grain::test::approx(normal::TsujiDamping::exact_alpha(std::log(0.5))).epsilon(1e-15));
  CHECK(q.tangent.stiffness_ratio == grain::test::approx((1 - 0.3) / (1 - 0.15)).epsilon(1e-15));
  // given values are kept
  HertzSDS::Params given;
  given.normal.damping.alpha = 0.7;
  given.tangent.stiffness = 123.0;
  const auto qg = HertzSDS::resolve(given, pair);
  CHECK(qg.normal.damping.alpha == 0.7);
  CHECK(qg.tangent.stiffness_ratio == 0.0);
  given.tangent.stiffness = 0.0;
  given.tangent.stiffness_ratio = 0.5;
  CHECK(HertzSDS::resolve(given, pair).tangent.stiffness_ratio == 0.5);
  HertzSDS::Params norouzi;
  norouzi.normal.damping.map = normal::TsujiMap::norouzi;
  CHECK(HertzSDS::resolve(norouzi, pair).normal.damping.alpha ==
        normal::TsujiDamping::norouzi_alpha(std::log(0.5)));
  // same bits with and without resolving, for several models and restitutions
  for (double e : {0.1, 0.5, 0.9}) {
    const auto pe = pair_of(1e7, 0.25, e, 0.4);
    check_resolved_same_bits<HertzSDS>({}, pe);
    check_resolved_same_bits<HertzSDS>(norouzi, pe);
    check_resolved_same_bits<Interaction<normal::Hertz<>, tangent::Spring>>({}, pe);
    check_resolved_same_bits<Interaction<normal::Hertz<>, tangent::SpringSlider>>({}, pe);
    check_resolved_same_bits<
        Interaction<normal::LinearSpringDashpot, tangent::SpringDashpotSlider>>({}, pe);
    check_resolved_same_bits<presets::HertzMindlin>({}, pe);
  }
}

// presets are ordinary interactions; their histories hold only what their models need
static_assert(sizeof(presets::HertzMindlin::History<3>) == sizeof(tangent::Mindlin::History<3>));
static_assert(presets::LinearCoulomb::stateless<3> == false);
static_assert(presets::HertzMindlinRolling::has_torque);
static_assert(sizeof(presets::HertzMindlinEPSD::History<3>) <=
              sizeof(tangent::Mindlin::History<3>) + sizeof(rolling::EPSD::History<3>));
