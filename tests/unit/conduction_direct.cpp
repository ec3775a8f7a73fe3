// Direct conduction (thermal pipe, collisional), contact-area corrections and convection
// correlations: closed forms, the collisional example of Sun & Chen / Zhou, Yu & Horio driven
// through an integrated Hertz impact, the physical targets of the area corrections, and the
// errors raised for bad parameters.
#include "../approx.hpp"
#include "../support/materials.hpp"
#include <algorithm>
#include <cmath>
#include <doctest/doctest.h>
#include <grain/grain.hpp>
#include <grain/models/area/lu_morris_li_benyahia.hpp>
#include <grain/models/area/morris_pannala_ma_hrenya.hpp>
#include <grain/models/area/zhou_yu_zulli.hpp>
#include <grain/models/conduction/batchelor_obrien.hpp>
#include <grain/models/conduction/collisional.hpp>
#include <grain/models/conduction/thermal_pipe.hpp>
#include <grain/models/convection/ranz_marshall.hpp>
#include <grain/models/convection/whitaker.hpp>
#include <limits>
#include <numbers>
#include <type_traits>

using namespace grain;

static_assert(ConductionModel<conduction::ThermalPipe> && conduction::ThermalPipe::thermal);
static_assert(ConductionModel<conduction::Collisional> && conduction::Collisional::thermal);
static_assert(!conducts_across_gaps<conduction::ThermalPipe> &&
              !conducts_across_gaps<conduction::Collisional>);
static_assert(AreaCorrectionModel<area::ZhouYuZulli> &&
              AreaCorrectionModel<area::LuMorrisLiBenyahia> &&
              AreaCorrectionModel<area::MorrisPannalaMaHrenya>);
static_assert(ConvectionModel<convection::RanzMarshall> && ConvectionModel<convection::Whitaker>);
static_assert(std::is_empty_v<conduction::ThermalPipe::History<3>> &&
              std::is_empty_v<area::ZhouYuZulli::History<3>> &&
              std::is_empty_v<area::LuMorrisLiBenyahia::History<2>> &&
              std::is_empty_v<area::MorrisPannalaMaHrenya::History<3>>);
static_assert(sizeof(conduction::Collisional::History<3>) == 3 * sizeof(double) &&
              sizeof(conduction::Collisional::History<2>) == 3 * sizeof(double));
static_assert(std::is_trivially_copyable_v<conduction::Collisional::History<3>>);

namespace {

constexpr double pi = std::numbers::pi;

// Glass-like spheres of verification.md 4.8: R = 1 mm, E = 70 GPa, nu = 0.25, rho = 2500,
// c = 800, k = 1.
using grain::test::glass;

double sphere_mass(double r, double rho) { return rho * 4.0 / 3.0 * pi * r * r * r; }

/// Geometry of two spheres (or a sphere and a flat wall if rj is infinite) with the given
/// overlap and normal velocity; only the fields the heat models read are set.
ContactGeometry<3> contact(double ri, double rj, double mi, double mj, double overlap, double vn) {
  ContactGeometry<3> g;
  g.normal = Vec3(1, 0, 0);
  g.overlap = overlap;
  g.normal_velocity = vn;
  g.radius_i = ri;
  g.radius_j = rj;
  g.wall = std::isinf(rj);
  g.r_eff = g.wall ? ri : ri * rj / (ri + rj);
  g.m_eff = g.wall ? mi : mi * mj / (mi + mj);
  g.distance = g.wall ? ri - overlap : ri + rj - overlap;
  return g;
}

HeatContext touching(double a, double distance, double dt = 0.0, double length = 0.0) {
  HeatContext c;
  c.touching = true;
  c.contact_radius = a;
  c.distance = distance;
  c.time_step = dt;
  c.length = length;
  return c;
}

} // namespace

// ---------------------------------------------------------------- thermal pipe

