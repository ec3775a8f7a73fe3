// Conditions (conditions/conditions.hpp and their use in simulation.hpp) against closed forms:
// prescribed forces, torques, heat rates and heat fluxes; fixed temperatures of particles and
// walls; prescribed motion (velocity and acceleration histories) for every integrator;
// restraints; time-dependent gravity, global and mass-proportional damping; wall motion by a
// fixed velocity; groups (selection, identity across re-sorting, input errors).
//
// Particles: R = 10 mm, rho = 2500 kg/m^3, E = 1e7 Pa, c = 800 J/(kg K), k = 1 W/(m K); a
// sphere has m = rho 4/3 pi R^3, I = 2/5 m R^2; a disk (unit thickness) m = rho pi R^2 L,
// I = 1/2 m R^2 (particles/shape.hpp). No gravity unless stated.
//
// Tolerances: "round-off" checks (1e-12 .. 1e-10 relative) are for schemes that reproduce the
// closed form exactly (constant or linear histories, forward Euler with a constant rate, the
// midpoint rule of a prescribed velocity): the only error is the rounding of N <= 1e4 summed
// increments, about N x 1.1e-16 relative. Truncation checks state their error estimate.
#include "../approx.hpp"
#include <doctest/doctest.h>
#include <grain/grain.hpp>
#include <grain/models/conduction/batchelor_obrien.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <set>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

using namespace grain;
using grain::test::approx;

namespace {

constexpr double pi = std::numbers::pi;
constexpr double R = 0.01;     // particle radius [m]
constexpr double rho = 2500.0; // [kg/m^3]
constexpr double cap = 800.0;  // specific heat capacity [J/(kg K)]

using ThermalContact =
    Interaction<normal::Hertz<>, tangent::Mindlin, rolling::None, conduction::BatchelorOBrien>;

template <class I = integrate::VelocityVerlet>
using Sim3 = Simulation<Sphere, search::CellList, presets::HertzMindlin, I>;
template <class I = integrate::VelocityVerlet>
using Sim2 = Simulation<Disk, search::CellList, presets::HertzMindlin, I>;
using Sim3T = Simulation<Sphere, search::CellList, ThermalContact>;
using Sim2T = Simulation<Disk, search::CellList, ThermalContact>;

#define GRAIN_ALL_INTEGRATORS                                                                      \
  integrate::VelocityVerlet, integrate::SymplecticEuler, integrate::ForwardEuler, integrate::Taylor2

Material grain_material() {
  Material m;
  m.name = "grain";
  m.density = rho;
  m.young = 1e7;
  m.poisson = 0.25;
  m.heat_capacity = cap;
  m.conductivity = 1.0;
  return m;
}

double sphere_mass() { return rho * 4.0 / 3.0 * pi * R * R * R; }
double sphere_inertia() { return 0.4 * sphere_mass() * R * R; }
double disk_mass() { return rho * pi * R * R * 1.0; }
double disk_inertia() { return 0.5 * disk_mass() * R * R; }

template <class Sim>
Sim make(double dt) {
  typename Sim::Params p;
  p.time_step = dt;
  return Sim(p);
}

/// Relative error |a - b| / |b| (for the messages).
double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

} // namespace

// ------------------------------------------------------------------------------------------------
// 1. prescribed forces
// ------------------------------------------------------------------------------------------------

namespace {
/// A free sphere under F = F0 sin(2 pi t / P) along x; returns (x, v) after n steps of dt.
template <class I>
std::pair<double, double> sine_force(double F0, double P, double dt, long n) {
  auto sim = make<Sim3<I>>(dt);
  const auto k = sim.add_material(grain_material());
  const auto id = sim.add_particle({.position = {0, 0, 0}, .radius = R, .material = k});
  sim.prescribe_force("all", VectorTimeFunction<3>(TimeFunction::oscillatory(0, F0, P), 0.0, 0.0));
  sim.steps(n);
  const auto i = sim.index_of(id);
  // the force is along x only: the other components stay exactly 0
  CHECK(sim.particles().position[i].y() == 0.0);
  CHECK(sim.particles().position[i].z() == 0.0);
  return {sim.particles().position[i].x(), sim.particles().velocity[i].x()};
}
} // namespace

TEST_CASE("conditions: free sphere under a sinusoidal prescribed force") {
  // x(t) = F0/m (t/w - sin(w t)/w^2), v(t) = F0/(m w) (1 - cos(w t)), w = 2 pi / P
  const double F0 = 0.01, P = 0.02, w = 2.0 * pi / P, dt = 1e-5, m = sphere_mass();
  const long n = 4500; // t = 2.25 P: sin(w t) = 1, both terms of x count
  const double t = n * dt;
  const double x_exact = F0 / m * (t / w - std::sin(w * t) / (w * w));
  const double v_exact = F0 / (m * w) * (1.0 - std::cos(w * t));
  {
    // velocity Verlet: v is the trapezoidal rule of a(t), error (dt^2/12) |a'(t) - a'(0)|
    // <= (w dt)^2/6 of F0/(m w); x obeys the central difference, error O((w dt)^2/12) of x.
    // Tolerance (w dt)^2 = 9.9e-6 relative.
    const auto [x, v] = sine_force<integrate::VelocityVerlet>(F0, P, dt, n);
    const double tol = (w * dt) * (w * dt);
    CHECK(x == approx(x_exact).epsilon(tol));
    CHECK(v == approx(v_exact).epsilon(tol));
    MESSAGE("sine force, velocity Verlet: rel. error x "
            << rel(x, x_exact) << ", v " << rel(v, v_exact) << " (tol " << tol << ")");
  }
  {
    // symplectic Euler: v is the left Riemann sum of a(t), error (dt/2) |a(t) - a(0)| <=
    // (w dt)/2 of F0/(m w) (here v = F0/(m w) exactly, so the bound is reached): first order.
    // Tolerance w dt = 3.1e-3 relative.
    const auto [x, v] = sine_force<integrate::SymplecticEuler>(F0, P, dt, n);
    const double tol = w * dt;
    CHECK(x == approx(x_exact).epsilon(tol));
    CHECK(v == approx(v_exact).epsilon(tol));
    MESSAGE("sine force, symplectic Euler: rel. error x "
            << rel(x, x_exact) << ", v " << rel(v, v_exact) << " (tol " << tol << ")");
  }
}

TEST_CASE("conditions: a force pulse acts once per step its interval covers, ends included") {
  // F on [0.5, 1.0] s, dt = 2^-12 s (the step times hit both ends exactly): 2049 evaluations,
  // impulse 2049 F dt (one step more than F x 0.5 s); the interval moved by dt/2 covers 2048
  // evaluations, impulse F x 0.5 s. Velocity Verlet, no gravity; tolerance: round-off, 1e-12.
  const double dt = 1.0 / 4096.0, F = 1e-3;
  auto velocity_after = [&](double a, double b) {
    auto sim = make<Sim3<>>(dt);
    const auto k = sim.add_material(grain_material());
    const auto id = sim.add_particle({.position = {0, 0, 0}, .radius = R, .material = k});
    sim.prescribe_force("all", VectorTimeFunction<3>(Vec3(F, 0, 0)).active(a, b));
    sim.steps(6144); // 1.5 s
    return sim.particles().velocity[sim.index_of(id)].x();
  };
  CHECK(velocity_after(0.5, 1.0) == approx(2049 * F * dt / sphere_mass()).epsilon(1e-12));
  CHECK(velocity_after(0.5 + dt / 2, 1.0 + dt / 2) ==
        approx(0.5 * F / sphere_mass()).epsilon(1e-12));
}

