// Normal contact models in a running simulation: single impacts against the closed forms of
// docs/models/normal.md (linear spring-dashpot, Hertz with Tsuji / critical-ratio /
// Kuwabara-Kono damping, Walton-Braun), particle-wall and particle-particle.
//
// Every impact starts at the instant of first contact (overlap 1e-12 R, so the initial force
// evaluation already sees the contact) with gravity off, search::AllPairs and velocity Verlet,
// at a time step of t_c/N with N >= 200 (N = 2000 for damped contacts, whose rebound converges
// slowly). Tolerance class B: 0.5 % relative. Each test prints its largest relative errors.
#include "../approx.hpp"
#include <algorithm>
#include <cmath>
#include <doctest/doctest.h>
#include <grain/grain.hpp>
#include <grain/models/normal/hertz.hpp>
#include <grain/models/normal/hertz_equivalent.hpp>
#include <grain/models/normal/linear_spring_dashpot.hpp>
#include <grain/models/normal/walton_braun.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

using namespace grain;

namespace {

constexpr double pi = std::numbers::pi;
constexpr double radius = 5e-3;  // particle radius [m]
constexpr double m_star = 1e-3;  // effective mass of every impact [kg]
constexpr double class_b = 5e-3; // relative tolerance of class B

/// Material of the impacts: E = 1e8 Pa, nu = 0.3, restitution e, density such that the effective
/// mass is m* = 1e-3 kg (a sphere, or a disk of unit thickness).
template <class Shape>
Material material(double e, bool wall) {
  const double mass = wall ? m_star : 2.0 * m_star;
  return {.name = "ball",
          .density = mass / Shape{}.volume(radius),
          .young = 1e8,
          .poisson = 0.3,
          .restitution = e};
}

/// Effective radius of the impacts.
double r_eff(bool wall) { return wall ? radius : 0.5 * radius; }

/// Effective properties of the impacts' pair of materials.
PairProperties pair_of(double e) {
  return PairProperties::mix(material<Sphere>(e, true), material<Sphere>(e, true));
}

/// What a single impact produced.
struct Impact {
  double restitution = 0.0;  ///< separation / approach speed
  double contact_time = 0.0; ///< from first contact to the overlap returning to zero [s]
  double max_overlap = 0.0;  ///< [m]
  double max_force = 0.0;    ///< [N]
  double residual = 0.0;     ///< overlap at which the force vanished while unloading [m]
  double peak_energy = 0.0;  ///< largest elastic energy of the contact [J]
  double force_time = 0.0;   ///< from first contact to the force vanishing while unloading [s]
};

/// A head-on impact at relative speed v: one particle against a flat wall (a plane, or a
/// segment in 2D) or two equal particles (each moving at v/2), with the normal model M, the
/// pair's restitution e and the time step dt.
template <class Shape, class M>
Impact impact(const typename M::Params& prm, double e, bool wall, double v, double dt) {
  constexpr int D = Shape::dimension;
  using V = Vec<D>;
  using Sim = Simulation<Shape, search::AllPairs, Interaction<M>, integrate::VelocityVerlet>;
  Sim sim({.time_step = dt, .contact = {.normal = prm}});
  const auto mat = sim.add_material(material<Shape>(e, wall));
  const double touch = 1e-12 * radius; // the contact starts at t = 0
  const V axis = V::Unit(D - 1);
  if (wall) {
    if constexpr (D == 3)
      sim.add_wall(walls::Plane{Vec3::Zero(), Vec3::UnitZ()}, {.material = mat});
    else
      sim.add_wall(walls::Segment{Vec2(-1, 0), Vec2(1, 0)}, {.material = mat});
    sim.add_particle({.position = V((radius - touch) * axis),
                      .radius = radius,
                      .material = mat,
                      .velocity = V(-v * axis)});
  } else {
    sim.add_particle(
        {.position = V::Zero(), .radius = radius, .material = mat, .velocity = V(0.5 * v * axis)});
    sim.add_particle({.position = V((2 * radius - touch) * axis),
                      .radius = radius,
                      .material = mat,
                      .velocity = V(-0.5 * v * axis)});
  }
  const auto& p = sim.particles();
  auto overlap = [&] {
    return wall ? radius - p.position[0].dot(axis)
                : 2 * radius - (p.position[1] - p.position[0]).norm();
  };
  auto approach = [&] {
    return wall ? -p.velocity[0].dot(axis) : (p.velocity[0] - p.velocity[1]).dot(axis);
  };
  auto normal_force = [&] { return wall ? p.force[0].dot(axis) : -p.force[0].dot(axis); };
  Impact r;
  sim.initialize();
  double d_prev = overlap(), f_prev = 0.0, f_prev2 = 0.0, d_prev2 = 0.0;
  bool unloaded = false;
  for (long k = 0; k < 1000000; ++k) {
    sim.step();
    const double d = overlap(), f = normal_force();
    r.max_overlap = std::max(r.max_overlap, d);
    r.max_force = std::max(r.max_force, f);
    sim.for_each_contact([&](auto, auto, bool, const auto&, const auto& res) {
      r.peak_energy = std::max(r.peak_energy, res.normal.elastic_energy);
    });
    if (!unloaded && d < r.max_overlap && f <= 0.0 && f_prev > 0.0) {
      // the force vanished: extrapolate the last two points of the unloading branch to F = 0
      unloaded = true;
      r.residual = d_prev - f_prev * (d_prev - d_prev2) / (f_prev - f_prev2);
      r.force_time = sim.time() - dt + dt * f_prev / (f_prev2 - f_prev);
    }
    if (d <= 0.0) {
      // the overlap crossed zero inside this step: interpolate the crossing time
      r.contact_time = sim.time() - dt * (-d) / (d_prev - d);
      r.restitution = -approach() / v;
      break;
    }
    d_prev2 = d_prev;
    f_prev2 = f_prev;
    d_prev = d;
    f_prev = f;
  }
  REQUIRE(r.contact_time > 0.0); // the pair separated
  return r;
}

/// Closed forms of the damped linear oscillator m* d'' + eta d' + K d = 0, d(0) = 0, d'(0) = v.
struct LinearClosedForm {
  double contact_time, max_overlap;
};
LinearClosedForm linear_closed_form(double k, double e, double v) {
  const double l = std::log(e);
  const double w0 = std::sqrt(k / m_star);
  return {pi / w0 * std::sqrt(1.0 + l * l / (pi * pi)),
          v / w0 * std::exp(-normal::hertz_equivalent::atan_beta_over_beta(l))};
}

double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

/// The largest relative error of each checked quantity of a test, for its summary message.
struct Errors {
  std::vector<std::pair<std::string, double>> worst;
  void add(const std::string& what, double err) {
    for (auto& w : worst)
      if (w.first == what) {
        w.second = std::max(w.second, err);
        return;
      }
    worst.emplace_back(what, err);
  }
  std::string summary() const {
    std::ostringstream s;
    s.precision(2);
    for (const auto& w : worst)
      s << "\n  " << w.first << ": " << w.second;
    return s.str();
  }
};

} // namespace

