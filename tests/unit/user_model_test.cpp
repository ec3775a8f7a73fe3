// Contact models written in a user's program, outside the library, as docs/adding_a_model.md
// teaches (the page shows this code): a linear spring without damping and a constant conductance,
// their parameters checked with the public checks of grain/core/error.hpp, plugged into
// Interaction and Simulation. The spring's impacts against the closed forms: contact duration
// pi sqrt(m*/K) and restitution 1, for a sphere shot onto a plane (m* = m) and two spheres shot at
// each other (m* = m/2), within 1e-5 relative at 1000 steps per contact; the conductance against
// forward Euler's recursion. And the public checks themselves: their messages, equal to those of
// the library's own.
#include "../approx.hpp"
#include "../errors.hpp"
#include <doctest/doctest.h>
#include <grain/grain.hpp>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>

// ----------------------------------------------------------------- the model, as on the page

namespace my_models {

/// Linear spring normal force without damping (a perfectly elastic contact, restitution 1).
///
///   F_n = K delta        [N], repulsive positive
///
/// K [N/m] is `stiffness`. Elastic energy K delta^2 / 2 [J]; contact duration pi sqrt(m*/K) [s].
/// History: none.
struct LinearSpring {
  static constexpr grain::Slot slot = grain::Slot::normal;
  static constexpr const char* name = "linear spring";

  struct Params {
    double stiffness = 1e3; ///< K [N/m], > 0
  };
  template <int D>
  struct History {}; // no per-contact state: costs zero bytes

  static void validate(const Params& p) {
    grain::require_positive("my_models::LinearSpring", "stiffness", p.stiffness);
  }

  template <int D>
  GRAIN_INLINE static grain::NormalResult force(const grain::ContactGeometry<D>& g,
                                                const grain::PairProperties&, const Params& p,
                                                History<D>&) {
    return {.force = p.stiffness * g.overlap,
            .stiffness = p.stiffness,
            .damping = 0.0,
            .elastic_energy = 0.5 * p.stiffness * g.overlap * g.overlap};
  }

  /// The stiffness is the same at every impact velocity.
  static double stiffness_estimate(const grain::PairProperties&, const Params& p, double /*r_eff*/,
                                   double /*m_eff*/, double /*v*/) {
    return p.stiffness;
  }
};

} // namespace my_models

namespace my_models {

/// A constant conductance H [W/K] per touching contact.
struct ConstantConductance {
  static constexpr grain::Slot slot = grain::Slot::conduction;
  static constexpr const char* name = "constant conductance";
  static constexpr bool thermal = true;
  static constexpr bool uses_distance = false; // HeatContext::distance is not read

  struct Params {
    double conductance = 1e-3; ///< H [W/K], > 0
  };
  template <int D>
  struct History {};

  static void validate(const Params& p) {
    grain::require_positive("my_models::ConstantConductance", "conductance", p.conductance);
  }

  template <int D>
  static double conductance(const grain::ContactGeometry<D>&, const grain::PairProperties&,
                            const grain::HeatContext& c, const Params& p, History<D>&) {
    return c.touching ? p.conductance : 0.0;
  }
};

} // namespace my_models

using Contact = grain::Interaction<my_models::LinearSpring>;
using Sim = grain::Simulation<grain::Sphere, grain::search::AllPairs, Contact>;

static_assert(grain::NormalModel<my_models::LinearSpring>);
static_assert(Contact::stateless<3>); // no history array is allocated
static_assert(grain::ConductionModel<my_models::ConstantConductance>);

// ----------------------------------------------------------------- the checks