TEST_CASE("ThermalPipe: closed form for spheres, cylinders, unequal radii and conductivities") {
  using M = conduction::ThermalPipe;
  const double r = 1e-3, a = 1e-4;
  const double d = 2.0 * std::sqrt(r * r - a * a);
  M::History<3> h;
  M::Params p;
  Material m = glass();
  PairProperties pair = PairProperties::mix(m, m);
  const auto g = contact(r, r, 1e-5, 1e-5, 2 * r - d, 0.0);
  // equal spheres, k = 1: H = pi a^2 k / d = 1.5787097e-5 W/K (hand-computed, 8 digits)
  CHECK(M::conductance(g, pair, touching(a, d), p, h) ==
        grain::test::approx(1.5787097e-5).epsilon(1e-7));
  // the same exactly: H = A k / d (round-off, 1e-12)
  CHECK(M::conductance(g, pair, touching(a, d), p, h) ==
        grain::test::approx(pi * a * a * 1.0 / d).epsilon(1e-12));
  // cylinders of length L = 1 cm: A = 2 a L, H = 1.0050378e-3 W/K (hand-computed, 8 digits)
  CHECK(M::conductance(g, pair, touching(a, d, 0.0, 0.01), p, h) ==
        grain::test::approx(1.0050378e-3).epsilon(1e-7));
  // not touching: no conduction
  HeatContext gap = touching(a, d);
  gap.touching = false;
  CHECK(M::conductance(g, pair, gap, p, h) == 0.0);

  // R1 = 1 mm, k1 = 1 and R2 = 2 mm, k2 = 3: k_avg = 3e-3/(1e-3 + 2e-3/3) = 1.8 W/(m K),
  // d = sqrt(R1^2 - a^2) + sqrt(R2^2 - a^2), H = 1.8896887e-5 W/K (hand-computed, 8 digits)
  Material m2 = glass();
  m2.conductivity = 3.0;
  const PairProperties pair12 = PairProperties::mix(m, m2);
  const double d12 = std::sqrt(r * r - a * a) + std::sqrt(4 * r * r - a * a);
  const auto g12 = contact(r, 2 * r, 1e-5, 8e-5, 3 * r - d12, 0.0);
  const double h12 = M::conductance(g12, pair12, touching(a, d12), p, h);
  CHECK(h12 == grain::test::approx(1.8896887e-5).epsilon(1e-7));
  // equals the series resistance of two rods of lengths R_i, R_j scaled to d (round-off)
  CHECK(h12 ==
        grain::test::approx(pi * a * a / (r / 1.0 + 2 * r / 3.0) * (3 * r) / d12).epsilon(1e-12));
  // symmetric in the partners (round-off)
  const PairProperties pair21 = PairProperties::mix(m2, m);
  const auto g21 = contact(2 * r, r, 8e-5, 1e-5, 3 * r - d12, 0.0);
  CHECK(M::conductance(g21, pair21, touching(a, d12), p, h) ==
        grain::test::approx(h12).epsilon(1e-12));
  // an insulating partner conducts nothing
  Material ins = glass();
  ins.conductivity = 0.0;
  CHECK(M::conductance(g, PairProperties::mix(m, ins), touching(a, d), p, h) == 0.0);
}

TEST_CASE("ThermalPipe: particle-wall contact, image and isothermal forms") {
  using M = conduction::ThermalPipe;
  const double r = 1e-3, a = 1e-4;
  const double dw = std::sqrt(r * r - a * a); // centre-to-surface distance consistent with a
  const double inf = std::numeric_limits<double>::infinity();
  const auto gw = contact(r, inf, 1e-5, inf, r - dw, 0.0);
  M::History<3> h;
  Material m = glass(), wall = glass();
  wall.conductivity = 3.0;
  // image form: H = A k_p k_w / ((k_p + k_w) d) = pi a^2 0.75 / d = 2.3680646e-5 W/K
  // (hand-computed, 8 digits)
  CHECK(M::conductance(gw, PairProperties::mix(m, wall), touching(a, dw), M::Params{}, h) ==
        grain::test::approx(2.3680646e-5).epsilon(1e-7));
  // isothermal walls (the seed's form): H = A k_p / d = 3.1574194e-5 W/K (hand-computed)
  const M::Params iso{.isothermal_walls = true};
  CHECK(M::conductance(gw, PairProperties::mix(m, wall), touching(a, dw), iso, h) ==
        grain::test::approx(3.1574194e-5).epsilon(1e-7));
  // a wall of the particle's material conducts exactly like the mirror image particle
  // (round-off, 1e-12)
  const auto gp = contact(r, r, 1e-5, 1e-5, 2 * (r - dw), 0.0);
  CHECK(M::conductance(gw, PairProperties::mix(m, m), touching(a, dw), M::Params{}, h) ==
        grain::test::approx(
            M::conductance(gp, PairProperties::mix(m, m), touching(a, 2 * dw), M::Params{}, h))
            .epsilon(1e-12));
  // an insulating wall conducts nothing (image form); a very good conductor tends to the
  // isothermal form (k_w = 1e9 k_p: relative difference 1e-9, checked to 1e-8)
  Material ins = glass();
  ins.conductivity = 0.0;
  CHECK(M::conductance(gw, PairProperties::mix(m, ins), touching(a, dw), M::Params{}, h) == 0.0);
  Material copper = glass();
  copper.conductivity = 1e9;
  CHECK(M::conductance(gw, PairProperties::mix(m, copper), touching(a, dw), M::Params{}, h) ==
        grain::test::approx(3.1574194169982765e-5).epsilon(1e-8));
}