/// Checks |value - ref| / |ref| < tol and records the relative error under `what`.
#define CHECK_REL(errors, what, value, ref, tol)                                                   \
  do {                                                                                             \
    const double value_ = (value), ref_ = (ref);                                                   \
    (errors).add(what, rel(value_, ref_));                                                         \
    CHECK_MESSAGE(rel(value_, ref_) < (tol), what << ": " << value_ << " vs " << ref_);            \
  } while (0)

TEST_CASE("linear spring-dashpot: restitution, contact time and maximum overlap, e = 0.1 ... 0.9") {
  // K given; the closed forms of the damped oscillator. Unclamped, the force jumps from
  // -eta v_out to zero inside the step in which the pair separates, so the rebound converges at
  // first order in dt: the convergence pair (t_c/200, t_c/400) at the end shows it.
  using M = normal::LinearSpringDashpot;
  Errors errors;
  const double k = 1e4, v = 1.0;
  for (bool wall : {true, false})
    for (double e : {0.1, 0.3, 0.5, 0.7, 0.9}) {
      CAPTURE(wall);
      CAPTURE(e);
      const auto ref = linear_closed_form(k, e, v);
      const auto r = impact<Sphere, M>({.stiffness = k}, e, wall, v, ref.contact_time / 2000);
      CHECK_REL(errors, "e", r.restitution, e, class_b);
      CHECK_REL(errors, "t_c", r.contact_time, ref.contact_time, class_b);
      CHECK_REL(errors, "delta_max", r.max_overlap, ref.max_overlap, class_b);
    }
  const auto ref = linear_closed_form(k, 0.1, v);
  const auto r200 = impact<Sphere, M>({.stiffness = k}, 0.1, true, v, ref.contact_time / 200);
  const auto r400 = impact<Sphere, M>({.stiffness = k}, 0.1, true, v, ref.contact_time / 400);
  const double de200 = std::abs(r200.restitution - 0.1), de400 = std::abs(r400.restitution - 0.1);
  CHECK(de200 < 0.003);
  CHECK(de400 < 0.6 * de200);
  MESSAGE("relative errors at t_c/2000:" << errors.summary() << "\n  e = 0.1: |de| = " << de200
                                         << " at t_c/200, " << de400 << " at t_c/400");
}

TEST_CASE("linear spring-dashpot with a damping ratio: e = exp(-pi zeta / sqrt(1 - zeta^2))") {
  // the third seed's GRANULAR damper: eta = 2 zeta sqrt(m* K) per contact, whatever the pair's
  // restitution (0.9 here); the rebound, contact time and overlap of the damped oscillator
  using M = normal::LinearSpringDashpot;
  Errors errors;
  const double k = 1e4, v = 1.0;
  for (bool wall : {true, false})
    for (double zeta : {0.1, 0.3, 0.5}) {
      CAPTURE(wall);
      CAPTURE(zeta);
      const double e = std::exp(-pi * zeta / std::sqrt(1.0 - zeta * zeta));
      const auto ref = linear_closed_form(k, e, v);
      const auto r = impact<Sphere, M>({.stiffness = k, .damping_ratio = zeta}, 0.9, wall, v,
                                       ref.contact_time / 2000);
      CHECK_REL(errors, "e", r.restitution, e, class_b);
      CHECK_REL(errors, "t_c", r.contact_time, ref.contact_time, class_b);
      CHECK_REL(errors, "delta_max", r.max_overlap, ref.max_overlap, class_b);
    }
  MESSAGE("relative errors at t_c/2000:" << errors.summary());
}

