// Contact parameters per pair of materials (the colour-pair table of the third seed's GRANULAR
// command, for every contact model): a pair without an entry uses SimulationParams::contact (the
// default pair); a pair with one uses its own spring, damping (through the pair's restitution),
// tangential-to-normal stiffness ratio, friction; particle-wall pairs too.
//
// Linear spring-dashpot impacts have closed forms: duration pi / omega_d with
// omega_d = omega_0 sqrt(1 - zeta^2), omega_0 = sqrt(k/m*), and restitution e (the damping is
// chosen from e). Tolerance 1e-3 (time step t_c / 2000).
#include "../approx.hpp"
#include "../errors.hpp"
#include <cmath>
#include <doctest/doctest.h>
#include <grain/grain.hpp>
#include <numbers>

using namespace grain;
using grain::test::approx;

namespace {

constexpr double pi = std::numbers::pi;
using Contact = Interaction<normal::LinearSpringDashpot, tangent::SpringDashpotSlider>;
using Sim = Simulation<Sphere, search::CellList, Contact>;

const Material red{.name = "red",
                   .density = 2500,
                   .young = 1e8,
                   .poisson = 0.3,
                   .restitution = 0.9,
                   .friction = 0.5};
const Material blue{.name = "blue",
                    .density = 2500,
                    .young = 1e8,
                    .poisson = 0.3,
                    .restitution = 0.9,
                    .friction = 0.5};
const Material steel{.name = "steel",
                     .density = 7800,
                     .young = 2e11,
                     .poisson = 0.3,
                     .restitution = 0.9,
                     .friction = 0.5};

/// The set-up: default pair k = 1e4 N/m; red-blue k = 4e4 N/m, k_t/k_n = 0.5, no tangential
/// damping, e = 0.6, friction 10; red-steel k = 9e4 N/m.
Sim make(double dt) {
  Sim::Params prm;
  prm.time_step = dt;
  prm.contact.normal.stiffness = 1e4;
  Sim sim(prm);
  const auto r = sim.add_material(red), b = sim.add_material(blue), s = sim.add_material(steel);
  Contact::Params rb = prm.contact;
  rb.normal.stiffness = 4e4;
  rb.tangent.stiffness_ratio = 0.5;
  rb.tangent.damping = 0.0;
  sim.set_pair_parameters(r, b, rb);
  sim.set_pair(r, b, {.restitution = 0.6, .friction = 10.0, .friction_static = 10.0});
  Contact::Params rs = prm.contact;
  rs.normal.stiffness = 9e4;
  sim.set_pair_parameters(s, r, rs); // either order
  return sim;
}

struct Impact {
  double duration = 0.0, restitution = 0.0;
};

/// Head-on impact of a red sphere at 0.1 m/s on a sphere of material `other` at rest, or on a
/// plane of it.
Impact impact(std::uint32_t other, bool wall, double k, double e) {
  const double R = 1e-3, m = 2500 * 4.0 / 3.0 * pi * R * R * R;
  const double mo = (other == 2 ? 7800.0 : 2500.0) * 4.0 / 3.0 * pi * R * R * R;
  const double ms = wall ? m : m * mo / (m + mo);
  const double zeta = -std::log(e) / std::sqrt(std::log(e) * std::log(e) + pi * pi);
  const double tc = pi / (std::sqrt(k / ms) * std::sqrt(1 - zeta * zeta));
  Sim sim = make(tc / 2000);
  const double v0 = 0.1;
  sim.add_particle(
      {.position = Vec3(0, 0, 0), .radius = R, .material = 0, .velocity = Vec3(v0, 0, 0)});
  if (wall)
    sim.add_wall(walls::Plane{Vec3(R * (1 + 1e-12), 0, 0), -Vec3::UnitX()}, {.material = other});
  else
    sim.add_particle({.position = Vec3(2 * R * (1 + 1e-12), 0, 0), .radius = R, .material = other});
  Impact out;
  long steps = 0;
  bool touching = true;
  while (touching && steps < 100000) {
    sim.step();
    ++steps;
    touching = sim.contact_counts().first + sim.contact_counts().second > 0;
  }
  out.duration = steps * sim.time_step();
  const auto& p = sim.particles();
  const double v_rel = wall ? -p.velocity[sim.index_of(0)].x()
                            : p.velocity[sim.index_of(1)].x() - p.velocity[sim.index_of(0)].x();
  out.restitution = v_rel / v0;
  return out;
}

} // namespace