// ---------------------------------------------------------------- collisional

TEST_CASE("Collisional: impact coefficients of the Sun-Chen example (verification 4.8)") {
  using M = conduction::Collisional;
  const Material m = glass();
  const PairProperties pair = PairProperties::mix(m, m);
  const double r = 1e-3, mass = sphere_mass(r, 2500.0);
  const auto im = M::impact(pair, r / 2, mass / 2, 1.0, false, M::Params{});
  // a_max = 3.1869e-5 m (reference to 5 digits; tolerance 1e-4)
  CHECK(im.radius == grain::test::approx(3.1869e-5).epsilon(1e-4));
  // t_c = 5.982e-6 s, computed there with c_t = 2.87; here the exact 2.86827 gives a 0.06 %
  // shorter t_c (tolerance 1e-3)
  CHECK(im.duration == grain::test::approx(5.982e-6).epsilon(1e-3));
  CHECK(im.duration / 5.982e-6 == grain::test::approx(2.868265699195333 / 2.87).epsilon(1e-4));
  // Fo = 0.0029 (reference to 2 digits; 0.002943 here; tolerance 2 %)
  CHECK(im.fourier == grain::test::approx(0.0029).epsilon(0.02));
  // C' = 0.9017 (reference to 4 digits; C barely depends on Fo; tolerance 1e-4)
  CHECK(im.correction == grain::test::approx(0.9017).epsilon(1e-4));
  // rate coefficient 8.3174e-4 W/K (t_c^(-1/2) differs by 0.03 % with the exact c_t; tol 1e-3)
  CHECK(im.conductance == grain::test::approx(8.3174e-4).epsilon(1e-3));
  // heat per impact per kelvin H t_c = 4.9755e-9 J/K (tolerance 1e-3, as above)
  CHECK(im.conductance * im.duration == grain::test::approx(4.9755e-9).epsilon(1e-3));
  // Sun & Chen's constant C' = 0.87: 4.8007e-9 J/K (tolerance 1e-3, as above)
  const auto sc = M::impact(pair, r / 2, mass / 2, 1.0, false, M::Params{.coefficient = 0.87});
  CHECK(sc.correction == 0.87);
  CHECK(sc.conductance * sc.duration == grain::test::approx(4.8007e-9).epsilon(1e-3));
  // the cancellation-free root equals the textbook formula at b = 1 (round-off)
  const double c1 = -2.3 + 8.909 - 4.235, c2 = 8.169 - 33.77 + 24.885,
               c3 = -5.758 + 24.464 - 20.511;
  const double fo = 0.0029;
  CHECK(M::correction(1.0, fo) ==
        grain::test::approx(0.435 * (std::sqrt(c2 * c2 - 4 * c1 * (c3 - fo)) - c2) / c1)
            .epsilon(1e-12));
  // at b = 0.5 (C2 > 0) the same quadratic root, from the other branch (round-off)
  {
    const double b = 0.5, d1 = -2.3 * b * b + 8.909 * b - 4.235;
    const double d2 = 8.169 * b * b - 33.77 * b + 24.885, d3 = -5.758 * b * b + 24.464 * b - 20.511;
    CHECK(M::correction(b, fo) ==
          grain::test::approx(0.435 * (std::sqrt(d2 * d2 - 4 * d1 * (d3 - fo)) - d2) / d1)
              .epsilon(1e-9));
  }
  // finite and positive where C1 vanishes (b = 0.5548, 3.319) and over 0.01 <= b <= 20
  for (double b : {0.01, 0.1, 0.5548, 1.0, 2.0, 3.319, 5.0, 20.0})
    for (double f : {0.0, 1e-3, 0.1, 1.0}) {
      const double c = M::correction(b, f);
      CHECK((std::isfinite(c) && c > 0.8 && c < 1.6));
    }
}