TEST_CASE_TEMPLATE("conditions: prescribed forces on a group are summed", I,
                   GRAIN_ALL_INTEGRATORS) {
  // two constant forces on the same group: v = (F1 + F2) t / m, x = (F1 + F2) t^2 / (2 m).
  // Every scheme gives v exactly for a constant force, and x = a t^2/2 exactly, except the
  // two first-order Euler schemes, whose positions are the exact sums x_n = a dt^2 n (n - 1)/2
  // (forward: old velocity) and a dt^2 n (n + 1)/2 (symplectic: new velocity).
  // Tolerance: round-off of 1e3 increments, 1e-12.
  const double dt = 1e-5, m = sphere_mass();
  auto sim = make<Sim3<I>>(dt);
  const auto k = sim.add_material(grain_material());
  const auto a = sim.add_particle({.position = {0, 0, 0}, .radius = R, .material = k});
  const auto b = sim.add_particle({.position = {0.5, 0, 0}, .radius = R, .material = k});
  sim.add_group("a", {a});
  const Vec3 F1(1e-3, 0, 2e-3), F2(0, -2e-3, 1e-3);
  sim.prescribe_force("a", F1);
  sim.prescribe_force("a", F2);
  const long n = 1000;
  sim.steps(n);
  const double t = sim.time();
  CHECK(t == approx(n * dt).epsilon(1e-14));
  const Vec3 acc = (F1 + F2) / m;
  const double xfac = std::is_same_v<I, integrate::ForwardEuler>      ? t * (t - dt) / 2
                      : std::is_same_v<I, integrate::SymplecticEuler> ? t * (t + dt) / 2
                                                                      : t * t / 2;
  const auto ia = sim.index_of(a), ib = sim.index_of(b);
  for (int d = 0; d < 3; ++d) {
    CHECK(sim.particles().velocity[ia][d] == approx(acc[d] * t).epsilon(1e-12));
    CHECK(sim.particles().position[ia][d] == approx(acc[d] * xfac).epsilon(1e-12));
  }
  // the other particle is not in the group: nothing acts on it
  CHECK(sim.particles().velocity[ib].norm() == 0.0);
  CHECK(sim.particles().position[ib].x() == 0.5);
}

TEST_CASE_TEMPLATE(
    "conditions: a prescribed force active in [t1, t2] gives the impulse F (t2 - t1)", I,
    GRAIN_ALL_INTEGRATORS) {
  // v = F (t2 - t1) / m after the interval. t1, t2 lie half-way between step ends, so no
  // evaluation time is ambiguous: velocity Verlet (trapezoid over the end-of-step values)
  // and the Euler schemes (one value per step) both integrate exactly N = (t2 - t1)/dt
  // active values. Tolerance: round-off, 1e-12.
  const double dt = 1e-5, m = sphere_mass();
  auto sim = make<Sim3<I>>(dt);
  const auto k = sim.add_material(grain_material());
  const auto id = sim.add_particle({.position = {0, 0, 0}, .radius = R, .material = k});
  const double t1 = 100.5 * dt, t2 = 600.5 * dt, F = 0.02;
  sim.prescribe_force(
      "all", VectorTimeFunction<3>::along(Vec3(1, 1, 0), TimeFunction::constant(F)).active(t1, t2));
  sim.steps(1000); // t = 1000 dt > t2
  const auto i = sim.index_of(id);
  const double v = F * (t2 - t1) / m / std::sqrt(2.0);
  CHECK(sim.particles().velocity[i].x() == approx(v).epsilon(1e-12));
  CHECK(sim.particles().velocity[i].y() == approx(v).epsilon(1e-12));
  CHECK(sim.particles().velocity[i].z() == 0.0);
}

// ------------------------------------------------------------------------------------------------
// 2. prescribed torques
// ------------------------------------------------------------------------------------------------

TEST_CASE("conditions: prescribed torque spins a sphere and a disk at T t / I") {
  const double dt = 1e-5;
  const long n = 10000;
  SUBCASE("sphere") {
    // omega = T t / I, I = 2/5 m R^2; the orientation is the rotation by |T| t^2/(2 I) about
    // T/|T| (velocity Verlet is exact for a constant rate). Tolerance: round-off of 1e4 steps,
    // 1e-12 on omega, 1e-10 rad on the orientation (1e4 quaternion products).
    auto sim = make<Sim3<>>(dt);
    const auto k = sim.add_material(grain_material());
    const auto id = sim.add_particle({.position = {0, 0, 0}, .radius = R, .material = k});
    const Vec3 T(2e-5, -1e-5, 3e-5);
    sim.prescribe_torque("all", T);
    sim.steps(n);
    const double t = sim.time(), I = sphere_inertia();
    const auto i = sim.index_of(id);
    for (int d = 0; d < 3; ++d)
      CHECK(sim.particles().omega[i][d] == approx(T[d] * t / I).epsilon(1e-12));
    const Eigen::Quaterniond q_exact(
        Eigen::AngleAxisd(T.norm() * t * t / (2.0 * I), T.normalized()));
    const double err = sim.particles().orientation[i].angularDistance(q_exact);
    CHECK(err <= 1e-10);
    CHECK(T.norm() * t * t / (2.0 * I) > 0.1); // the rotation is large enough to be seen
    CHECK(sim.particles().velocity[i].norm() == 0.0);
  }
  SUBCASE("disk") {
    // 2D disk of unit thickness: I = 1/2 m R^2, omega = T t / I, angle = T t^2 / (2 I).
    auto sim = make<Sim2<>>(dt);
    const auto k = sim.add_material(grain_material());
    const auto id = sim.add_particle({.position = {0, 0}, .radius = R, .material = k});
    const double T = 1e-3;
    sim.prescribe_torque("all", TimeFunction::constant(T));
    sim.steps(n);
    const double t = sim.time(), I = disk_inertia();
    const auto i = sim.index_of(id);
    CHECK(sim.particles().omega[i] == approx(T * t / I).epsilon(1e-12));
    CHECK(sim.particles().orientation[i] == approx(T * t * t / (2.0 * I)).epsilon(1e-10));
  }
}

// A prescribed torque spins the particle whatever the contact law, also with a contact without
// tangential or rolling model (Contact::has_torque == false).
TEST_CASE("conditions: prescribed torque without a torque-producing contact model") {
  using Frictionless = Interaction<normal::Hertz<>>;
  static_assert(!Frictionless::has_torque);
  typename Simulation<Sphere, search::CellList, Frictionless>::Params p;
  p.time_step = 1e-5;
  Simulation<Sphere, search::CellList, Frictionless> sim(p);
  const auto k = sim.add_material(grain_material());
  const auto id = sim.add_particle({.position = {0, 0, 0}, .radius = R, .material = k});
  const Vec3 T(0, 0, 2e-5);
  sim.prescribe_torque("all", T);
  sim.steps(1000);
  // omega = T t / I exactly (constant rate); tolerance: round-off, 1e-12
  CHECK(sim.particles().omega[sim.index_of(id)].z() ==
        approx(T.z() * sim.time() / sphere_inertia()).epsilon(1e-12));
}