TEST_CASE("linear spring-dashpot: each Hertz-equivalent formulation matches its Hertz quantity") {
  using M = normal::LinearSpringDashpot;
  using normal::Equivalence;
  namespace he = normal::hertz_equivalent;
  Errors errors;
  const double v = 1.0;
  for (bool wall : {true, false})
    for (double e : {0.1, 0.3, 0.5, 0.7, 0.9})
      for (auto q : {Equivalence::energy, Equivalence::overlap, Equivalence::time}) {
        CAPTURE(wall);
        CAPTURE(e);
        CAPTURE(static_cast<int>(q));
        const auto pair = pair_of(e);
        const M::Params prm{.reference_velocity = v, .equivalence = q};
        const double k = M::stiffness(pair, prm, r_eff(wall), m_star);
        const auto ref = linear_closed_form(k, e, v);
        const auto r = impact<Sphere, M>(prm, e, wall, v, ref.contact_time / 2000);
        // the linear closed forms with this K
        CHECK_REL(errors, "e", r.restitution, e, class_b);
        CHECK_REL(errors, "t_c (linear)", r.contact_time, ref.contact_time, class_b);
        CHECK_REL(errors, "delta_max (linear)", r.max_overlap, ref.max_overlap, class_b);
        // the quantity of the undamped Hertz impact that the formulation reproduces
        const double d_hertz = he::hertz_max_overlap(pair, r_eff(wall), m_star, v);
        const double t_hertz = he::hertz_contact_time(pair, r_eff(wall), m_star, v);
        if (q == Equivalence::overlap) {
          CHECK_REL(errors, "overlap: delta_max = Hertz delta_max", r.max_overlap, d_hertz,
                    class_b);
          if (e <= 0.5) CHECK(rel(r.contact_time, t_hertz) > 0.05); // not the duration
        } else if (q == Equivalence::time) {
          CHECK_REL(errors, "time: t_c = Hertz t_c", r.contact_time, t_hertz, class_b);
          if (e <= 0.5) CHECK(rel(r.max_overlap, d_hertz) > 0.05); // not the overlap
        } else {
          // damped: delta_max = delta_Hertz exp(-atan(beta)/beta)
          CHECK_REL(errors, "energy: damped delta_max", r.max_overlap,
                    d_hertz * std::exp(-he::atan_beta_over_beta(std::log(e))), class_b);
          if (e == 0.5) {
            // undamped: the Hertz maximum overlap and maximum strain energy 1/2 m* v^2
            const auto u = impact<Sphere, M>({.reference_velocity = v, .damping = 0.0}, e, wall, v,
                                             ref.contact_time / 2000);
            CHECK_REL(errors, "energy: undamped delta_max = Hertz delta_max", u.max_overlap,
                      d_hertz, class_b);
            CHECK_REL(errors, "energy: undamped peak energy = 1/2 m* v^2", u.peak_energy,
                      0.5 * m_star * v * v, class_b);
          }
        }
      }
  MESSAGE("relative errors at t_c/2000:" << errors.summary());
}

TEST_CASE("linear spring-dashpot without artificial cohesion: the clamped table") {
  using M = normal::LinearSpringDashpot;
  Errors errors;
  const double k = 1e4, w0 = std::sqrt(k / m_star);
  struct Row {
    double e, e_clamped, tc_w0;
  };
  for (bool wall : {true, false})
    for (const Row& row :
         {Row{0.1, 0.2527, 3.5090}, Row{0.3, 0.3971, 3.2963}, Row{0.5, 0.5503, 3.2033},
          Row{0.7, 0.7182, 3.1598}, Row{0.9, 0.9020, 3.1433}}) {
      CAPTURE(wall);
      CAPTURE(row.e);
      const auto r = impact<Sphere, M>({.stiffness = k, .no_cohesion = true}, row.e, wall, 1.0,
                                       row.tc_w0 / w0 / 2000);
      CHECK_REL(errors, "e (clamped)", r.restitution, row.e_clamped, class_b);
      CHECK_REL(errors, "t_c w0 (clamped)", r.contact_time * w0, row.tc_w0, class_b);
    }
  MESSAGE("relative errors at t_c/2000:" << errors.summary());
}

TEST_CASE("linear spring-dashpot: per-contact impact velocity versus reference velocity") {
  using normal::Equivalence;
  namespace he = normal::hertz_equivalent;
  Errors errors;
  const double e = 0.5;
  const auto pair = pair_of(e);
  for (bool wall : {true, false}) {
    CAPTURE(wall);
    const double t_ref = he::hertz_contact_time(pair, r_eff(wall), m_star, 1.0);
    for (double v : {0.1, 1.0, 10.0}) {
      CAPTURE(v);
      // per contact, "time": each contact lasts as long as the Hertz impact at its own speed
      const double t_hertz = he::hertz_contact_time(pair, r_eff(wall), m_star, v);
      const auto pc = impact<Sphere, normal::LinearSpringDashpotPerContact>(
          {.equivalence = Equivalence::time}, e, wall, v, t_hertz / 2000);
      CHECK_REL(errors, "per contact: t_c = Hertz t_c(v)", pc.contact_time, t_hertz, class_b);
      CHECK_REL(errors, "per contact: e", pc.restitution, e, class_b);
      // reference velocity: one stiffness for every contact, so every impact lasts as long as
      // the Hertz impact at the reference velocity
      const auto rv = impact<Sphere, normal::LinearSpringDashpot>(
          {.reference_velocity = 1.0, .equivalence = Equivalence::time}, e, wall, v, t_ref / 2000);
      CHECK_REL(errors, "reference: t_c = Hertz t_c(1 m/s)", rv.contact_time, t_ref, class_b);
    }
    // an impact slower than min_impact_velocity (0.01 m/s) uses the reference velocity: no
    // vanishing stiffness
    const auto slow = impact<Sphere, normal::LinearSpringDashpotPerContact>(
        {.reference_velocity = 1.0, .equivalence = Equivalence::time}, e, wall, 0.004,
        t_ref / 2000);
    CHECK_REL(errors, "below the floor: t_c = Hertz t_c(1 m/s)", slow.contact_time, t_ref, class_b);
    CHECK_REL(errors, "below the floor: e", slow.restitution, e, class_b);
  }
  MESSAGE("relative errors at t_c/2000:" << errors.summary());
}