TEST_CASE("Collisional: heat over an integrated Hertz impact, then Batchelor-O'Brien") {
  using M = conduction::Collisional;
  const Material m = glass();
  const PairProperties pair = PairProperties::mix(m, m);
  const double r = 1e-3, mass = sphere_mass(r, 2500.0), v = 1.0, dT = 100.0;
  const double m_eff = mass / 2, r_eff = r / 2;
  const double kh = 4.0 / 3.0 * pair.young_eff * std::sqrt(r_eff);
  const auto im = M::impact(pair, r_eff, m_eff, v, false, M::Params{});
  const double tc = im.duration;

  // undamped Hertz impact, velocity Verlet with dt = t_c/2000; the heat model sees each step's
  // overlap and approach velocity, and the Hertz radius of the overlap
  const double dt = tc / 2000.0;
  double delta = 0.0, rate = v, heat = 0.0, contact_time = 0.0;
  auto accel = [&](double x) { return x > 0 ? -kh * x * std::sqrt(x) / m_eff : 0.0; };
  M::History<3> h;
  for (int n = 0; n < 100000; ++n) {
    const double half = rate + 0.5 * dt * accel(delta);
    delta += dt * half;
    rate = half + 0.5 * dt * accel(delta);
    if (delta <= 0.0) break;
    const auto g = contact(r, r, mass, mass, delta, rate);
    const double a = std::sqrt(r_eff * delta);
    heat += M::conductance(g, pair, touching(a, 2 * r - delta, dt), M::Params{}, h) * dT * dt;
    contact_time += dt;
  }
  // the simulated contact lasts the Hertz t_c (to a step; tolerance 2 dt)
  CHECK(std::abs(contact_time - tc) <= 2 * dt);
  // the impact was recorded with the first-step velocity (v (1 - O((dt/t_c)^(5/2))), tol 1e-6)
  CHECK(h.conductance == grain::test::approx(im.conductance).epsilon(1e-6));
  // heat of one impact at dT = 100 K: 4.9755e-7 J (verification 4.8; tolerance 1 %)
  CHECK(heat == grain::test::approx(4.9755e-9 * dT).epsilon(0.01));
  // and the model's own H_coll t_c dT to a step of BOB at most (tolerance 1e-3)
  CHECK(heat == grain::test::approx(im.conductance * tc * dT).epsilon(1e-3));
}

TEST_CASE("Collisional: switch to Batchelor-O'Brien after t_c, resting contacts, reset") {
  using M = conduction::Collisional;
  const Material m = glass();
  const PairProperties pair = PairProperties::mix(m, m);
  const double r = 1e-3, mass = sphere_mass(r, 2500.0);
  const auto im = M::impact(pair, r / 2, mass / 2, 1.0, false, M::Params{});
  const double a = 2e-5, bob = 4.0 * pair.conductivity_eff * a; // static conductance
  const double dt = im.duration / 3.5;                          // t_c falls mid-step
  const auto g_in = contact(r, r, mass, mass, 1e-7, 1.0);
  const auto g_rest = contact(r, r, mass, mass, 1e-7, 0.0);
  const HeatContext c = touching(a, 2 * r - 1e-7, dt);

  M::History<3> h;
  double q = 0.0;
  // steps 1-3: impact conductance (round-off)
  for (int n = 0; n < 3; ++n) {
    const double hn = M::conductance(n == 0 ? g_in : g_rest, pair, c, M::Params{}, h);
    CHECK(hn == grain::test::approx(im.conductance).epsilon(1e-12));
    q += hn * dt;
  }
  // step 4 crosses t_c: half impact, half static (round-off)
  const double h4 = M::conductance(g_rest, pair, c, M::Params{}, h);
  CHECK(h4 == grain::test::approx(0.5 * im.conductance + 0.5 * bob).epsilon(1e-12));
  q += h4 * dt;
  // heat over the first 4 steps = H_coll t_c + BOB (4 dt - t_c), whatever dt (round-off)
  CHECK(q == grain::test::approx(im.conductance * im.duration + bob * (4 * dt - im.duration))
                 .epsilon(1e-12));
  // afterwards the enduring contact conducts as Batchelor-O'Brien, 4 k* a (round-off)
  for (int n = 0; n < 5; ++n)
    CHECK(M::conductance(g_in, pair, c, M::Params{}, h) == grain::test::approx(bob).epsilon(1e-12));
  conduction::BatchelorOBrien::History<3> hb;
  CHECK(bob == grain::test::approx(conduction::BatchelorOBrien::conductance(
                                       g_rest, pair, c, conduction::BatchelorOBrien::Params{}, hb))
                   .epsilon(1e-12));

  // a new impact after the simulation reset the history starts afresh
  h = M::History<3>{};
  CHECK(M::conductance(g_in, pair, c, M::Params{}, h) ==
        grain::test::approx(im.conductance).epsilon(1e-12));

  // resting contact (v0 = 0) or separating first step: BOB throughout, also when the pair later
  // approaches
  for (double v0 : {0.0, -0.5}) {
    M::History<3> hr;
    CHECK(M::conductance(contact(r, r, mass, mass, 1e-7, v0), pair, c, M::Params{}, hr) ==
          grain::test::approx(bob).epsilon(1e-12));
    CHECK(hr.duration < 0.0);
    CHECK(M::conductance(g_in, pair, c, M::Params{}, hr) ==
          grain::test::approx(bob).epsilon(1e-12));
  }

  // a partner without heat capacity: no impact phase, BOB throughout
  Material dry = glass();
  dry.heat_capacity = 0.0;
  M::History<3> hd;
  const PairProperties pd = PairProperties::mix(m, dry);
  CHECK(M::conductance(g_in, pd, c, M::Params{}, hd) ==
        grain::test::approx(4.0 * pd.conductivity_eff * a).epsilon(1e-12));
}