TEST_CASE("pair parameters: each pair of materials impacts with its own spring and damping") {
  SUBCASE("default pair: red-red uses SimulationParams::contact") {
    const auto i = impact(0, false, 1e4, 0.9);
    const double R = 1e-3, m = 2500 * 4.0 / 3.0 * pi * R * R * R, ms = m / 2;
    const double zeta = -std::log(0.9) / std::sqrt(std::log(0.9) * std::log(0.9) + pi * pi);
    CHECK(i.duration ==
          approx(pi / (std::sqrt(1e4 / ms) * std::sqrt(1 - zeta * zeta))).epsilon(1e-3));
    CHECK(i.restitution == approx(0.9).epsilon(1e-3));
  }
  SUBCASE("red-blue: its own spring and restitution") {
    const auto i = impact(1, false, 4e4, 0.6);
    const double R = 1e-3, m = 2500 * 4.0 / 3.0 * pi * R * R * R, ms = m / 2;
    const double zeta = -std::log(0.6) / std::sqrt(std::log(0.6) * std::log(0.6) + pi * pi);
    CHECK(i.duration ==
          approx(pi / (std::sqrt(4e4 / ms) * std::sqrt(1 - zeta * zeta))).epsilon(1e-3));
    CHECK(i.restitution == approx(0.6).epsilon(1e-3));
  }
  SUBCASE("red on a steel wall: the pair's spring") {
    const auto i = impact(2, true, 9e4, 0.9);
    const double R = 1e-3, m = 2500 * 4.0 / 3.0 * pi * R * R * R;
    const double zeta = -std::log(0.9) / std::sqrt(std::log(0.9) * std::log(0.9) + pi * pi);
    CHECK(i.duration ==
          approx(pi / (std::sqrt(9e4 / m) * std::sqrt(1 - zeta * zeta))).epsilon(1e-3));
    CHECK(i.restitution == approx(0.9).epsilon(1e-3));
  }
}

TEST_CASE("pair parameters: the tangential spring of a pair follows its k_t/k_n") {
  // an oblique red-blue impact that sticks (friction 10, no tangential damping): F_t = -k_t xi
  // with k_t = 0.5 x 4e4 N/m at every step of the contact
  Sim sim = make(2e-7); // the contact lasts about 180 steps
  const double R = 1e-3;
  sim.add_particle(
      {.position = Vec3(0, 0, 0), .radius = R, .material = 0, .velocity = Vec3(0.1, 0.02, 0)});
  sim.add_particle({.position = Vec3(2 * R * (1 + 1e-12), 0, 0), .radius = R, .material = 1});
  int seen = 0;
  for (int k = 0; k < 400; ++k) {
    sim.step();
    sim.for_each_contact([&](const Sim::ContactViewType& c) {
      const Vec3 xi = load<3>(c.data.tangent.spring);
      // sticking (the last steps, as the normal force vanishes, may slide)
      if (xi.norm() == 0.0 || c.data.tangent.sliding) return;
      ++seen;
      CHECK(c.result.tangent.force.norm() / xi.norm() == approx(2e4).epsilon(1e-9));
    });
  }
  CHECK(seen > 100);
  // and the critical step sees the stiffest pair: 2 sqrt(m/k) of a red sphere on steel
  Sim lone = make(0.0);
  lone.add_particle({.position = Vec3::Zero(), .radius = R, .material = 0});
  lone.add_wall(walls::Plane{Vec3(0, 0, -2 * R), Vec3::UnitZ()}, {.material = 2});
  const double m = 2500 * 4.0 / 3.0 * pi * R * R * R;
  CHECK(lone.contact_time_step() == approx(2 * std::sqrt(m / 9e4)).epsilon(1e-12));
  CHECK(lone.contact_params(2, 0).normal.stiffness == 9e4);
  CHECK(lone.contact_params(1, 1).normal.stiffness == 1e4);
}

TEST_CASE("pair parameters: bad input") {
  using grain::test::error_of, grain::test::has;
  Sim sim = make(1e-6);
  Contact::Params bad;
  bad.normal.stiffness = -5.0;
  const auto e = error_of([&] { sim.set_pair_parameters(0, 1, bad); });
  CHECK(has(e, "materials 'red' and 'blue'"));
  CHECK(has(e, "stiffness"));
  CHECK(has(error_of([&] { sim.set_pair_parameters(0, 7, Contact::Params{}); }), "7"));
  // a restitution above 1 would make the dashpot add energy
  const auto r = error_of([&] { sim.set_pair(0, 1, {.restitution = 1.5}); });
  CHECK(has(r, "Simulation::set_pair: restitution = 1.5 is invalid; valid range: (0, 1]"));
  CHECK(has(error_of([&] { sim.set_pair(0, 1, {.restitution = 0.0}); }), "restitution = 0"));
  CHECK(has(error_of([&] { sim.set_pair(0, 1, {.friction = std::nan("")}); }), "friction = nan"));
  CHECK(error_of([&] { sim.set_pair(0, 1, {.restitution = 1.0, .friction = 0.3}); }).empty());
}