TEST_CASE("Hertz: the undamped impact (maximum overlap, force, contact time)") {
  namespace he = normal::hertz_equivalent;
  using M = normal::Hertz<>;
  Errors errors;
  for (bool wall : {true, false})
    for (double v : {0.1, 1.0}) {
      CAPTURE(wall);
      CAPTURE(v);
      const auto pair = pair_of(1.0); // e = 1: alpha = 0
      const double re = r_eff(wall);
      const double tc = he::hertz_contact_time(pair, re, m_star, v);
      const double dmax = he::hertz_max_overlap(pair, re, m_star, v);
      const double kh = M::k_hertz(pair, re);
      const auto r = impact<Sphere, M>({}, 1.0, wall, v, tc / 200);
      CHECK_REL(errors, "delta_max", r.max_overlap, dmax, class_b);
      CHECK_REL(errors, "F_max", r.max_force, kh * dmax * std::sqrt(dmax), class_b);
      CHECK_REL(errors, "t_c", r.contact_time, tc, class_b);
      CHECK_REL(errors, "e", r.restitution, 1.0, 1e-4);
      // t_c = 2.9432 delta_max / v = 3.2181 (m*/K_hz)^(2/5) v^(-1/5)
      CHECK(tc == grain::test::approx(2.9432 * dmax / v).epsilon(1e-4));
      CHECK(tc == grain::test::approx(3.2181 * std::pow(m_star / kh, 0.4) * std::pow(v, -0.2))
                      .epsilon(1e-4));
    }
  MESSAGE("relative errors at t_c/200:" << errors.summary());
}

TEST_CASE("Hertz with Tsuji damping: exact map, Norouzi fit and clamped rebound") {
  namespace he = normal::hertz_equivalent;
  using M = normal::Hertz<normal::TsujiDamping>;
  Errors errors;
  struct Row {
    double e, e_norouzi, e_clamped;
  };
  double worst200 = 0;
  for (bool wall : {true, false})
    for (const Row& row :
         {Row{0.1, 0.0983, 0.2527}, Row{0.2, 0.1988, 0.3249}, Row{0.3, 0.2992, 0.3971},
          Row{0.5, 0.4997, 0.5503}, Row{0.7, 0.6999, 0.7182}, Row{0.9, 0.9000, 0.9020}}) {
      CAPTURE(wall);
      CAPTURE(row.e);
      const double tc = he::hertz_contact_time(pair_of(row.e), r_eff(wall), m_star, 1.0);
      // exact map: |de| <= 0.003 at t_c/200, class B at t_c/2000
      const auto coarse = impact<Sphere, M>({}, row.e, wall, 1.0, tc / 200);
      CHECK(std::abs(coarse.restitution - row.e) <= 0.003);
      worst200 = std::max(worst200, std::abs(coarse.restitution - row.e));
      const auto r = impact<Sphere, M>({}, row.e, wall, 1.0, tc / 2000);
      CHECK_REL(errors, "exact map: e", r.restitution, row.e, class_b);
      // Norouzi fit: its own table column
      const auto n = impact<Sphere, M>({.damping = {.map = normal::TsujiMap::norouzi}}, row.e, wall,
                                       1.0, tc / 2000);
      CHECK_REL(errors, "Norouzi fit: e vs its column", n.restitution, row.e_norouzi, class_b);
      // without artificial cohesion
      const auto c = impact<Sphere, M>({.no_cohesion = true}, row.e, wall, 1.0, tc / 2000);
      CHECK_REL(errors, "no cohesion: e vs clamped column", c.restitution, row.e_clamped, class_b);
    }
  // the rebound does not depend on the impact velocity
  for (double v : {0.1, 10.0}) {
    const double tc = he::hertz_contact_time(pair_of(0.3), r_eff(true), m_star, v);
    const auto r = impact<Sphere, M>({}, 0.3, true, v, tc / 2000);
    CHECK_REL(errors, "exact map: e at 0.1 and 10 m/s", r.restitution, 0.3, class_b);
  }
  MESSAGE("relative errors at t_c/2000:" << errors.summary()
                                         << "\n  exact map, largest |de| at t_c/200: " << worst200);
}