TEST_CASE("Collisional: particle-wall impact uses the particle's Fourier number") {
  using M = conduction::Collisional;
  const Material m = glass();
  Material wall = glass();
  wall.conductivity = 5.0;
  wall.density = 7800.0;
  wall.heat_capacity = 500.0;
  const PairProperties pair = PairProperties::mix(m, wall);
  const double r = 1e-3, mass = sphere_mass(r, 2500.0);
  const double inf = std::numeric_limits<double>::infinity();
  const auto g = contact(r, inf, mass, inf, 1e-7, 0.8);
  M::History<3> h;
  const double hc = M::conductance(g, pair, touching(2e-5, r - 1e-7, 1e-9), M::Params{}, h);
  const auto im = M::impact(pair, r, mass, 0.8, true, M::Params{});
  CHECK(hc == grain::test::approx(im.conductance).epsilon(1e-12));
  // Fo = k_p t_c / (rho_p c_p a_max^2) of the particle alone (round-off)
  CHECK(im.fourier ==
        grain::test::approx(1.0 * im.duration / (2500.0 * 800.0 * im.radius * im.radius))
            .epsilon(1e-12));
  // H_coll = C pi a_max^2 t_c^(-1/2) / ((rho c k)_p^(-1/2) + (rho c k)_w^(-1/2)), with
  // C = C(b = rho_p c_p/(rho_w c_w), Fo) (round-off)
  const double b = 2500.0 * 800.0 / (7800.0 * 500.0);
  const double ref = M::correction(b, im.fourier) * pi * im.radius * im.radius /
                     std::sqrt(im.duration) /
                     (1 / std::sqrt(2500.0 * 800.0 * 1.0) + 1 / std::sqrt(7800.0 * 500.0 * 5.0));
  CHECK(im.conductance == grain::test::approx(ref).epsilon(1e-12));
  // a_max and t_c of the sphere-wall impact: R* = R, m* = m (round-off)
  CHECK(im.radius ==
        grain::test::approx(std::pow(15 * mass * r * r * 0.64 / (16 * pair.young_eff), 0.2))
            .epsilon(1e-12));
}

TEST_CASE("Collisional: parameter validation") {
  using M = conduction::Collisional;
  CHECK_NOTHROW(M::validate(M::Params{}));
  CHECK_NOTHROW(M::validate(M::Params{.coefficient = 0.87}));
  CHECK_THROWS_AS(M::validate(M::Params{.coefficient = -0.1}), InputError);
  CHECK_THROWS_AS(M::validate(M::Params{.coefficient = std::numeric_limits<double>::quiet_NaN()}),
                  InputError);
  CHECK_THROWS_AS(M::validate(M::Params{.coefficient = std::numeric_limits<double>::infinity()}),
                  InputError);
  CHECK_NOTHROW(conduction::ThermalPipe::validate(conduction::ThermalPipe::Params{}));
}

// ---------------------------------------------------------------- area corrections

TEST_CASE("Area corrections: Zhou-Yu-Zulli is exact for the maximum radius of a Hertz impact") {
  // E_sim = E_0/1000; impact of two glass spheres at 1 m/s
  const PairProperties soft = PairProperties::mix(glass(70e6, 70e9), glass(70e6, 70e9));
  const PairProperties real = PairProperties::mix(glass(), glass());
  CHECK(soft.young_real_eff == grain::test::approx(real.young_eff).epsilon(1e-14));
  const double r = 1e-3, mass = sphere_mass(r, 2500.0), r_eff = r / 2, m_eff = mass / 2;
  using normal::hertz_equivalent::hertz_max_overlap;
  const double dmax_soft = hertz_max_overlap(soft, r_eff, m_eff, 1.0);
  const double a_real = std::sqrt(r_eff * hertz_max_overlap(real, r_eff, m_eff, 1.0));
  const auto g = contact(r, r, mass, mass, dmax_soft, 0.0);
  const double a_zyz = area::ZhouYuZulli::radius(g, soft, NormalResult{}, {});
  // closed forms: a'_max = sqrt(R* delta_max(E_0)) (round-off, 1e-12)
  CHECK(a_zyz == grain::test::approx(a_real).epsilon(1e-12));
  // = a_max of verification 4.8, 3.1869e-5 m (reference to 5 digits; tolerance 1e-4)
  CHECK(a_zyz == grain::test::approx(3.1869e-5).epsilon(1e-4));

  // integrated soft impact (velocity Verlet, dt = t_c/4000): the largest corrected radius over the
  // steps is the real a_max (tolerance 1e-5: overlap sampled near its maximum, O(dt^2))
  const double kh = 4.0 / 3.0 * soft.young_eff * std::sqrt(r_eff);
  const double dt = normal::hertz_equivalent::hertz_contact_time(soft, r_eff, m_eff, 1.0) / 4000;
  double delta = 0.0, rate = 1.0, a_max = 0.0;
  for (int n = 0; n < 100000; ++n) {
    const double half = rate - 0.5 * dt * (delta > 0 ? kh * delta * std::sqrt(delta) / m_eff : 0.0);
    delta += dt * half;
    rate = half - 0.5 * dt * (delta > 0 ? kh * delta * std::sqrt(delta) / m_eff : 0.0);
    if (delta <= 0) break;
    a_max = std::max(a_max, area::ZhouYuZulli::radius(contact(r, r, mass, mass, delta, rate), soft,
                                                      NormalResult{}, {}));
  }
  CHECK(a_max == grain::test::approx(a_real).epsilon(1e-5));
}