// Rotational damping acts on whatever spins: with a contact model that makes no torque, a
// prescribed torque T against the damping torque -c_r omega levels off at omega = T / c_r
// (omega = T/c_r (1 - exp(-c_r t / I))), for the integrator with the fused pass and the one
// without, and with mass-proportional damping (c = I d_w) as well.
TEST_CASE_TEMPLATE("conditions: rotational damping without a torque-producing contact model",
                   Integrator, integrate::VelocityVerletHalfStep, integrate::SymplecticEuler) {
  using Frictionless = Interaction<normal::Hertz<>>;
  using S = Simulation<Sphere, search::CellList, Frictionless, Integrator>;
  const double I = sphere_inertia(), T = 2e-5, c = 200.0 * I; // time constant I / c = 5 ms
  for (bool mass_proportional : {false, true}) {
    typename S::Params p;
    p.time_step = 1e-5;
    if (!mass_proportional) p.damping_rotational = c;
    S sim(p);
    const auto k = sim.add_material(grain_material());
    const auto id = sim.add_particle({.position = {0, 0, 0}, .radius = R, .material = k});
    if (mass_proportional) sim.set_mass_damping(Vec3(Vec3::Zero()), Vec3(Vec3::Constant(c / I)));
    sim.prescribe_torque("all", Vec3(0, 0, T));
    sim.run(0.02); // four time constants
    const double t = sim.time();
    // tolerance: the schemes' O(dt/tau) = 2e-3 error on the transient
    CHECK(sim.particles().omega[sim.index_of(id)].z() ==
          approx(T / c * (1.0 - std::exp(-c * t / I))).epsilon(5e-3));
  }
}

// ------------------------------------------------------------------------------------------------
// 3. thermal conditions
// ------------------------------------------------------------------------------------------------

TEST_CASE("conditions: prescribed heat rate and heat flux heat an isolated particle") {
  // C dT/dt = Q: T = T0 + Q t / C with C = m c; a heat flux q gives Q = q S, S = 4 pi R^2 (a
  // sphere), 2 pi R L (a disk of thickness L = 1). Forward Euler is exact for a constant Q.
  // The rates are scaled by 1 s / dt so that the rise over the 1e3 steps is of order 1e2 K in
  // both analyses; tolerance: round-off of 1e3 increments to T ~ 7e2 K, 1e3 x 1.1e-16 x 7e2 /
  // 1e2 ~ 1e-12 of the rise, so 1e-11 relative.
  // A rate active in [t1, t2] (half-way between step ends) adds exactly Q (t2 - t1) / C, in a
  // thermal analysis (rate at the start of each step) and a thermo-mechanical one (velocity
  // Verlet: at the end of each step) alike.
  for (const Analysis analysis : {Analysis::thermal, Analysis::thermo_mechanical}) {
    CAPTURE(static_cast<int>(analysis));
    const double dt = analysis == Analysis::thermal ? 1.0 : 1e-5;
    const long n = 1000;
    const double f = 1.0 / dt; // rate scale [1/s]
    const double T0 = 300.0, Q = 2.0 * f, q = 500.0 * f, Qall = 1.0 * f, Qwin = 3.0 * f;
    const double t1 = 200.5 * dt, t2 = 700.5 * dt;
    {
      Sim3T::Params p;
      p.time_step = dt;
      p.analysis = analysis;
      p.initial_temperature = T0;
      Sim3T sim(p);
      const auto k = sim.add_material(grain_material());
      const auto a = sim.add_particle({.position = {0, 0, 0}, .radius = R, .material = k});
      const auto b = sim.add_particle({.position = {0.5, 0, 0}, .radius = R, .material = k});
      sim.add_group("a", {a});
      sim.add_group("b", {b});
      sim.prescribe_heat_rate("a", Q);
      sim.prescribe_heat_flux("b", q);
      sim.prescribe_heat_rate("all", Qall); // summed with the others
      sim.prescribe_heat_rate("b", TimeFunction::constant(Qwin).active(t1, t2));
      sim.steps(n);
      const double t = sim.time(), C = sphere_mass() * cap;
      const auto& T = sim.particles().temperature;
      CHECK(T[sim.index_of(a)] - T0 == approx((Q + Qall) * t / C).epsilon(1e-11));
      CHECK(T[sim.index_of(b)] - T0 ==
            approx(((q * 4.0 * pi * R * R + Qall) * t + Qwin * (t2 - t1)) / C).epsilon(1e-11));
    }
    {
      Sim2T::Params p;
      p.time_step = dt;
      p.analysis = analysis;
      p.initial_temperature = T0;
      Sim2T sim(p);
      const auto k = sim.add_material(grain_material());
      const auto id = sim.add_particle({.position = {0, 0}, .radius = R, .material = k});
      sim.prescribe_heat_flux("all", q);
      sim.steps(n);
      const double C = disk_mass() * cap;
      CHECK(sim.particles().temperature[sim.index_of(id)] - T0 ==
            approx(q * 2.0 * pi * R * 1.0 * sim.time() / C).epsilon(1e-11));
    }
  }
}

TEST_CASE("conditions: heat rates and forces that depend on temperature and speed") {
  // The first seed's prescribed conditions with temperature or speed as independent variable.
  // (1) Q(T) = h (T_inf - T) (a linear function of T: 0 - h (T - T_inf)) on an isolated sphere,
  // thermal analysis: forward Euler gives T_n - T_inf = (T0 - T_inf)(1 - h dt/C)^n exactly
  // (round-off, 1e-11 of the initial difference), and the continuous solution
  // exp(-h t/C) within the scheme's truncation, n (h dt/C)^2/2 = 7e-4 of it (tolerance 1e-3).
  // (2) A radiative heat flux q(T) = eps sigma (T_e^4 - T^4) as a callable of T: C dT/dt =
  // -K' (T^4 - a^4) with K' = eps sigma S, whose solution gives the time to reach T as
  // t = [G(T0) - G(T)] C / K', G(T) = (ln((T - a)/(T + a)) - 2 atan(T/a)) / (4 a^3). Cooling
  // from 1000 K towards a = 500 K for 80 s in steps of 0.01 s (the radiative time constant
  // C / (4 K' T^3) is 37 s at 1000 K): forward Euler's time error is about dt/2 over the run,
  // 1e-4 relative (tolerance 1e-3).
  // (3) A drag force F = -c |v| along x as a function of speed, on a sphere moving along +x:
  // v = v0 exp(-c t/m); velocity Verlet with the force of the half-step velocity, c dt/m = 1e-3,
  // follows it to about (c dt / m) x (c t / m) = 1e-3 of v0 after 0.5 s (tolerance 2e-3).
  const double C = sphere_mass() * cap;
  // a sphere alone at T0, thermal analysis with step dt
  auto isolated_sphere = [](double dt, double T0) {
    Sim3T::Params p;
    p.time_step = dt;
    p.analysis = Analysis::thermal;
    p.initial_temperature = T0;
    Sim3T sim(p);
    const auto k = sim.add_material(grain_material());
    sim.add_particle({.position = {0, 0, 0}, .radius = R, .material = k});
    return sim;
  };
  {
    const double h = 0.01, T_inf = 350.0, T0 = 300.0, dt = 1.0;
    const long n = 1000;
    Sim3T sim = isolated_sphere(dt, T0);
    sim.prescribe_heat_rate("all", TimeFunction::linear(0.0, -h, T_inf), Variable::temperature);
    sim.steps(n);
    const double T = sim.particles().temperature[0];
    const double discrete = T_inf + (T0 - T_inf) * std::pow(1.0 - h * dt / C, n);
    const double exact = T_inf + (T0 - T_inf) * std::exp(-h * sim.time() / C);
    CHECK(std::abs(T - discrete) < 1e-11 * std::abs(T0 - T_inf));
    CHECK(std::abs(T - exact) < 1e-3 * std::abs(T0 - T_inf));
    MESSAGE("Q(T) = h (T_inf - T): T = " << T << " K, closed form " << exact << " K");
  }
  {
    const double eps = 0.8, sigma = 5.670374419e-8, a = 500.0, T0 = 1000.0, dt = 0.01;
    const long n = 8000;
    Sim3T sim = isolated_sphere(dt, T0);
    sim.prescribe_heat_flux("all", TimeFunction::callable([&](double T) {
                              return eps * sigma * (std::pow(a, 4) - std::pow(T, 4));
                            }),
                            Variable::temperature);
    sim.steps(n);
    const double T = sim.particles().temperature[0];
    auto G = [&](double x) {
      return (std::log((x - a) / (x + a)) - 2.0 * std::atan(x / a)) / (4.0 * a * a * a);
    };
    const double Kp = eps * sigma * 4.0 * pi * R * R;
    const double t_closed = (G(T0) - G(T)) * C / Kp;
    REQUIRE(T < 800.0);
    CHECK(t_closed == approx(sim.time()).epsilon(1e-3));
    MESSAGE("radiative cooling to " << T << " K: closed-form time " << t_closed << " s, run "
                                    << sim.time() << " s");
  }
  {
    const double c = 0.02, v0 = 0.2, dt = 5e-4, m = sphere_mass();
    auto sim = make<Sim3<>>(dt);
    const auto k = sim.add_material(grain_material());
    sim.add_particle({.position = {0, 0, 0}, .radius = R, .material = k, .velocity = {v0, 0, 0}});
    sim.prescribe_force("all",
                        VectorTimeFunction<3>::along(Vec3::UnitX(), TimeFunction::linear(0.0, -c)),
                        Variable::speed);
    sim.steps(1000);
    const double v = sim.particles().velocity[0][0];
    const double exact = v0 * std::exp(-c * sim.time() / m);
    CHECK(std::abs(v - exact) < 2e-3 * v0);
    MESSAGE("drag of speed: v = " << v << " m/s, closed form " << exact << " m/s");
    // temperature needs a thermal state
    auto mech = make<Sim3<>>(dt);
    mech.add_material(grain_material());
    CHECK_THROWS_WITH_AS(mech.prescribe_force("all", Vec3(1, 0, 0), Variable::temperature),
                         doctest::Contains("prescribe_force (group 'all'): of = temperature is "
                                           "invalid without a conduction model"),
                         InputError);
  }
}