// The elastic and viscous parts of the normal force (NormalResult::viscous; the elastic part is
// force - viscous). A Hertz-Tsuji sphere hits a wall at 1 m/s with e = 0.5: at every step of the
// contact the elastic part is 4/3 E* sqrt(R*) delta^(3/2) and the viscous part eta(delta) v_n,
// to round-off (1e-12 relative); and the work of the viscous part over the impact,
// sum(F_v v_n dt), is the kinetic energy lost, 1/2 m* v^2 (1 - e_measured^2), to 1 % (the sum
// is a first-order quadrature at t_c/2000). The linear spring-dashpot splits the same way
// (elastic part K delta, viscous part F - K delta).
TEST_CASE("normal force: elastic and viscous parts, and the work of the viscous part") {
  namespace he = normal::hertz_equivalent;
  using M = normal::Hertz<normal::TsujiDamping>;
  using Sim = Simulation<Sphere, search::AllPairs, Interaction<M>, integrate::VelocityVerlet>;
  const double e = 0.5, v = 1.0;
  const PairProperties pair = pair_of(e);
  const double tc = he::hertz_contact_time(pair, r_eff(true), m_star, v);
  const double dt = tc / 2000;
  Sim sim({.time_step = dt});
  const auto mat = sim.add_material(material<Sphere>(e, true));
  sim.add_wall(walls::Plane{Vec3::Zero(), Vec3::UnitZ()}, {.material = mat});
  sim.add_particle({.position = Vec3(0, 0, radius * (1 - 1e-12)),
                    .radius = radius,
                    .material = mat,
                    .velocity = Vec3(0, 0, -v)});
  sim.initialize();
  double work = 0.0, worst_elastic = 0.0, worst_viscous = 0.0;
  const double k_hz = 4.0 / 3.0 * sim.pair_properties(0, 0).young_eff * std::sqrt(radius);
  for (long k = 0; k < 100000 && (k == 0 || sim.contact_counts().second > 0); ++k) {
    sim.step();
    sim.for_each_contact([&](auto, auto, bool, const auto& g, const auto& r) {
      const double elastic = r.normal.force - r.normal.viscous;
      const double fe = k_hz * std::pow(g.overlap, 1.5);
      worst_elastic = std::max(worst_elastic, std::abs(elastic - fe) / fe);
      const double fv = r.normal.damping * g.normal_velocity;
      worst_viscous =
          std::max(worst_viscous, std::abs(r.normal.viscous - fv) / std::max(std::abs(fv), 1e-300));
      work += r.normal.viscous * g.normal_velocity * dt;
    });
  }
  const double e_measured = sim.particles().velocity[0][2] / v;
  const double lost = 0.5 * m_star * v * v * (1.0 - e_measured * e_measured);
  CHECK(worst_elastic < 1e-12);
  CHECK(worst_viscous < 1e-12);
  CHECK(work == grain::test::approx(lost).epsilon(0.01));
  MESSAGE("Hertz-Tsuji e = " << e_measured << ": viscous work " << work << " J, energy lost "
                             << lost << " J; elastic part error " << worst_elastic);

  // the linear spring-dashpot: elastic part K delta
  using L = normal::LinearSpringDashpot;
  using SimL = Simulation<Sphere, search::AllPairs, Interaction<L>, integrate::VelocityVerlet>;
  SimL lin({.time_step = dt, .contact = {.normal = {.stiffness = 1e4}}});
  const auto ml = lin.add_material(material<Sphere>(e, true));
  lin.add_wall(walls::Plane{Vec3::Zero(), Vec3::UnitZ()}, {.material = ml});
  lin.add_particle({.position = Vec3(0, 0, radius * (1 - 1e-6)),
                    .radius = radius,
                    .material = ml,
                    .velocity = Vec3(0, 0, -v)});
  lin.steps(20);
  int seen = 0;
  lin.for_each_contact([&](auto, auto, bool, const auto& g, const auto& r) {
    CHECK(r.normal.force - r.normal.viscous == grain::test::approx(1e4 * g.overlap).epsilon(1e-12));
    CHECK(r.normal.viscous ==
          grain::test::approx(r.normal.damping * g.normal_velocity).epsilon(1e-12));
    ++seen;
  });
  CHECK(seen == 1);
}

TEST_CASE("Hertz with critical-ratio damping equals Tsuji with alpha = sqrt(6) xi") {
  namespace he = normal::hertz_equivalent;
  using M = normal::Hertz<normal::CriticalRatioDamping>;
  Errors errors;
  for (double e : {0.3, 0.7}) {
    CAPTURE(e);
    const double xi = normal::TsujiDamping::exact_alpha(std::log(e)) / std::sqrt(6.0);
    const double tc = he::hertz_contact_time(pair_of(e), r_eff(false), m_star, 1.0);
    // this policy does not use the pair's restitution: the material has e = 1
    const auto r = impact<Sphere, M>({.damping = {.ratio = xi}}, 1.0, false, 1.0, tc / 2000);
    CHECK_REL(errors, "e", r.restitution, e, class_b);
  }
  MESSAGE("relative errors at t_c/2000:" << errors.summary());
}