TEST_CASE("Area corrections: static Hertz load, real radius a* = (3 F R*/(4 E*_0))^(1/3)") {
  const PairProperties soft = PairProperties::mix(glass(70e6, 70e9), glass(70e6, 70e9));
  const double r = 1e-3, r_eff = r / 2, f = 0.5; // static force [N]
  const double kh_soft = 4.0 / 3.0 * soft.young_eff * std::sqrt(r_eff);
  const double delta = std::pow(f / kh_soft, 2.0 / 3.0); // static overlap of the soft contact
  const auto g = contact(r, r, 1e-5, 1e-5, delta, 0.0);
  using Hz = normal::Hertz<>;
  Hz::History<3> hh;
  const NormalResult n = Hz::force(g, soft, Hz::Params{}, hh);
  CHECK(n.force == grain::test::approx(f).epsilon(1e-12));
  const double a_star = std::cbrt(3.0 * f * r_eff / (4.0 * soft.young_real_eff));

  // MPMH and LMLB give the real Hertz radius at that force (round-off, 1e-12)
  CHECK(area::MorrisPannalaMaHrenya::radius(g, soft, n, {}) ==
        grain::test::approx(a_star).epsilon(1e-12));
  CHECK(area::LuMorrisLiBenyahia::radius(g, soft, n, {}) ==
        grain::test::approx(a_star).epsilon(1e-12));
  // LMLB: the real overlap delta_0 = (E*/E*_0)^(2/3) delta, a' = sqrt(R* delta_0) (round-off)
  CHECK(area::LuMorrisLiBenyahia::radius(g, soft, n, {}) ==
        grain::test::approx(std::sqrt(r_eff * std::pow(1e-3, 2.0 / 3.0) * delta)).epsilon(1e-12));
  // the seed's MPMH form (F R*/E*_0)^(1/3) is (4/3)^(1/3) = 1.1006 times a* (4 digits)
  CHECK(std::cbrt(f * r_eff / soft.young_real_eff) / a_star ==
        grain::test::approx(1.1006).epsilon(1e-4));

  // ZYZ is not exact under static load: it overestimates a* by (E_0/E_sim)^(2/15) = 2.51
  // (reference to 3 digits; tolerance 1e-3), exactly 1000^(2/15) (round-off)
  const double ratio = area::ZhouYuZulli::radius(g, soft, n, {}) / a_star;
  CHECK(ratio == grain::test::approx(2.51).epsilon(1e-3));
  CHECK(ratio == grain::test::approx(std::pow(1000.0, 2.0 / 15.0)).epsilon(1e-12));

  // without a softened modulus every correction is the Hertz radius sqrt(R* delta) (round-off)
  const PairProperties real = PairProperties::mix(glass(), glass());
  const double d_real = std::pow(f / (4.0 / 3.0 * real.young_eff * std::sqrt(r_eff)), 2.0 / 3.0);
  const auto gr = contact(r, r, 1e-5, 1e-5, d_real, 0.0);
  const NormalResult nr = Hz::force(gr, real, Hz::Params{}, hh);
  const double a_h = area::None::radius(gr, real, nr, {});
  CHECK(area::ZhouYuZulli::radius(gr, real, nr, {}) == grain::test::approx(a_h).epsilon(1e-12));
  CHECK(area::MorrisPannalaMaHrenya::radius(gr, real, nr, {}) ==
        grain::test::approx(a_h).epsilon(1e-12));
  CHECK(area::LuMorrisLiBenyahia::radius(gr, real, nr, {}) ==
        grain::test::approx(a_h).epsilon(1e-12));
}