TEST_CASE("conditions: fixed temperatures at both ends of a row of three particles") {
  // Three equal spheres in a row, overlaps delta = 1e-4 m, thermal analysis. The ends are held
  // at T1 and T2 by fix_temperature on two groups; the middle obeys C dT/dt = H (T1 - T) +
  // H (T2 - T), so forward Euler gives T_n - Ts = (T_0 - Ts) (1 - 2 H dt / C)^n with the
  // steady temperature Ts = (T1 + T2)/2. Batchelor-O'Brien with the Hertz contact radius:
  // H = 4 k* a = 2 k a, a = sqrt(R* delta), R* = R/2.
  // Tolerances: round-off (1e-12 relative) for the recursion; 1e-9 K for the steady state
  // (0.7^200 ~ 1e-31 of the initial 100 K is left).
  const double delta = 1e-4, k = 1.0;
  const double H = 2.0 * k * std::sqrt(0.5 * R * delta);
  const double C = sphere_mass() * cap;
  const double dt = 0.3 * C / (2.0 * H); // 1 - 2 H dt / C = 0.7
  const double T1 = 400.0, T2 = 300.0, T0 = 250.0, Ts = 0.5 * (T1 + T2);

  Sim3T::Params p;
  p.time_step = dt;
  p.analysis = Analysis::thermal;
  Sim3T sim(p);
  const auto m = sim.add_material(grain_material());
  const double s = 2.0 * R - delta;
  const auto left =
      sim.add_particle({.position = {0, 0, 0}, .radius = R, .material = m, .temperature = T0});
  const auto mid =
      sim.add_particle({.position = {s, 0, 0}, .radius = R, .material = m, .temperature = T0});
  const auto right =
      sim.add_particle({.position = {2 * s, 0, 0}, .radius = R, .material = m, .temperature = T0});
  sim.add_group("hot", {left});
  sim.add_group("cold", {right});
  sim.fix_temperature("hot", T1);
  sim.fix_temperature("cold", T2);
  sim.initialize();
  int contacts = 0;
  sim.for_each_conductance([&](std::size_t, std::size_t, bool wall, double h) {
    CHECK_FALSE(wall);
    CHECK(h == approx(H).epsilon(1e-12));
    ++contacts;
  });
  CHECK(contacts == 2);
  auto T = [&](std::int64_t id) { return sim.particles().temperature[sim.index_of(id)]; };
  // fixed before the first step
  CHECK(T(left) == T1);
  CHECK(T(right) == T2);
  sim.steps(10);
  CHECK(T(mid) - Ts == approx((T0 - Ts) * std::pow(1.0 - 2.0 * H * dt / C, 10.0)).epsilon(1e-12));
  sim.steps(190);
  CHECK(std::abs(T(mid) - Ts) <= 1e-9);
  CHECK(T(left) == T1);
  CHECK(T(right) == T2);
}

TEST_CASE("conditions: a wall in a group with fixed temperature") {
  // A sphere resting on a plane (overlap 1e-4 m) whose group has a fixed temperature Tw: the
  // wall, insulated before, conducts at Tw and the particle relaxes as
  // T_n - Tw = (T_0 - Tw)(1 - H dt / C)^n (forward Euler, thermal analysis; H read from the
  // simulation). A second plane, far away, follows a ramp Tw2(t) = 300 + 2 t exactly.
  // Tolerances: round-off, 1e-12 relative.
  const double delta = 1e-4, C = sphere_mass() * cap, Tw = 400.0, T0 = 300.0;
  auto build = [&](double dt) {
    Sim3T::Params p;
    p.time_step = dt;
    p.analysis = Analysis::thermal;
    p.initial_temperature = T0;
    Sim3T sim(p);
    const auto m = sim.add_material(grain_material());
    sim.add_wall(walls::Plane{.point = {0, 0, 0}, .normal = {0, 0, 1}},
                 {.name = "floor", .material = m});
    sim.add_wall(walls::Plane{.point = {0, 0, 1}, .normal = {0, 0, -1}},
                 {.name = "lid", .material = m});
    sim.add_particle({.position = {0, 0, R - delta}, .radius = R, .material = m});
    sim.add_group("floor", {}, {0});
    sim.add_group("lid", {}, {1});
    return sim;
  };
  // conductance of the particle-wall contact
  double H = 0.0;
  {
    auto sim = build(1.0);
    sim.fix_temperature("floor", Tw);
    sim.initialize();
    sim.for_each_conductance([&](std::size_t, std::size_t w, bool wall, double h) {
      CHECK(wall);
      CHECK(w == 0);
      H = h;
    });
    // Batchelor-O'Brien, H = 4 k* a, k* = k/2 for two equal conductivities, a = sqrt(R delta)
    // (Hertz contact radius with a flat wall); round-off tolerance
    CHECK(H == approx(4.0 * 0.5 * std::sqrt(R * delta)).epsilon(1e-12));
    REQUIRE(H > 0);
  }
  const double dt = 0.5 * C / H; // 1 - H dt / C = 0.5
  auto sim = build(dt);
  sim.fix_temperature("floor", Tw);
  sim.fix_temperature("lid", TimeFunction::linear(300.0, 2.0));
  sim.steps(20);
  CHECK(sim.walls()[0].temperature == Tw);
  CHECK(sim.walls()[1].temperature == approx(300.0 + 2.0 * sim.time()).epsilon(1e-12));
  CHECK(sim.particles().temperature[0] - Tw ==
        approx((T0 - Tw) * std::pow(1.0 - H * dt / C, 20.0)).epsilon(1e-12));
}