TEST_CASE("Hertz with Kuwabara-Kono damping: e(kappa) table and slope 1/5") {
  namespace he = normal::hertz_equivalent;
  using M = normal::Hertz<normal::KuwabaraKonoDamping>;
  Errors errors;
  const auto pair = pair_of(1.0);
  struct Row {
    double kappa, e_clamped, e;
  };
  // kappa = eta v^(1/5) / (K_hz^(3/5) m*^(2/5)); the wall at 1 m/s, the pair at 3 m/s
  for (bool wall : {true, false}) {
    const double v = wall ? 1.0 : 3.0;
    const double kh = M::k_hertz(pair, r_eff(wall));
    const double tc = he::hertz_contact_time(pair, r_eff(wall), m_star, v);
    for (const Row& row :
         {Row{0.01, 0.9885, 0.9885}, Row{0.05, 0.9444, 0.9443}, Row{0.1, 0.8929, 0.8921},
          Row{0.2, 0.8010, 0.7976}, Row{0.5, 0.5953, 0.5738}, Row{1.0, 0.3939, 0.3312}}) {
      CAPTURE(wall);
      CAPTURE(row.kappa);
      const double eta = row.kappa * std::pow(kh, 0.6) * std::pow(m_star, 0.4) / std::pow(v, 0.2);
      const auto r = impact<Sphere, M>({.damping = {.coefficient = eta}}, 1.0, wall, v, tc / 2000);
      CHECK_REL(errors, "e(kappa)", r.restitution, row.e, class_b);
      const auto c = impact<Sphere, M>({.no_cohesion = true, .damping = {.coefficient = eta}}, 1.0,
                                       wall, v, tc / 2000);
      CHECK_REL(errors, "e(kappa), no cohesion", c.restitution, row.e_clamped, class_b);
    }
  }
  // fixed eta, v = 0.1 ... 10 m/s (kappa = 0.004 ... 0.01): 1 - e grows as v^(1/5)
  const double kh = M::k_hertz(pair, r_eff(true));
  const double eta = 0.004 * std::pow(kh, 0.6) * std::pow(m_star, 0.4) / std::pow(0.1, 0.2);
  double sx = 0, sy = 0, sxx = 0, sxy = 0, worst = 0;
  for (double v : {0.1, 0.3, 1.0, 3.0, 10.0}) {
    CAPTURE(v);
    const double tc = he::hertz_contact_time(pair, r_eff(true), m_star, v);
    const auto r = impact<Sphere, M>({.damping = {.coefficient = eta}}, 1.0, true, v, tc / 2000);
    const double kappa = eta * std::pow(v, 0.2) / (std::pow(kh, 0.6) * std::pow(m_star, 0.4));
    const double de = std::abs(r.restitution - (1 - 1.1534 * kappa + 0.7983 * kappa * kappa));
    CHECK(de < 1e-4);
    worst = std::max(worst, de);
    const double x = std::log(v), y = std::log(1.0 - r.restitution);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  const double n = 5.0;
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  CHECK(std::abs(slope - 0.2) <= 0.01);
  MESSAGE("relative errors at t_c/2000:"
          << errors.summary() << "\n  |e - (1 - 1.1534 kappa + 0.7983 kappa^2)| <= " << worst
          << "\n  d ln(1 - e) / d ln v = " << slope);
}

TEST_CASE("Walton-Braun, constant unloading: e, delta_max, F_max, t_c and residual overlap") {
  using M = normal::WaltonBraun;
  Errors errors;
  const double kl = 1e5, v = 1.0;
  for (bool wall : {true, false})
    for (double e : {0.3, 0.6, 0.9}) {
      CAPTURE(wall);
      CAPTURE(e);
      const double tc = 0.5 * pi * std::sqrt(m_star / kl) * (1 + e); // = 1.5708e-4 (1 + e) s
      const auto r = impact<Sphere, M>({.stiffness = kl}, e, wall, v, tc / 2000);
      CHECK_REL(errors, "e", r.restitution, e, class_b);
      CHECK_REL(errors, "delta_max = 1e-4 m", r.max_overlap, 1.0e-4, class_b);
      CHECK_REL(errors, "F_max = 10 N", r.max_force, 10.0, class_b);
      CHECK_REL(errors, "t_c (force)", r.force_time, tc, class_b);
      CHECK_REL(errors, "delta_res", r.residual, 1.0e-4 * (1 - e * e), class_b);
      // after the force has vanished the pair flies apart at e v through the residual overlap
      CHECK_REL(errors, "t_c (overlap)", r.contact_time, tc + r.residual / (e * v), class_b);
    }
  MESSAGE("relative errors at t_c/2000:" << errors.summary());
}

TEST_CASE("Walton-Braun, variable unloading: residual overlap from the actual maximum") {
  using M = normal::WaltonBraun;
  Errors errors;
  const double kl = 1e5, s = 2e4, e_pair = 0.5;
  for (bool wall : {true, false})
    for (double v : {0.5, 1.0, 2.0}) {
      CAPTURE(wall);
      CAPTURE(v);
      const double dmax = v * std::sqrt(m_star / kl), fmax = v * std::sqrt(m_star * kl);
      const double ku = kl + s * fmax;
      const double e = std::sqrt(kl / ku);
      CHECK(e == grain::test::approx(1.0 / std::sqrt(1 + s * v * std::sqrt(m_star / kl))));
      const double tc = 0.5 * pi * std::sqrt(m_star / kl) * (1 + e);
      const auto r = impact<Sphere, M>(
          {.stiffness = kl, .unloading = normal::Unloading::variable, .unloading_slope = s}, e_pair,
          wall, v, tc / 2000);
      CHECK_REL(errors, "e(v)", r.restitution, e, class_b);
      CHECK_REL(errors, "delta_max", r.max_overlap, dmax, class_b);
      CHECK_REL(errors, "F_max", r.max_force, fmax, class_b);
      CHECK_REL(errors, "t_c (force)", r.force_time, tc, class_b);
      CHECK_REL(errors, "delta_res = delta_max (1 - K_L/K_U)", r.residual, dmax * (1 - kl / ku),
                class_b);
      // the a-priori value delta_max (1 - e_input^2) is a different number
      CHECK(rel(r.residual, dmax * (1 - e_pair * e_pair)) > 0.05);
    }
  MESSAGE("relative errors at t_c/2000:" << errors.summary());
}

TEST_CASE("Walton-Braun, given unloading stiffness: e = sqrt(K_L/K_U), whatever the pair's e") {
  using M = normal::WaltonBraun;
  Errors errors;
  const double kl = 1e5, v = 1.0, e_pair = 0.3; // the pair's e is not used
  for (bool wall : {true, false})
    for (double ku : {1.2e5, 4e5, 2e6}) {
      CAPTURE(wall);
      CAPTURE(ku);
      const double e = std::sqrt(kl / ku), dmax = v * std::sqrt(m_star / kl);
      const double tc = 0.5 * pi * std::sqrt(m_star / kl) * (1 + e);
      const auto r = impact<Sphere, M>(
          {.stiffness = kl, .unloading = normal::Unloading::given, .unloading_stiffness = ku},
          e_pair, wall, v, tc / 2000);
      CHECK_REL(errors, "e", r.restitution, e, class_b);
      CHECK_REL(errors, "t_c (force)", r.force_time, tc, class_b);
      CHECK_REL(errors, "delta_res = delta_max (1 - K_L/K_U)", r.residual, dmax * (1 - kl / ku),
                class_b);
    }
  // a K_U below K_L is taken as K_L: an elastic contact, e = 1, no residual overlap
  const double tc = pi * std::sqrt(m_star / kl);
  const auto r = impact<Sphere, M>(
      {.stiffness = kl, .unloading = normal::Unloading::given, .unloading_stiffness = 0.5 * kl},
      e_pair, true, v, tc / 2000);
  CHECK_REL(errors, "e (K_U < K_L)", r.restitution, 1.0, class_b);
  // the time equivalence with a given K_U: the contact lasts the undamped Hertz time
  {
    namespace he = normal::hertz_equivalent;
    const auto pair = pair_of(e_pair);
    const double th = he::hertz_contact_time(pair, r_eff(true), m_star, v);
    const typename M::Params p{.equivalence = normal::Equivalence::time,
                               .unloading = normal::Unloading::given,
                               .unloading_stiffness = 4e6};
    const double k = M::loading_stiffness(pair, p, r_eff(true), m_star, v);
    const double twb = 0.5 * pi * std::sqrt(m_star / k) * (1 + std::sqrt(k / 4e6));
    CHECK_REL(errors, "Walton-Braun duration = Hertz duration (time, given K_U)", twb, th, 1e-12);
  }
  // Unloading::given needs a stiffness
  CHECK_THROWS_WITH_AS(M::validate({.unloading = normal::Unloading::given}),
                       doctest::Contains("unloading_stiffness"), InputError);
  MESSAGE("relative errors at t_c/2000:" << errors.summary());
}

TEST_CASE("Walton-Braun with a force cap: plateau, then unloading from the cap") {
  using M = normal::WaltonBraun;
  Errors errors;
  const double kl = 1e5, v = 1.0, e = 0.6, cap = 6.0;
  const double f0 = v * std::sqrt(m_star * kl); // 10 N without the cap
  const double ku = kl / (e * e);
  // energy: 1/2 m v^2 = cap^2/(2 K_L) + cap (delta_max - cap/K_L)
  const double dmax = 0.5 * cap / kl + 0.5 * m_star * v * v / cap;
  const double v1 = v * std::sqrt(1 - (cap / f0) * (cap / f0)); // speed when the cap is reached
  const double tc = std::sqrt(m_star / kl) * std::asin(cap / f0) + m_star * v1 / cap +
                    0.5 * pi * std::sqrt(m_star / ku);
  for (bool wall : {true, false}) {
    CAPTURE(wall);
    const auto r = impact<Sphere, M>({.stiffness = kl, .max_force = cap}, e, wall, v, tc / 2000);
    CHECK_REL(errors, "F_max = cap", r.max_force, cap, 1e-12);
    CHECK_REL(errors, "delta_max", r.max_overlap, dmax, class_b);
    // the contact gives back cap^2/(2 K_U): e_out = e cap / F_0
    CHECK_REL(errors, "e", r.restitution, e * cap / f0, class_b);
    CHECK_REL(errors, "delta_res", r.residual, dmax - cap / ku, class_b);
    CHECK_REL(errors, "t_c (force)", r.force_time, tc, class_b);
  }
  MESSAGE("relative errors at t_c/2000:" << errors.summary());
}

TEST_CASE("Walton-Braun: Hertz-equivalent loading stiffness") {
  namespace he = normal::hertz_equivalent;
  using M = normal::WaltonBraun;
  using normal::Equivalence;
  Errors errors;
  const double v = 1.0;
  for (bool wall : {true, false}) {
    CAPTURE(wall);
    // energy (= overlap for this model): the maximum overlap and strain energy of the undamped
    // Hertz impact; e^2 of that energy comes back
    for (auto q : {Equivalence::energy, Equivalence::overlap}) {
      const auto pair = pair_of(0.5);
      const M::Params prm{.equivalence = q};
      const double kl = M::loading_stiffness(pair, prm, r_eff(wall), m_star, v);
      const double tc = 0.5 * pi * std::sqrt(m_star / kl) * 1.5;
      const auto r = impact<Sphere, M>(prm, 0.5, wall, v, tc / 2000);
      CHECK_REL(errors, "energy/overlap: delta_max = Hertz delta_max", r.max_overlap,
                he::hertz_max_overlap(pair, r_eff(wall), m_star, v), class_b);
      CHECK_REL(errors, "energy/overlap: recoverable energy = e^2 m* v^2/2", r.peak_energy,
                0.5 * m_star * v * v * 0.25, class_b);
    }
    // time: the force contact lasts as long as the undamped Hertz impact
    for (double e : {0.3, 0.6}) {
      CAPTURE(e);
      const auto pair = pair_of(e);
      const double t_hertz = he::hertz_contact_time(pair, r_eff(wall), m_star, v);
      const auto r =
          impact<Sphere, M>({.equivalence = Equivalence::time}, e, wall, v, t_hertz / 2000);
      CHECK_REL(errors, "time: t_c = Hertz t_c", r.force_time, t_hertz, class_b);
      CHECK_REL(errors, "time: e", r.restitution, e, class_b);
    }
    const auto pair = pair_of(0.5);
    const double t_hertz = he::hertz_contact_time(pair, r_eff(wall), m_star, v);
    const auto r = impact<Sphere, M>({.equivalence = Equivalence::time,
                                      .unloading = normal::Unloading::variable,
                                      .unloading_slope = 1e4},
                                     0.5, wall, v, t_hertz / 2000);
    CHECK_REL(errors, "time, variable unloading: t_c = Hertz t_c", r.force_time, t_hertz, class_b);
  }
  MESSAGE("relative errors at t_c/2000:" << errors.summary());
}

TEST_CASE("Walton-Braun: re-loading before full unloading follows the unloading line") {
  // Two particles moved by prescribed velocities (fixed particles keep theirs): load to d1,
  // unload half-way down the unloading line, re-load past d1 to d2, unload completely. The force
  // of every step is compared with the loading and unloading lines through the largest overlap
  // reached so far.
  using M = normal::WaltonBraun;
  using Sim = Simulation<Sphere, search::AllPairs, Interaction<M>, integrate::VelocityVerlet>;
  const double kl = 1e5, e = 0.5, ku = kl / (e * e), u = 0.02, dt = 1e-7;
  const double d1 = 4e-5, d2 = 6e-5;
  Sim sim({.time_step = dt, .contact = {.normal = {.stiffness = kl}}});
  const auto mat = sim.add_material(material<Sphere>(e, false));
  sim.add_particle({.position = Vec3::Zero(), .radius = radius, .material = mat, .fixed = true});
  sim.add_particle({.position = Vec3(2 * radius - 1e-12, 0, 0),
                    .radius = radius,
                    .material = mat,
                    .velocity = Vec3(-u, 0, 0),
                    .fixed = true});
  auto& p = sim.particles();
  int phase = 0; // 0 load to d1, 1 unload half-way, 2 re-load to d2, 3 unload
  double dmax = 0.0, worst = 0.0, half = 0.0;
  bool unloaded_on_line = false, reloaded_on_line = false, separated_at_residual = false;
  for (long k = 0; k < 200000 && phase < 4; ++k) {
    sim.step();
    const double d = 2 * radius - (p.position[1] - p.position[0]).norm();
    const double f = p.force[1].x(); // repulsive: pushes particle 1 along +x
    double expected = 0.0;
    if (d >= dmax) {
      dmax = d;
      expected = kl * d;
    } else {
      const double residual = dmax * (1 - kl / ku);
      expected = std::max(0.0, ku * (d - residual));
      if (phase == 1 && d > residual) unloaded_on_line = true;
      if (phase == 2 && d > residual) reloaded_on_line = true;
      if (phase == 3 && d > 0 && d < residual && f == 0.0) separated_at_residual = true;
    }
    worst = std::max(worst, std::abs(f - expected) / (kl * d2));
    if (phase == 0 && d >= d1) {
      phase = 1;
      half = d1 - 0.5 * d1 * kl / ku; // half-way between d1 and its residual overlap
      p.velocity[1].x() = u;
    } else if (phase == 1 && d <= half) {
      phase = 2;
      p.velocity[1].x() = -u;
    } else if (phase == 2 && d >= d2) {
      phase = 3;
      p.velocity[1].x() = u;
    } else if (phase == 3 && d < 0.0) {
      phase = 4;
    }
  }
  CHECK(phase == 4);
  CHECK(unloaded_on_line);
  CHECK(reloaded_on_line);
  CHECK(separated_at_residual);
  CHECK(worst < 1e-9);
  MESSAGE("largest deviation from the loading/unloading lines: " << worst << " K_L d2");
}

TEST_CASE("2D disks: linear spring-dashpot and Walton-Braun closed forms") {
  Errors errors;
  const double k = 1e4, v = 1.0;
  for (bool wall : {true, false}) {
    CAPTURE(wall);
    const auto ref = linear_closed_form(k, 0.3, v);
    const auto r = impact<Disk, normal::LinearSpringDashpot>({.stiffness = k}, 0.3, wall, v,
                                                             ref.contact_time / 2000);
    CHECK_REL(errors, "linear: e", r.restitution, 0.3, class_b);
    CHECK_REL(errors, "linear: t_c", r.contact_time, ref.contact_time, class_b);
    const double tc = 0.5 * pi * std::sqrt(m_star / 1e5) * 1.6;
    const auto w = impact<Disk, normal::WaltonBraun>({.stiffness = 1e5}, 0.6, wall, v, tc / 2000);
    CHECK_REL(errors, "Walton-Braun: e", w.restitution, 0.6, class_b);
    CHECK_REL(errors, "Walton-Braun: F_max", w.max_force, 10.0, class_b);
    CHECK_REL(errors, "Walton-Braun: t_c (force)", w.force_time, tc, class_b);
  }
  MESSAGE("relative errors at t_c/2000:" << errors.summary());
}