TEST_CASE("Area corrections: damping, linear springs, walls and negative forces") {
  const PairProperties soft = PairProperties::mix(glass(70e6, 70e9), glass(70e6, 70e9));
  const double r = 1e-3, r_eff = r / 2, e0 = soft.young_real_eff;
  // a linear spring-dashpot result: K = 1e4 N/m, eta = 0.05 N s/m, delta = 2 um, approaching at
  // 0.3 m/s
  const double k = 1e4, eta = 0.05, delta = 2e-6, vn = 0.3;
  const auto g = contact(r, r, 1e-5, 1e-5, delta, vn);
  const NormalResult n{k * delta + eta * vn, k, eta, 0.5 * k * delta * delta};
  // LMLB: real Hertz radius of the spring force K delta, the dashpot left out (round-off)
  CHECK(area::LuMorrisLiBenyahia::radius(g, soft, n, {}) ==
        grain::test::approx(std::cbrt(0.75 * k * delta * r_eff / e0)).epsilon(1e-12));
  // equivalently sqrt(R* delta_0), delta_0 = (K delta / K_hz,0)^(2/3) (round-off)
  const double kh0 = 4.0 / 3.0 * e0 * std::sqrt(r_eff);
  CHECK(
      area::LuMorrisLiBenyahia::radius(g, soft, n, {}) ==
      grain::test::approx(std::sqrt(r_eff * std::pow(k * delta / kh0, 2.0 / 3.0))).epsilon(1e-12));
  // MPMH: the total normal force (round-off)
  CHECK(area::MorrisPannalaMaHrenya::radius(g, soft, n, {}) ==
        grain::test::approx(std::cbrt(0.75 * (k * delta + eta * vn) * r_eff / e0)).epsilon(1e-12));
  // the seed's LMLB form (K a / K_hz,0)^(2/3) with its lens radius a = sqrt(2 R* delta) is
  // (3 K/(2 E*_0 R*))^(1/3) = 0.093 times the radius here (2 digits; tolerance 1 %)
  const double seed = std::pow(k * std::sqrt(2 * r_eff * delta) / kh0, 2.0 / 3.0);
  CHECK(seed / area::LuMorrisLiBenyahia::radius(g, soft, n, {}) ==
        grain::test::approx(0.093).epsilon(0.01));

  // a damped Hertz contact (Tsuji damping): LMLB follows the overlap, (E*/E*_0)^(1/3)
  // sqrt(R* delta) (round-off)
  using Hz = normal::Hertz<>;
  Hz::History<3> hh;
  PairProperties damped = soft;
  damped.restitution = 0.5;
  damped.log_restitution = std::log(0.5);
  const NormalResult nd = Hz::force(g, damped, Hz::Params{}, hh);
  CHECK(nd.damping > 0.0);
  CHECK(area::LuMorrisLiBenyahia::radius(g, damped, nd, {}) ==
        grain::test::approx(std::cbrt(1e-3) * std::sqrt(r_eff * delta)).epsilon(1e-12));

  // attractive (negative) force: zero radius, never NaN
  const NormalResult pull{-0.1, k, 0.0, 0.0};
  CHECK(area::MorrisPannalaMaHrenya::radius(g, soft, pull, {}) == 0.0);
  CHECK(area::LuMorrisLiBenyahia::radius(g, soft, pull, {}) == 0.0);
  CHECK(area::ZhouYuZulli::radius(contact(r, r, 1e-5, 1e-5, -1e-6, 0.0), soft, pull, {}) == 0.0);

  // particle-wall: R* = R (round-off)
  const double inf = std::numeric_limits<double>::infinity();
  const auto gw = contact(r, inf, 1e-5, inf, delta, 0.0);
  const NormalResult nw{0.2, 0.0, 0.0, 0.0};
  CHECK(area::MorrisPannalaMaHrenya::radius(gw, soft, nw, {}) ==
        grain::test::approx(std::cbrt(0.75 * 0.2 * r / e0)).epsilon(1e-12));
  CHECK(area::ZhouYuZulli::radius(gw, soft, nw, {}) ==
        grain::test::approx(std::pow(1e-3, 0.2) * std::sqrt(r * delta)).epsilon(1e-12));
}