namespace {

constexpr double pi = std::numbers::pi;
constexpr double radius = 1e-3;   // [m]
constexpr double density = 2500;  // [kg/m^3]
constexpr double stiffness = 500; // K [N/m]
constexpr double speed = 0.1;     // relative approach speed [m/s]
// relative, at 1000 steps per contact (velocity Verlet lengthens the contact by (w dt)^2/24 = 4e-7)
constexpr double tolerance = 1e-5;

/// What one head-on impact gave.
struct Impact {
  double duration = 0.0;    ///< from first contact to the overlap returning to zero [s]
  double restitution = 0.0; ///< separation speed / approach speed
};

/// A sphere shot at `speed` onto a plane (`wall`), or two spheres approaching each other at
/// `speed`, from the instant of first contact (overlap 1e-12 R), gravity off, the default
/// integrator (velocity Verlet) at the time step dt, stepped until the overlap returns to zero.
Impact impact(bool wall, double dt) {
  using grain::Vec3;
  Sim::Params params;
  params.contact.normal.stiffness = stiffness;
  params.time_step = dt;
  Sim sim(params);
  const auto glass = sim.add_material({.name = "glass", .density = density, .young = 1e7});
  const double touch = 1e-12 * radius;
  if (wall) {
    sim.add_wall(grain::walls::Plane{Vec3::Zero(), Vec3::UnitZ()}, {.material = glass});
    sim.add_particle({.position = Vec3(0, 0, radius - touch),
                      .radius = radius,
                      .material = glass,
                      .velocity = Vec3(0, 0, -speed)});
  } else {
    sim.add_particle({.position = Vec3::Zero(),
                      .radius = radius,
                      .material = glass,
                      .velocity = Vec3(0, 0, 0.5 * speed)});
    sim.add_particle({.position = Vec3(0, 0, 2 * radius - touch),
                      .radius = radius,
                      .material = glass,
                      .velocity = Vec3(0, 0, -0.5 * speed)});
  }
  const auto& p = sim.particles();
  auto overlap = [&] {
    return wall ? radius - p.position[0].z() : 2 * radius - (p.position[1] - p.position[0]).norm();
  };
  auto approach = [&] { return wall ? -p.velocity[0].z() : (p.velocity[0] - p.velocity[1]).z(); };
  sim.initialize();
  Impact r;
  double before = overlap();
  for (long k = 0; k < 100000; ++k) {
    sim.step();
    const double d = overlap();
    if (d <= 0.0) { // the overlap crossed zero inside this step: interpolate the instant
      r.duration = sim.time() - dt * (-d) / (before - d);
      r.restitution = -approach() / speed;
      break;
    }
    before = d;
  }
  REQUIRE(r.duration > 0.0); // the pair separated
  return r;
}

double sphere_mass() { return 4.0 / 3.0 * pi * radius * radius * radius * density; }

} // namespace

TEST_CASE("user model: force, stiffness and energy of one contact") {
  grain::ContactGeometry<3> g;
  g.overlap = 1e-5;
  my_models::LinearSpring::History<3> h;
  const auto r =
      my_models::LinearSpring::force(g, grain::PairProperties{}, {.stiffness = 100.0}, h);
  CHECK(r.force == grain::test::approx(100.0 * 1e-5));
  CHECK(r.stiffness == 100.0);
  CHECK(r.damping == 0.0);
  CHECK(r.elastic_energy == grain::test::approx(0.5 * 100.0 * 1e-10));
  CHECK(grain::io::describe_contact<Contact>() == "normal linear spring"); // `name`, for output
}

TEST_CASE("user model: a sphere onto a plane lasts pi sqrt(m/K) and rebounds with e = 1") {
  const double m_star = sphere_mass(); // a plane has infinite mass
  const double t_c = pi * std::sqrt(m_star / stiffness);
  const Impact r = impact(true, t_c / 1000);
  MESSAGE("relative errors: duration " << std::abs(r.duration / t_c - 1) << ", restitution "
                                       << std::abs(r.restitution - 1));
  CHECK(r.duration == grain::test::approx(t_c).epsilon(tolerance));
  CHECK(r.restitution == grain::test::approx(1.0).epsilon(tolerance));
}

TEST_CASE("user model: two spheres last pi sqrt(m*/K), m* = m/2, and rebound with e = 1") {
  const double m_star = 0.5 * sphere_mass();
  const double t_c = pi * std::sqrt(m_star / stiffness);
  const Impact r = impact(false, t_c / 1000);
  MESSAGE("relative errors: duration " << std::abs(r.duration / t_c - 1) << ", restitution "
                                       << std::abs(r.restitution - 1));
  CHECK(r.duration == grain::test::approx(t_c).epsilon(tolerance));
  CHECK(r.restitution == grain::test::approx(1.0).epsilon(tolerance));
}

TEST_CASE("user model: a constant conductance relaxes two spheres as forward Euler predicts") {
  // C_1 = C_2 = m c; forward Euler: dT_n = dT_0 (1 - dt H (1/C_1 + 1/C_2))^n, to round-off
  using Heat = grain::Interaction<my_models::LinearSpring, grain::tangent::None,
                                  grain::rolling::None, my_models::ConstantConductance>;
  using HeatSim = grain::Simulation<grain::Sphere, grain::search::AllPairs, Heat>;
  using grain::Vec3;
  HeatSim::Params params;
  params.analysis = grain::Analysis::thermal;
  params.time_step = 1.0;                       // [s]
  params.contact.conduction.conductance = 1e-4; // [W/K]
  HeatSim sim(params);
  const auto glass =
      sim.add_material({.name = "glass", .density = density, .young = 1e7, .heat_capacity = 800});
  sim.add_particle(
      {.position = Vec3::Zero(), .radius = radius, .material = glass, .temperature = 300});
  sim.add_particle({.position = Vec3(2 * radius - 1e-6, 0, 0),
                    .radius = radius,
                    .material = glass,
                    .temperature = 400});
  sim.steps(100);
  const auto& p = sim.particles();
  const double C = sphere_mass() * 800;
  const double dT = p.temperature[sim.index_of(1)] - p.temperature[sim.index_of(0)];
  CHECK(dT ==
        grain::test::approx(100.0 * std::pow(1.0 - 1.0 * 1e-4 * 2.0 / C, 100.0)).epsilon(1e-11));
  CHECK(grain::io::describe_contact<Heat>() ==
        "normal linear spring, conduction constant conductance");
}