// fix_temperature on a wall of a thermal analysis that is already running: the wall starts to
// conduct (the simulation initialises again, with the conductances of the wall).
TEST_CASE("conditions: fixing a wall temperature during a thermal analysis") {
  // Same set-up as above: after 5 steps on an insulated wall (T stays T0 exactly) the wall is
  // fixed at Tw; then T_n - Tw = (T0 - Tw)(1 - H dt / C)^n, round-off tolerance 1e-12.
  const double delta = 1e-4, C = sphere_mass() * cap, Tw = 400.0, T0 = 300.0;
  const double H = 4.0 * (0.5 * 1.0) * std::sqrt(R * delta); // 4 k* a, k* = k/2, a = sqrt(R delta)
  const double dt = 0.5 * C / H;
  Sim3T::Params p;
  p.time_step = dt;
  p.analysis = Analysis::thermal;
  p.initial_temperature = T0;
  Sim3T sim(p);
  const auto m = sim.add_material(grain_material());
  sim.add_wall(walls::Plane{.point = {0, 0, 0}, .normal = {0, 0, 1}},
               {.name = "floor", .material = m});
  sim.add_particle({.position = {0, 0, R - delta}, .radius = R, .material = m});
  sim.add_group("floor", {}, {0});
  sim.steps(5);
  CHECK(sim.particles().temperature[0] == T0);
  sim.fix_temperature("floor", Tw);
  sim.steps(10);
  CHECK(sim.particles().temperature[0] - Tw ==
        approx((T0 - Tw) * std::pow(1.0 - H * dt / C, 10.0)).epsilon(1e-12));
}

// ------------------------------------------------------------------------------------------------
// 4. prescribed motion
// ------------------------------------------------------------------------------------------------

TEST_CASE_TEMPLATE("conditions: prescribed velocity ramp (vv) overrides gravity", I,
                   GRAIN_ALL_INTEGRATORS) {
  // v(t) = (a t, 0, 0) prescribed with gravity (0, 0, -9.81): over a step the particle moves by
  // dt v(t + dt/2), the midpoint rule, exact for a linear v: x = a t^2 / 2, z unchanged, and
  // v = (a t, 0, 0) at the end. A second, free particle feels gravity (and makes the cell list
  // re-sort at rebuilds). Tolerance: round-off of 1e4 increments, 1e-12 relative; z and the
  // transverse velocities exactly.
  const double dt = 1e-5, a = 2.0, g = 9.81;
  auto sim = make<Sim3<I>>(dt);
  sim.set_gravity(Vec3(0, 0, -g));
  const auto k = sim.add_material(grain_material());
  const auto id = sim.add_particle({.position = {0, 0.3, 0.5}, .radius = R, .material = k});
  const auto other = sim.add_particle({.position = {0.5, 0, 0}, .radius = R, .material = k});
  sim.add_group("p", {id});
  sim.fix_velocity("p", VectorTimeFunction<3>(TimeFunction::linear(0.0, a), 0.0, 0.0));
  sim.steps(10000);
  const double t = sim.time();
  const auto i = sim.index_of(id);
  const auto& P = sim.particles();
  CHECK(P.position[i].x() == approx(a * t * t / 2).epsilon(1e-12));
  CHECK(P.position[i].y() == 0.3);
  CHECK(P.position[i].z() == 0.5);
  CHECK(P.velocity[i].x() == approx(a * t).epsilon(1e-12));
  CHECK(P.velocity[i].y() == 0.0);
  CHECK(P.velocity[i].z() == 0.0);
  // the free particle falls: v_z = -g t (every scheme exact in v for constant g)
  CHECK(P.velocity[sim.index_of(other)].z() == approx(-g * t).epsilon(1e-12));
}

TEST_CASE_TEMPLATE("conditions: prescribed acceleration with angular velocity (av) in 2D", I,
                   GRAIN_ALL_INTEGRATORS) {
  // linear acceleration a and angular velocity w prescribed, gravity (0, -9.81) overridden:
  // x = x0 + v0 t + a t^2 / 2, v = v0 + a t, angle = w t, omega = w (the update
  // x += dt (v_old + v_new)/2 is exact for a constant a). A second disk, free and fast, forces
  // neighbour-list rebuilds (which re-sort the particles) during the run.
  // Tolerance: round-off of 1e4 increments, 1e-12 relative.
  const double dt = 1e-5, w = 7.0;
  const Vec2 x0(0.01, -0.02), v0(0.5, 1.0), a(3.0, -2.0);
  auto sim = make<Sim2<I>>(dt);
  sim.set_gravity(Vec2(0, -9.81));
  const auto k = sim.add_material(grain_material());
  const auto id = sim.add_particle({.position = x0, .radius = R, .material = k, .velocity = v0});
  sim.add_particle({.position = {0.5, 0.5}, .radius = R, .material = k, .velocity = {-1.0, 0.0}});
  sim.add_group("p", {id});
  sim.prescribe_motion("p", VectorTimeFunction<2>(a), TimeFunction::constant(w), "av");
  sim.steps(10000);
  REQUIRE(sim.counters().rebuilds > 5); // the re-sorting rebuilds did happen
  const double t = sim.time();
  const auto i = sim.index_of(id);
  const auto& P = sim.particles();
  for (int d = 0; d < 2; ++d) {
    CAPTURE(d);
    CHECK(P.position[i][d] == approx(x0[d] + v0[d] * t + 0.5 * a[d] * t * t).epsilon(1e-12));
    CHECK(P.velocity[i][d] == approx(v0[d] + a[d] * t).epsilon(1e-12));
  }
  CHECK(P.orientation[i] == approx(w * t).epsilon(1e-12));
  CHECK(P.omega[i] == approx(w).epsilon(1e-15));
}

TEST_CASE_TEMPLATE("conditions: a particle with prescribed velocity pushes into a fixed particle",
                   I, GRAIN_ALL_INTEGRATORS) {
  // Sphere A moves at v = 0.1 m/s (fix_velocity) into sphere B (fixed = true), 1 mm away, for
  // 2 mm: the contact (overlap up to 1 mm, a Hertz force of order 10 N on 10 g) does not change
  // A's motion: x = v t, velocity v at the end of every step (round-off, 1e-12), and B stays
  // where it is, at rest (exactly). A moves more than half the skin (0.2 R), so the cell list
  // rebuilds (and re-sorts) during the push.
  const double dt = 1e-5, v = 0.1, gap = 1e-3;
  auto sim = make<Sim3<I>>(dt);
  sim.set_gravity(Vec3(0, 0, -9.81));
  const auto k = sim.add_material(grain_material());
  const auto a = sim.add_particle({.position = {0, 0, 0}, .radius = R, .material = k});
  const Vec3 xb(2 * R + gap, 0, 0);
  const auto b = sim.add_particle({.position = xb, .radius = R, .material = k, .fixed = true});
  sim.add_group("pusher", {a});
  sim.fix_velocity("pusher", Vec3(v, 0, 0));
  double worst = 0.0; // largest |v_A - v| after any step
  sim.steps(2000, [&](auto& s) {
    const Vec3 va = s.particles().velocity[s.index_of(a)];
    worst = std::max(worst, (va - Vec3(v, 0, 0)).norm());
  });
  const double t = sim.time();
  REQUIRE(sim.counters().rebuilds > 1);
  REQUIRE(sim.contact_counts().first == 1);
  CHECK(worst <= 1e-12 * v);
  double force = 0.0;
  sim.for_each_contact(
      [&](auto, auto, bool, const auto&, const auto& r) { force = r.force.norm(); });
  CHECK(force > 1.0); // N: the contact pushes back hard
  const auto& P = sim.particles();
  const auto ia = sim.index_of(a), ib = sim.index_of(b);
  CHECK(P.position[ia].x() == approx(v * t).epsilon(1e-12));
  CHECK(P.position[ia].y() == 0.0);
  CHECK(P.position[ia].z() == 0.0);
  CHECK(P.velocity[ia].x() == approx(v).epsilon(1e-12));
  CHECK(P.velocity[ia].y() == 0.0);
  CHECK(P.velocity[ia].z() == 0.0);
  CHECK(P.position[ib] == xb);
  CHECK(P.velocity[ib].norm() == 0.0);
}