TEST_CASE("Area corrections and direct conduction through the Interaction pipeline") {
  using C = Interaction<normal::Hertz<>, tangent::None, rolling::None, conduction::ThermalPipe,
                        area::MorrisPannalaMaHrenya>;
  const PairProperties soft = PairProperties::mix(glass(70e6, 70e9), glass(70e6, 70e9));
  const double r = 1e-3, delta = 1e-6;
  const auto g = contact(r, r, 1e-5, 1e-5, delta, 0.0);
  C::Params p;
  C::History<3> h;
  const NormalResult n = normal::Hertz<>::force(g, soft, p.normal, h.normal);
  const double a = std::cbrt(0.75 * n.force * (r / 2) / soft.young_real_eff);
  const double d = 2.0 * std::sqrt(r * r - a * a);
  // H = pi a*^2 k / d with the corrected radius and the consistent distance (round-off)
  CHECK(C::conductance(g, soft, n, p, h, 1e-6, 0.0, std::numeric_limits<double>::infinity()) ==
        grain::test::approx(pi * a * a * 1.0 / d).epsilon(1e-12));
}

// ---------------------------------------------------------------- convection

TEST_CASE("Convection: Ranz-Marshall and Whitaker Nusselt numbers") {
  using RM = convection::RanzMarshall;
  using W = convection::Whitaker;
  // hand-computed values, 10 significant digits (tolerance 1e-9)
  CHECK(RM::nusselt(0.0, 0.7, {}) == 2.0);
  CHECK(W::nusselt(0.0, 0.7, {}) == 2.0);
  CHECK(RM::nusselt(100.0, 0.7, {}) == grain::test::approx(7.327424010).epsilon(1e-9));
  CHECK(W::nusselt(100.0, 0.7, {}) == grain::test::approx(6.588949502).epsilon(1e-9));
  CHECK(RM::nusselt(1000.0, 7.0, {}) == grain::test::approx(38.29531727).epsilon(1e-9));
  CHECK(W::nusselt(1000.0, 7.0, {}) == grain::test::approx(42.61601788).epsilon(1e-9));
  CHECK(RM::nusselt(10.0, 380.0, {}) == grain::test::approx(15.74292309).epsilon(1e-9));
  CHECK(W::nusselt(10.0, 380.0, {}) == grain::test::approx(18.61092180).epsilon(1e-9));
  // exponents: (Nu - 2) ~ Re^(1/2) and Pr^(1/3) for Ranz-Marshall (round-off)
  CHECK((RM::nusselt(400.0, 0.7, {}) - 2) / (RM::nusselt(100.0, 0.7, {}) - 2) ==
        grain::test::approx(2.0).epsilon(1e-12));
  CHECK((RM::nusselt(100.0, 8.0, {}) - 2) / (RM::nusselt(100.0, 1.0, {}) - 2) ==
        grain::test::approx(2.0).epsilon(1e-12));
  CHECK_NOTHROW(RM::validate({}));
  CHECK_NOTHROW(W::validate({}));
}

TEST_CASE("Walton-Braun: no heat flows through a contact off its plastic dent") {
  // below the residual overlap the law carries no force: the particles have left the dent, so
  // the contact conducts nothing although the overlap (and an area from it) is not zero
  using C =
      Interaction<normal::WaltonBraun, tangent::None, rolling::None, conduction::BatchelorOBrien>;
  Material m = glass();
  m.restitution = 0.5; // K_U = 4 K_L: residual overlap 3/4 of the largest
  const PairProperties pair = PairProperties::mix(m, m);
  const double r = 1e-3;
  C::Params p;
  p.normal.stiffness = 1e3;
  C::History<3> h;
  auto H_at = [&](double delta, double vn) {
    const auto g = contact(r, r, 1e-5, 1e-5, delta, vn);
    const NormalResult n = normal::WaltonBraun::force(g, pair, p.normal, h.normal);
    return std::pair{n.force, C::conductance(g, pair, n, p, h, 1e-6, 0.0,
                                             std::numeric_limits<double>::infinity())};
  };
  const auto [f_load, H_load] = H_at(2e-6, 0.1); // loading: Batchelor-O'Brien, 4 k sqrt(R* d)
  CHECK(f_load > 0.0);
  CHECK(
      H_load ==
      grain::test::approx(4.0 * pair.conductivity_eff * std::sqrt(0.5 * r * 2e-6)).epsilon(1e-12));
  const double residual = normal::WaltonBraun::residual_overlap(pair, p.normal, 1e3, h.normal);
  REQUIRE(residual > 1e-6);
  const auto [f_above, H_above] = H_at(0.5 * (residual + 2e-6), -0.1); // unloading, in contact
  CHECK(f_above > 0.0);
  CHECK(H_above > 0.0);
  const auto [f_off, H_off] = H_at(0.9 * residual, -0.1); // below the residual overlap
  CHECK(f_off == 0.0);
  CHECK(H_off == 0.0);
}