TEST_CASE("user model: bad parameters raise InputError with the documented message") {
  using grain::test::error_of;
  for (double k : {0.0, -2.0, std::numeric_limits<double>::quiet_NaN(),
                   std::numeric_limits<double>::infinity()}) {
    Sim::Params params;
    params.contact.normal.stiffness = k;
    CAPTURE(k);
    CHECK_THROWS_AS(Sim{params}, grain::InputError);
  }
  Sim::Params params;
  params.contact.normal.stiffness = -2.0;
  CHECK(error_of([&] { Sim sim(params); }) ==
        "my_models::LinearSpring: stiffness = -2 is invalid; valid range: (0, inf)");
  // per pair of materials: the same message, after the pair's name
  Sim sim;
  const auto a = sim.add_material({.name = "a", .density = 2500, .young = 1e7});
  const auto b = sim.add_material({.name = "b", .density = 2500, .young = 1e7});
  CHECK(error_of([&] { sim.set_pair_parameters(a, b, {.normal = {.stiffness = 0.0}}); }) ==
        "Simulation::set_pair_parameters (materials 'a' and 'b'): my_models::LinearSpring: "
        "stiffness = 0 is invalid; valid range: (0, inf)");
}

TEST_CASE("public checks: messages name the object, the value and the valid range") {
  using grain::test::error_of;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  CHECK(error_of([] { grain::require_positive("my::Law", "k", 0.0); }) ==
        "my::Law: k = 0 is invalid; valid range: (0, inf)");
  CHECK(error_of([&] { grain::require_positive("my::Law", "k", inf); }) ==
        "my::Law: k = inf is invalid; valid range: (0, inf)");
  CHECK(error_of([] { grain::require_non_negative("my::Law", "c", -0.5); }) ==
        "my::Law: c = -0.5 is invalid; valid range: [0, inf)");
  CHECK(error_of([&] { grain::require_finite("my::Law", "x", nan); }) ==
        "my::Law: x = nan is invalid; valid range: a finite number");
  CHECK(error_of([] { grain::require_in("my::Law", "e", 1.5, 0.0, 1.0); }) ==
        "my::Law: e = 1.5 is invalid; valid range: [0, 1]");
  CHECK(error_of([] { grain::require_in("my::Law", "e", 0.0, 0.0, 1.0, "(0, 1]"); }).empty());
  CHECK(error_of([&] { grain::require_in("my::Law", "e", nan, 0.0, 1.0, "(0, 1]"); }) ==
        "my::Law: e = nan is invalid; valid range: (0, 1]");
  CHECK(error_of([] { grain::require(3 % 2 == 0, "my::Law", "n", 3, "even numbers"); }) ==
        "my::Law: n = 3 is invalid; valid range: even numbers");
  // values that pass raise nothing
  CHECK(error_of([] {
          grain::require_positive("my::Law", "k", 1e-300);
          grain::require_non_negative("my::Law", "c", 0.0);
          grain::require_finite("my::Law", "x", -1e300);
          grain::require_in("my::Law", "e", 1.0, 0.0, 1.0);
          grain::require(true, "my::Law", "n", 2, "even numbers");
        }).empty());
  // the library's own checks give the same messages
  const std::string object = "my::Law";
  CHECK(error_of([&] { grain::detail::require_positive(object, "k", 0.0); }) ==
        error_of([&] { grain::require_positive(object, "k", 0.0); }));
  CHECK(error_of([&] { grain::detail::require_non_negative(object, "c", -0.5); }) ==
        error_of([&] { grain::require_non_negative(object, "c", -0.5); }));
  CHECK(error_of([&] { grain::detail::require_finite(object, "x", nan); }) ==
        error_of([&] { grain::require_finite(object, "x", nan); }));
  CHECK(error_of([&] { grain::detail::require_in(object, "e", 2.0, 0.0, 1.0, "[0, 1]"); }) ==
        error_of([&] { grain::require_in(object, "e", 2.0, 0.0, 1.0); }));
  CHECK(error_of([&] { grain::detail::require(false, object, "n", 3, std::string("odd")); }) ==
        "my::Law: n = 3 is invalid; valid range: odd");
}