// ------------------------------------------------------------------------------------------------
// 5. restraints
// ------------------------------------------------------------------------------------------------

TEST_CASE("conditions: each component of a prescribed velocity follows its own interval") {
  // fix_velocity (0, 0, -0.05 m/s while t <= 0.5 s) under gravity (0, 0, -g): x and y are held
  // at 0 throughout; z moves at -0.05 m/s until 0.5 s and then falls freely from that velocity:
  // v_z = -0.05 - g (t - 0.5), z = z0 - 0.025 - 0.05 (t - 0.5) - g (t - 0.5)^2 / 2. A second
  // particle has its x angular velocity held at 2 rad/s until 0.5 s under a torque (T, 0, 0),
  // then spins up freely: omega_x = 2 + T (t - 0.5) / I. Velocity Verlet is exact for constant
  // loads: tolerance 1e-9 relative (round-off of 1e4 steps).
  const double dt = 1e-4, g = 9.81, T = 1e-6;
  auto sim = make<Sim3<>>(dt);
  sim.set_gravity(Vec3(0, 0, -g));
  const auto k = sim.add_material(grain_material());
  const Vec3 x0(0.0, 0.0, 1.0);
  const auto a = sim.add_particle({.position = x0, .radius = R, .material = k});
  const auto b = sim.add_particle({.position = {0.5, 0, 0}, .radius = R, .material = k});
  sim.add_group("a", {a});
  sim.add_group("b", {b});
  sim.fix_velocity("a",
                   VectorTimeFunction<3>(0.0, 0.0, TimeFunction::constant(-0.05).active(0, 0.5)));
  sim.fix_omega("b", VectorTimeFunction<3>(TimeFunction::constant(2.0).active(0, 0.5), 0.0, 0.0));
  sim.prescribe_torque("b", Vec3(T, 0, 0));
  sim.steps(10000);
  const double t = sim.time(), s = t - 0.5;
  const auto& P = sim.particles();
  const auto i = sim.index_of(a);
  CHECK(P.position[i].x() == 0.0);
  CHECK(P.position[i].y() == 0.0);
  CHECK(P.velocity[i].x() == 0.0);
  CHECK(P.velocity[i].y() == 0.0);
  CHECK(P.velocity[i].z() == approx(-0.05 - g * s).epsilon(1e-9));
  CHECK(P.position[i].z() == approx(x0.z() - 0.025 - 0.05 * s - g * s * s / 2).epsilon(1e-9));
  const auto j = sim.index_of(b);
  CHECK(P.omega[j].x() == approx(2.0 + T * s / sphere_inertia()).epsilon(1e-9));
  CHECK(P.omega[j].y() == 0.0);
  CHECK(P.omega[j].z() == 0.0);
  CHECK(P.velocity[j].z() == approx(-g * t).epsilon(1e-9)); // b's linear motion is free
}

TEST_CASE("conditions: a restraint added between runs holds from the first step after it") {
  // a sphere falls under gravity (1, 0, -9.81) for 100 steps; z is then restrained: z and v_z
  // stay exactly where the first run left them (the loads of the last evaluation, used by the
  // next first half kick, lose their z component too), x keeps accelerating.
  const double dt = 1e-4;
  auto sim = make<Sim3<>>(dt);
  sim.set_gravity(Vec3(1.0, 0.0, -9.81));
  const auto k = sim.add_material(grain_material());
  const auto id = sim.add_particle({.position = {0, 0, 1}, .radius = R, .material = k});
  sim.steps(100);
  const double z1 = sim.particles().position[sim.index_of(id)].z();
  sim.restrain("all", {Vec3::UnitZ()});
  sim.steps(100);
  const auto i = sim.index_of(id);
  CHECK(sim.particles().position[i].z() == z1);
  CHECK(sim.particles().velocity[i].z() == 0.0);
  CHECK(sim.particles().position[i].x() == approx(0.5 * sim.time() * sim.time()).epsilon(1e-9));
}

TEST_CASE("conditions: restraints remove motion along the restrained directions") {
  const double dt = 1e-5;
  const long n = 10000;
  const Vec3 g(1.0, 0.0, -9.81);
  SUBCASE("z restrained under gravity (1, 0, -9.81)") {
    // x = t^2/2 (velocity Verlet exact for a constant force; tolerance 1e-9 relative), z and
    // v_z unchanged exactly.
    auto sim = make<Sim3<>>(dt);
    sim.set_gravity(g);
    const auto k = sim.add_material(grain_material());
    const auto id = sim.add_particle({.position = {0, 0, 0.2},
                                      .radius = R,
                                      .material = k,
                                      .velocity = {0, 0, 0.3}}); // v_z removed by the restraint
    sim.restrain("all", {Vec3::UnitZ()});
    sim.steps(n);
    const double t = sim.time();
    const auto i = sim.index_of(id);
    CHECK(sim.particles().position[i].x() == approx(t * t / 2).epsilon(1e-9));
    CHECK(sim.particles().position[i].y() == 0.0);
    CHECK(sim.particles().position[i].z() == 0.2);
    CHECK(sim.particles().velocity[i].z() == 0.0);
  }
  SUBCASE("oblique restraint") {
    // restrained u = (1, 0, 1)/sqrt(2): acceleration g - (g.u) u, position x0 + that t^2/2
    // (1e-9 relative), displacement along u 0 within round-off: 1e4 projections of rounding
    // 1e-16 |v| dt each, bounded by 1e-13 m.
    auto sim = make<Sim3<>>(dt);
    sim.set_gravity(g);
    const auto k = sim.add_material(grain_material());
    const Vec3 x0(0.1, 0.2, 0.3);
    const auto id = sim.add_particle({.position = x0, .radius = R, .material = k});
    const Vec3 u = Vec3(1, 0, 1).normalized();
    sim.restrain("all", {Vec3(1, 0, 1)});
    sim.steps(n);
    const double t = sim.time();
    const Vec3 dx = sim.particles().position[sim.index_of(id)] - x0;
    const Vec3 ae = g - g.dot(u) * u;
    CHECK(dx.x() == approx(ae.x() * t * t / 2).epsilon(1e-9));
    CHECK(dx.z() == approx(ae.z() * t * t / 2).epsilon(1e-9));
    CHECK(std::abs(dx.y()) == 0.0);
    CHECK(std::abs(dx.dot(u)) <= 1e-13);
  }
  SUBCASE("rotation restrained under a prescribed torque (3D)") {
    // torque (T, 0, T) with the z rotation restrained: omega = (T t / I, 0, 0), omega_z = 0
    // exactly. Tolerance: round-off, 1e-12.
    auto sim = make<Sim3<>>(dt);
    const auto k = sim.add_material(grain_material());
    const auto id =
        sim.add_particle({.position = {0, 0, 0}, .radius = R, .material = k, .omega = {0, 0, 5.0}});
    const double T = 2e-5;
    sim.prescribe_torque("all", Vec3(T, 0, T));
    sim.restrain("all", {}, {Vec3::UnitZ()});
    sim.steps(n);
    const Vec3 w = sim.particles().omega[sim.index_of(id)];
    CHECK(w.x() == approx(T * sim.time() / sphere_inertia()).epsilon(1e-12));
    CHECK(w.y() == 0.0);
    CHECK(w.z() == 0.0);
  }
  SUBCASE("rotation restrained under a prescribed torque (2D)") {
    auto sim = make<Sim2<>>(dt);
    const auto k = sim.add_material(grain_material());
    const auto id = sim.add_particle({.position = {0, 0}, .radius = R, .material = k});
    sim.prescribe_torque("all", TimeFunction::constant(1e-3));
    sim.restrain("all", {}, {1.0});
    sim.steps(n);
    CHECK(sim.particles().omega[sim.index_of(id)] == 0.0);
    CHECK(sim.particles().orientation[sim.index_of(id)] == 0.0);
  }
}

// ------------------------------------------------------------------------------------------------
// 6. time-dependent gravity, damping
// ------------------------------------------------------------------------------------------------

TEST_CASE("conditions: time-dependent gravity") {
  // g_z(t) = g0 + s t: v_z = g0 t + s t^2 / 2 (velocity Verlet: trapezoidal rule of the
  // end-of-step values, exact for a linear g); g_x = 2 m/s^2 active in [t1, t2] (half-way
  // between step ends): v_x = 2 (t2 - t1). Tolerance: round-off, 1e-12 relative.
  const double dt = 1e-5, g0 = -9.81, s = -50.0;
  const double t1 = 1000.5 * dt, t2 = 3000.5 * dt;
  auto sim = make<Sim3<>>(dt);
  const auto k = sim.add_material(grain_material());
  const auto id = sim.add_particle({.position = {0, 0, 0}, .radius = R, .material = k});
  sim.set_gravity(VectorTimeFunction<3>(TimeFunction::constant(2.0).active(t1, t2), 0.0,
                                        TimeFunction::linear(g0, s)));
  sim.steps(5000);
  const double t = sim.time();
  const auto i = sim.index_of(id);
  CHECK(sim.particles().velocity[i].z() == approx(g0 * t + s * t * t / 2).epsilon(1e-12));
  CHECK(sim.particles().velocity[i].x() == approx(2.0 * (t2 - t1)).epsilon(1e-12));
  CHECK(sim.particles().velocity[i].y() == 0.0);
  // the gravity of the last force evaluation (at t, velocity Verlet)
  CHECK(sim.gravity().z() == approx(g0 + s * t).epsilon(1e-12));
}

TEST_CASE("conditions: global damping and mass-proportional damping") {
  // set_damping(c_t, c_r): m dv/dt = -c_t v, I dw/dt = -c_r w: v = v0 exp(-c_t t / m),
  // w = w0 exp(-c_r t / I). set_mass_damping(d, d_w): dv_k/dt = -d_k v_k per component.
  // Velocity Verlet, whose forces see the predicted velocity v(n+1/2) + a(n) dt/2, multiplies
  // v by 1 - h + h^2/2 + h^3/4 per step (h = k dt; the dominant eigenvalue of the two-step
  // recursion), against exp(-h) = 1 - h + h^2/2 - h^3/6: relative error (5/12) k t (k dt)^2
  // after t. Tolerance tol(k) = k t (k dt)^2 (2.4 times that): 1e-8 .. 2.7e-7 for k = 10 .. 30
  // 1/s, dt = 1e-5, t = 0.1 s. An undamped component stays exactly constant.
  const double dt = 1e-5;
  const long n = 10000; // t = 0.1 s
  const Vec3 v0(1.0, -2.0, 0.5), w0(3.0, 0.0, -4.0);
  const double tf = n * dt;
  auto tol = [&](double k) { return k * tf * (k * dt) * (k * dt); };
  SUBCASE("set_damping") {
    auto sim = make<Sim3<>>(dt);
    const auto k = sim.add_material(grain_material());
    const auto id = sim.add_particle(
        {.position = {0, 0, 0}, .radius = R, .material = k, .velocity = v0, .omega = w0});
    const double kt = 10.0, kr = 20.0; // 1/s
    sim.set_damping(TimeFunction::constant(kt * sphere_mass()),
                    TimeFunction::constant(kr * sphere_inertia()));
    sim.steps(n);
    const double t = sim.time();
    const auto i = sim.index_of(id);
    for (int d = 0; d < 3; ++d) {
      CAPTURE(d);
      CHECK(sim.particles().velocity[i][d] == approx(v0[d] * std::exp(-kt * t)).epsilon(tol(kt)));
      if (w0[d] != 0.0)
        CHECK(sim.particles().omega[i][d] == approx(w0[d] * std::exp(-kr * t)).epsilon(tol(kr)));
      else
        CHECK(sim.particles().omega[i][d] == 0.0);
    }
    // position: x0 + v0 (1 - exp(-k t)) / k
    CHECK(sim.particles().position[i].x() ==
          approx(v0.x() * (1.0 - std::exp(-kt * t)) / kt).epsilon(tol(kt)));
    MESSAGE("set_damping: rel. error v_x "
            << rel(sim.particles().velocity[i].x(), v0.x() * std::exp(-kt * t)) << " (tol "
            << tol(kt) << "), omega_x "
            << rel(sim.particles().omega[i].x(), w0.x() * std::exp(-kr * t)) << " (tol " << tol(kr)
            << ")");
  }
  SUBCASE("set_mass_damping") {
    auto sim = make<Sim3<>>(dt);
    const auto k = sim.add_material(grain_material());
    const auto id = sim.add_particle(
        {.position = {0, 0, 0}, .radius = R, .material = k, .velocity = v0, .omega = w0});
    const Vec3 d(10.0, 20.0, 0.0), dw(0.0, 0.0, 30.0);
    sim.set_mass_damping(d, dw);
    sim.steps(n);
    const double t = sim.time();
    const auto i = sim.index_of(id);
    CHECK(sim.particles().velocity[i].x() ==
          approx(v0.x() * std::exp(-d.x() * t)).epsilon(tol(d.x())));
    CHECK(sim.particles().velocity[i].y() ==
          approx(v0.y() * std::exp(-d.y() * t)).epsilon(tol(d.y())));
    CHECK(sim.particles().velocity[i].z() == v0.z());
    CHECK(sim.particles().omega[i].x() == w0.x());
    CHECK(sim.particles().omega[i].z() ==
          approx(w0.z() * std::exp(-dw.z() * t)).epsilon(tol(dw.z())));
    MESSAGE("set_mass_damping: rel. error omega_z "
            << rel(sim.particles().omega[i].z(), w0.z() * std::exp(-dw.z() * t)) << " (tol "
            << tol(dw.z()) << ")");
  }
}

// ------------------------------------------------------------------------------------------------
// 7. walls with a fixed velocity
// ------------------------------------------------------------------------------------------------

TEST_CASE("conditions: a plane wall with an oscillatory fixed velocity") {
  // v_z(t) = A sin(2 pi t / P): the plane's point moves by the integral A/w (1 - cos(w t)),
  // w = 2 pi / P. Walls move by dt v(t + dt/2) per step (midpoint rule): relative error at most
  // (w dt)^2 / 24 = 1.6e-6 at t = P/4, where the displacement is A / w. Tolerance 1e-5; the
  // in-plane coordinates stay exactly 0 and the wall's velocity is v(t) (1e-12).
  const double dt = 1e-5, A = 0.05, P = 0.01, w = 2.0 * pi / P;
  auto sim = make<Sim3<>>(dt);
  const auto k = sim.add_material(grain_material());
  sim.add_wall(walls::Plane{.point = {0, 0, 0}, .normal = {0, 0, 1}},
               {.name = "piston", .material = k});
  sim.add_particle({.position = {0, 0, 0.5}, .radius = R, .material = k});
  sim.add_group("piston", {}, {0});
  sim.fix_velocity("piston", VectorTimeFunction<3>(0.0, 0.0, TimeFunction::oscillatory(0.0, A, P)));
  sim.steps(250); // t = P / 4
  const double t = sim.time();
  const auto& plane = std::get<walls::Plane>(sim.walls()[0].geometry);
  const double z_exact = A / w * (1.0 - std::cos(w * t));
  CHECK(plane.point.z() == approx(z_exact).epsilon(1e-5));
  CHECK(plane.point.x() == 0.0);
  CHECK(plane.point.y() == 0.0);
  CHECK(sim.walls()[0].options.velocity.z() == approx(A * std::sin(w * t)).epsilon(1e-12));
  MESSAGE("wall displacement: rel. error " << rel(plane.point.z(), z_exact) << " (tol 1e-5)");
  sim.steps(750); // a whole period: back to the start
  CHECK(std::abs(std::get<walls::Plane>(sim.walls()[0].geometry).point.z()) <= 1e-5 * A / w);
}

// ------------------------------------------------------------------------------------------------
// 8. groups
// ------------------------------------------------------------------------------------------------

TEST_CASE("conditions: groups follow particle ids through re-sorting") {
  // Two columns of spheres, at x = 0 (moving +z at 1 m/s) and x = 0.05 (moving -z), ten each,
  // 5 cm apart in z: they never touch, but pass each other in z, so the cell list (z-major cell
  // order) re-sorts them at its rebuilds. "low" = the spheres with z < 0 at the start gets a
  // prescribed force F along y; "high" (z > 0) a prescribed acceleration a along -y ("av").
  // After 1e4 steps (t = 0.1 s): low: v_y = F t / m, high: y = -a t^2 / 2, v_y = -a t, the
  // others 0, all exactly (round-off, 1e-12); group_indices name the original ids.
  const double dt = 1e-5, F = 1e-3, a = 5.0;
  auto sim = make<Sim3<>>(dt);
  const auto k = sim.add_material(grain_material());
  std::vector<std::int64_t> ids;
  // added in an order unrelated to the cell order
  for (int j = 0; j < 10; ++j)
    for (int c = 0; c < 2; ++c) {
      const double z = 0.05 * ((j * 7) % 10 - 4.5);
      ids.push_back(sim.add_particle({.position = {0.05 * c, 0, z},
                                      .radius = R,
                                      .material = k,
                                      .velocity = {0, 0, c == 0 ? 1.0 : -1.0}}));
    }
  std::set<std::int64_t> low, high;
  for (const auto id : ids) {
    const double z = sim.particles().position[sim.index_of(id)].z();
    (z < 0 ? low : high).insert(id);
  }
  sim.add_group_where("low", [](const Vec3& x, double) { return x.z() < 0; });
  sim.add_group_where("high", [](const Vec3& x, double r) { return x.z() > 0 && r == R; });
  auto ids_of = [&](const std::string& g) {
    std::set<std::int64_t> s;
    for (const auto i : sim.group_indices(g))
      s.insert(sim.particles().id[i]);
    return s;
  };
  CHECK(ids_of("low") == low);
  CHECK(ids_of("high") == high);
  CHECK(low.size() == 10);
  std::vector<std::size_t> index0;
  for (const auto id : ids)
    index0.push_back(sim.index_of(id));

  sim.prescribe_force("low", Vec3(0, F, 0));
  sim.prescribe_motion("high", VectorTimeFunction<3>(Vec3(0, -a, 0)), std::nullopt, "av");
  sim.steps(10000);
  const double t = sim.time();
  // precondition: rebuilds re-sorted the particles
  REQUIRE(sim.counters().rebuilds > 10);
  bool moved = false;
  for (std::size_t q = 0; q < ids.size(); ++q)
    moved = moved || sim.index_of(ids[q]) != index0[q];
  REQUIRE(moved);

  CHECK(ids_of("low") == low);
  CHECK(ids_of("high") == high);
  CHECK(ids_of("all").size() == ids.size());
  const auto& P = sim.particles();
  for (const auto id : ids) {
    CAPTURE(id);
    const auto i = sim.index_of(id);
    if (low.count(id)) {
      CHECK(P.velocity[i].y() == approx(F * t / sphere_mass()).epsilon(1e-12));
    } else {
      CHECK(P.velocity[i].y() == approx(-a * t).epsilon(1e-12));
      CHECK(P.position[i].y() == approx(-a * t * t / 2).epsilon(1e-12));
    }
    CHECK(std::abs(P.velocity[i].z()) == 1.0); // the columns keep their speed
  }
}

TEST_CASE("conditions: input errors name the offending value") {
  auto sim = make<Sim3<>>(1e-5);
  const auto k = sim.add_material(grain_material());
  const auto id = sim.add_particle({.position = {0, 0, -0.1}, .radius = R, .material = k});
  sim.add_particle({.position = {0, 0, 0.1}, .radius = R, .material = k});
  sim.add_wall(walls::Plane{}, {.material = k});
  sim.add_group_where("low", [](const Vec3& x, double) { return x.z() < 0; });
  CHECK(sim.group_indices("low").size() == 1);
  CHECK(sim.group("low").ids == std::vector<std::int64_t>{id});

  // unknown group: the message names the known groups
  CHECK_THROWS_WITH_AS(sim.prescribe_force("nope", Vec3(1, 0, 0)),
                       doctest::Contains("group = 'nope' is invalid; valid values: 'all', 'low'"),
                       InputError);
  CHECK_THROWS_WITH_AS(sim.set_velocity("nope", Vec3(1, 0, 0)), doctest::Contains("'nope'"),
                       InputError);
  // duplicate and reserved names
  CHECK_THROWS_WITH_AS(sim.add_group("low", {id}), doctest::Contains("name = 'low' is invalid"),
                       InputError);
  CHECK_THROWS_WITH_AS(sim.add_group("all", {}), doctest::Contains("name = 'all' is invalid"),
                       InputError);
  // unknown particle id and wall index
  CHECK_THROWS_WITH_AS(sim.add_group("x", {id, 42}),
                       doctest::Contains("particle id = 42 is invalid"), InputError);
  CHECK_THROWS_WITH_AS(sim.add_group("x", {}, {3}), doctest::Contains("wall = 3 is invalid"),
                       InputError);
  // a failed add_group adds nothing: "x" is still free
  CHECK_NOTHROW(sim.add_group("x", {id}));
  // prescribed motion kind
  CHECK_THROWS_WITH_AS(sim.prescribe_motion("low", Vec3(1, 0, 0), std::nullopt, "xy"),
                       doctest::Contains("kind = 'xy' is invalid"), InputError);
  CHECK_THROWS_WITH_AS(sim.prescribe_motion("low", Vec3(1, 0, 0), std::nullopt, "xy"),
                       doctest::Contains("prescribe_motion (group 'low')"), InputError);
  // dependent restraint directions
  CHECK_THROWS_WITH_AS(sim.restrain("low", {Vec3(1, 0, 0), Vec3(-2, 0, 0)}),
                       doctest::Contains("linearly dependent"), InputError);
  CHECK_THROWS_WITH_AS(sim.restrain("low", {}, {Vec3(0, 1, 1), Vec3(0, 2, 2)}),
                       doctest::Contains("angular directions are linearly dependent"), InputError);
  CHECK_THROWS_WITH_AS(sim.restrain("low", {Vec3(0, 0, 0)}),
                       doctest::Contains("direction |d| = 0 is invalid"), InputError);
  // walls take velocity histories only
  sim.add_group("floor", {}, {0});
  CHECK_THROWS_WITH_AS(sim.prescribe_motion("floor", Vec3(1, 0, 0), std::nullopt, "av"),
                       doctest::Contains("kind = 'av' is invalid for wall"), InputError);
}
