// Indirect conduction models (Voronoi A and B, surrounding fluid layer) and the adaptive
// quadrature behind them. The figures and their sources are listed in
// docs/models/conduction_indirect.md.
//
// Tolerances: doctest::Approx(x).epsilon(e) is relative only with .scale(0) (its default scale
// 1 turns e into an absolute bound for the small conductances here), hence `rel(x, e)`.
#include "../errors.hpp"
#include <algorithm>
#include <cmath>
#include <doctest/doctest.h>
#include <grain/core/quadrature.hpp>
#include <grain/grain.hpp>
#include <grain/models/conduction/batchelor_obrien.hpp>
#include <grain/models/conduction/combined.hpp>
#include <grain/models/conduction/surrounding_layer.hpp>
#include <grain/models/conduction/voronoi_a.hpp>
#include <grain/models/conduction/voronoi_b.hpp>
#include <limits>
#include <numbers>
#include <string>
#include <type_traits>

using namespace grain;
using conduction::SurroundingLayer;
using conduction::VoronoiA;
using conduction::VoronoiB;

static_assert(ConductionModel<VoronoiA> && ConductionModel<VoronoiB> &&
              ConductionModel<SurroundingLayer>);
static_assert(conducts_across_gaps<VoronoiA> && conducts_across_gaps<VoronoiB> &&
              conducts_across_gaps<SurroundingLayer>);
static_assert(uses_cell_radius<VoronoiA> && uses_cell_radius<VoronoiB> &&
              !uses_cell_radius<SurroundingLayer>);
static_assert(conducts_across_gaps<conduction::Combined<conduction::BatchelorOBrien, VoronoiA>>);
static_assert(uses_cell_radius<conduction::Combined<conduction::BatchelorOBrien, VoronoiB>>);
static_assert(std::is_empty_v<VoronoiA::History<3>> && std::is_empty_v<VoronoiB::History<2>> &&
              std::is_empty_v<SurroundingLayer::History<3>>);
// in an Interaction: the search reaches across gaps, and the cell radius is requested
using ContactVA = Interaction<normal::Hertz<>, tangent::None, rolling::None,
                              conduction::Combined<conduction::BatchelorOBrien, VoronoiA>>;
using ContactSL = Interaction<normal::Hertz<>, tangent::None, rolling::None, SurroundingLayer>;
static_assert(ContactVA::thermal && ContactVA::indirect && ContactVA::needs_cell_radius);
static_assert(ContactSL::thermal && ContactSL::indirect && !ContactSL::needs_cell_radius);

namespace {

using grain::test::error_of;
using grain::test::has;

constexpr double pi = std::numbers::pi;
constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double kf_air = 0.026; // W/(m K)

doctest::Approx rel(double x, double e) { return doctest::Approx(x).epsilon(e).scale(0.0); }

/// Pair properties of two materials of conductivities ki, kj in a fluid of conductivity kf.
PairProperties props(double ki, double kj, double kf) {
  Material a{.density = 2500, .young = 1e9, .conductivity = ki};
  Material b{.density = 2500, .young = 1e9, .conductivity = kj};
  auto p = PairProperties::mix(a, b);
  p.fluid_conductivity = kf;
  return p;
}

/// Geometry of particles i, j (radius rj = inf: flat wall) whose surfaces are `gap` apart
/// (gap < 0: overlap).
template <int D>
ContactGeometry<D> geom(double ri, double rj, double gap) {
  ContactGeometry<D> g;
  g.normal = Vec<D>::UnitX();
  g.radius_i = ri;
  g.radius_j = rj;
  g.wall = std::isinf(rj);
  g.r_eff = g.wall ? ri : ri * rj / (ri + rj);
  g.overlap = -gap;
  g.distance = g.wall ? ri + gap : ri + rj + gap;
  return g;
}

/// Heat context of a touching pair of contact radius a (distance consistent with a).
HeatContext touching(double ri, double rj, double a, double cell = inf) {
  HeatContext c;
  c.touching = true;
  c.contact_radius = a;
  c.distance = std::sqrt(ri * ri - a * a) + (std::isinf(rj) ? 0.0 : std::sqrt(rj * rj - a * a));
  c.cell_radius = cell;
  return c;
}

/// Heat context of a pair (or particle-wall) separated by `gap`.
HeatContext apart(double ri, double rj, double gap, double cell = inf) {
  HeatContext c;
  c.touching = false;
  c.gap = gap;
  c.distance = std::isinf(rj) ? ri + gap : ri + rj + gap;
  c.cell_radius = cell;
  return c;
}

template <class M, int D = 3>
double H(const ContactGeometry<D>& g, const PairProperties& p, const HeatContext& c,
         const typename M::Params& prm = {}) {
  typename M::template History<D> h;
  return M::conductance(g, p, c, prm, h);
}

/// Porosity-based cell radius 0.56 R (1 - phi)^(-1/3).
double cell_radius(double R, double porosity) {
  return 0.56 * R * std::pow(1.0 - porosity, -1.0 / 3.0);
}

} // namespace

// ---------------------------------------------------------------- quadrature

TEST_CASE("indirect conduction, quadrature: Gauss-Kronrod 15 is exact up to degree 22") {
  for (int k : {0, 1, 5, 13, 22}) {
    auto f = [k](double x) { return std::pow(x, k); };
    const auto r = detail::integrate(f, 0.0, 1.0, {.abs_tol = 0.0, .rel_tol = 1e-13});
    CHECK(r.converged);
    CHECK(r.value == rel(1.0 / (k + 1), 1e-14));
  }
  // degree <= 13: the embedded Gauss rule agrees, so one panel suffices
  auto p13 = [](double x) { return 3.0 * std::pow(x, 13) - x + 2.0; };
  const auto r = detail::integrate(p13, -1.0, 2.0, {.abs_tol = 0.0, .rel_tol = 1e-12});
  CHECK(r.evaluations == 15);
  CHECK(r.value == rel(3.0 * (std::pow(2.0, 14) - 1.0) / 14.0 - 1.5 + 6.0, 1e-14));
}

TEST_CASE("indirect conduction, quadrature: tolerances, reversed bounds, break points, guards") {
  auto s = [](double x) { return std::sin(x); };
  const auto r = detail::integrate(s, 0.0, pi, {.abs_tol = 0.0, .rel_tol = 1e-13});
  CHECK(r.converged);
  CHECK(r.value == rel(2.0, 1e-13));
  CHECK(r.error <= 1e-13 * 2.0);
  CHECK(detail::integrate(s, pi, 0.0).value == rel(-2.0, 1e-6));
  CHECK(detail::integrate(s, 1.0, 1.0).value == 0.0);

  // a kink at x = 0.3: exact with the break point (two panels), many more panels without
  auto kink = [](double x) { return std::abs(x - 0.3); };
  const double exact = 0.5 * (0.3 * 0.3 + 0.7 * 0.7);
  const detail::QuadratureOptions tight{.abs_tol = 0.0, .rel_tol = 1e-12};
  const auto split = detail::integrate_split(kink, 0.0, 1.0, {0.3, 7.0, -1.0}, tight);
  CHECK(split.converged);
  CHECK(split.evaluations == 30);
  CHECK(split.value == rel(exact, 1e-14));
  const auto plain = detail::integrate(kink, 0.0, 1.0, tight);
  CHECK(plain.converged);
  CHECK(plain.evaluations > 10 * split.evaluations);
  CHECK(plain.value == rel(exact, 1e-11));

  // an endpoint singularity with an unreachable tolerance: the depth guard stops the refinement
  auto sing = [](double x) { return 1.0 / std::sqrt(x); };
  const auto g =
      detail::integrate(sing, 0.0, 1.0, {.abs_tol = 0.0, .rel_tol = 1e-15, .max_depth = 8});
  CHECK_FALSE(g.converged);
  CHECK(std::isfinite(g.value));
  CHECK(g.value == rel(2.0, 0.05));
  const auto c =
      detail::integrate(sing, 0.0, 1.0, {.abs_tol = 0.0, .rel_tol = 1e-15, .max_intervals = 10});
  CHECK_FALSE(c.converged);
  CHECK(c.evaluations == 15 + 30 * 9); // 9 bisections up to 10 subintervals
  // a non-finite integrand is reported
  auto bad = [](double x) { return x > 0.5 ? std::numeric_limits<double>::quiet_NaN() : 1.0; };
  CHECK_FALSE(detail::integrate(bad, 0.0, 1.0).converged);
}

// ---------------------------------------------------------------- surrounding layer

TEST_CASE("indirect conduction, surrounding layer: p-p references (verification 4.6)") {
  // R = 1 mm, k_f = 0.026 W/(m K), layer 0.4 R, S = 2.75e-8 m, a = 0.
  // Printed references have 6 significant digits: tolerance 5e-6 relative (half a unit in the
  // 6th digit); the 12-digit values (30-digit arithmetic, same integral) are checked to 1e-8.
  const double R = 1e-3;
  const auto p = props(1.0, 1.0, kf_air);
  struct Case {
    double gap, ref6, ref12;
  };
  for (const Case& k :
       {Case{0.0, 8.59890e-4, 8.59889781826e-4}, Case{10e-6, 2.98279e-4, 2.98279151395e-4},
        Case{100e-6, 1.15763e-4, 1.15762618548e-4}}) {
    CAPTURE(k.gap);
    const auto c = k.gap == 0.0 ? touching(R, R, 0.0) : apart(R, R, k.gap);
    const double h = H<SurroundingLayer>(geom<3>(R, R, k.gap), p, c);
    CHECK(h == rel(k.ref6, 5e-6));
    CHECK(h == rel(k.ref12, 1e-8));
  }
  // the solids' conductivities do not enter
  CHECK(H<SurroundingLayer>(geom<3>(R, R, 10e-6), props(3.0, 70.0, kf_air), apart(R, R, 10e-6)) ==
        rel(2.98279151395e-4, 1e-8));
}

TEST_CASE("indirect conduction, surrounding layer: p-wall references, closed form = integral") {
  const double R = 1e-3, kf = kf_air;
  const SurroundingLayer::Params prm;
  const auto p = props(1.0, 16.0, kf);
  // verification 4.6 (6 significant digits: 5e-6; 12-digit recomputation: 1e-8)
  CHECK(H<SurroundingLayer>(geom<3>(R, inf, 10e-6), p, apart(R, inf, 10e-6)) ==
        rel(5.92291e-4, 5e-6));
  CHECK(H<SurroundingLayer>(geom<3>(R, inf, 10e-6), p, apart(R, inf, 10e-6)) ==
        rel(5.92290621866e-4, 1e-8));
  CHECK(H<SurroundingLayer>(geom<3>(R, inf, 100e-6), p, apart(R, inf, 100e-6)) ==
        rel(2.40296e-4, 5e-6));
  CHECK(H<SurroundingLayer>(geom<3>(R, inf, 100e-6), p, apart(R, inf, 100e-6)) ==
        rel(2.40296154659e-4, 1e-8));

  // the closed form equals k_f int_a^r_out 2 pi r dr / max(S, d - sqrt(R^2 - r^2)) (computed
  // here independently, split at the kink) for gaps above and below S and in contact
  auto numeric = [&](double d, double a) {
    const double Ro = (1.0 + prm.layer_ratio) * R, S = prm.min_gap;
    const double r_out = std::min(R, std::sqrt(Ro * Ro - d * d));
    const double s = d - S;
    const double r_in = s < R ? std::sqrt(R * R - s * s) : 0.0;
    auto f = [&](double r) { return 2.0 * pi * r / std::max(S, d - std::sqrt(R * R - r * r)); };
    return kf *
           detail::integrate_split(f, a, r_out, {r_in}, {.abs_tol = 0.0, .rel_tol = 1e-13}).value;
  };
  for (double gap : {1e-4, 1e-5, 1e-6, 5e-8, 1e-8, 0.35e-3}) {
    CAPTURE(gap);
    CHECK(SurroundingLayer::wall(R, R + gap, 0.0, kf, prm) == rel(numeric(R + gap, 0.0), 1e-11));
  }
  for (double a : {0.0, 1e-6, 1e-5, 5e-5, 0.25e-3}) { // 0.25 R: r_out = R (layer past equator)
    CAPTURE(a);
    const double d = std::sqrt(R * R - a * a);
    CHECK(SurroundingLayer::wall(R, d, a, kf, prm) == rel(numeric(d, a), 1e-11));
    CHECK(H<SurroundingLayer>(geom<3>(R, inf, d - R), p, touching(R, inf, a)) ==
          rel(numeric(d, a), 1e-11));
  }
  // beyond the layer nothing flows; the gap of a wall pair conducts up to L = 0.4 R
  CHECK(SurroundingLayer::wall(R, 1.4 * R, 0.0, kf, prm) == 0.0);
  CHECK(SurroundingLayer::wall(R, 1.399 * R, 0.0, kf, prm) > 0.0);
  CHECK(SurroundingLayer::cutoff(prm, R) == doctest::Approx(0.4 * R));
}

TEST_CASE("indirect conduction, surrounding layer: Morris wall form, DEMLab resting_single") {
  // DEMLab example resting_single: R = 1 m, centre 0.99 m above the wall, k_f = 10 W/(m K).
  // DEMLab's wall form (layer term only) gives 1019.37 W/K; the clamped disc a < r < r_in,
  // where the gap is held at S, adds k_f pi (r_in^2 - a^2)/S = 62.20 W/K.
  const double R = 1.0, d = 0.99, kf = 10.0, S = 2.75e-8;
  const SurroundingLayer::Params prm;
  const double a = std::sqrt(R * R - d * d);
  const double h = SurroundingLayer::wall(R, d, a, kf, prm);
  CHECK(h == rel(1081.57500781, 1e-9));
  // Morris et al.: 2 pi k_f R [(a'+1) ln(|b - a' - 1|/|a' - c + 1|) + b - c]
  const double ap = (d - R) / R;
  const double r_in = std::sqrt(1.0 - std::pow(S / R - ap - 1.0, 2));
  const double r_out = std::sqrt(std::pow((R + 0.4 * R) / R, 2) - std::pow(ap + 1.0, 2));
  const double b = std::sqrt(1.0 - r_out * r_out), c = std::sqrt(1.0 - r_in * r_in);
  const double morris =
      2.0 * pi * kf * R *
      ((ap + 1.0) * std::log(std::abs(b - ap - 1.0) / std::abs(ap - c + 1.0)) + b - c);
  CHECK(morris == rel(1019.37147413, 1e-8));
  const double disc = kf * pi * (r_in * r_in * R * R - a * a) / S;
  CHECK(h == rel(morris + disc, 1e-8));
}

TEST_CASE("indirect conduction, surrounding layer: sizes, symmetry, contact limit, S") {
  const double R1 = 1e-3, R2 = 1.5e-3, kf = kf_air;
  const SurroundingLayer::Params prm;
  const double a = 2e-5;
  const double dt = std::sqrt(R1 * R1 - a * a) + std::sqrt(R2 * R2 - a * a);
  // 12-digit references (30-digit arithmetic) of the same integral
  CHECK(SurroundingLayer::pair_conductance(R1, R2, dt, a, kf, prm) == rel(1.05676678095e-3, 1e-8));
  CHECK(SurroundingLayer::pair_conductance(R1, R2, R1 + R2, 0.0, kf, prm) ==
        rel(1.05693508914e-3, 1e-8));
  CHECK(SurroundingLayer::pair_conductance(R1, R2, R1 + R2 + 1e-5, 0.0, kf, prm) ==
        rel(3.83336340163e-4, 1e-8));
  // symmetric in i and j
  CHECK(SurroundingLayer::pair_conductance(R2, R1, dt, a, kf, prm) ==
        rel(SurroundingLayer::pair_conductance(R1, R2, dt, a, kf, prm), 1e-14));
  // continuous from gap to contact: gap -> 0+ and a -> 0 meet (dH/dgap ~ H/S near contact)
  const double h0 = SurroundingLayer::pair_conductance(R1, R1, 2 * R1, 0.0, kf, prm);
  CHECK(SurroundingLayer::pair_conductance(R1, R1, 2 * R1 + 1e-15, 0.0, kf, prm) == rel(h0, 1e-6));
  const double at = 1e-7;
  CHECK(SurroundingLayer::pair_conductance(R1, R1, 2 * std::sqrt(R1 * R1 - at * at), at, kf, prm) ==
        rel(h0, 1e-3));
  // larger R2 at the same gap conducts more; H decreases with the gap
  CHECK(SurroundingLayer::pair_conductance(R1, R2, R1 + R2 + 1e-5, 0.0, kf, prm) >
        SurroundingLayer::pair_conductance(R1, R1, 2 * R1 + 1e-5, 0.0, kf, prm));
  double last = inf;
  for (double gap : {0.0, 1e-8, 1e-7, 1e-6, 1e-5, 1e-4, 3e-4}) {
    const double h = SurroundingLayer::pair_conductance(R1, R1, 2 * R1 + gap, 0.0, kf, prm);
    CHECK(h < last);
    last = h;
  }
  // the layer of the larger particle decides the reach: H = 0 from gap = 0.4 R_l on
  CHECK(SurroundingLayer::pair_conductance(R1, R2, R1 + R2 + 0.4 * R2, 0.0, kf, prm) == 0.0);
  CHECK(SurroundingLayer::pair_conductance(R1, R2, R1 + R2 + 0.39 * R2, 0.0, kf, prm) > 0.0);
  // H(gap 0) depends on S logarithmically: halving S adds about pi R k_f ln 2
  SurroundingLayer::Params half = prm;
  half.min_gap = 0.5 * prm.min_gap;
  const double dh = SurroundingLayer::pair_conductance(R1, R1, 2 * R1, 0.0, kf, half) - h0;
  CHECK(dh == rel(pi * R1 * kf * std::log(2.0), 1e-3));
  // fluid conductivity 0: nothing flows
  CHECK(H<SurroundingLayer>(geom<3>(R1, R1, 1e-5), props(1, 1, 0.0), apart(R1, R1, 1e-5)) == 0.0);
}

TEST_CASE("indirect conduction, surrounding layer: p-p closed form = quadrature") {
  const double kf = kf_air;
  SurroundingLayer::Params quad, closed;
  quad.closed_form = false;
  quad.rel_tolerance = 1e-13;
  quad.abs_tolerance = 0.0;
  closed.closed_form = true;
  // verification 4.6 with the closed form
  const double R = 1e-3;
  CHECK(SurroundingLayer::pair_conductance(R, R, 2 * R, 0.0, kf, closed) ==
        rel(8.59889781826e-4, 1e-10));
  CHECK(SurroundingLayer::pair_conductance(R, R, 2 * R + 1e-5, 0.0, kf, closed) ==
        rel(2.98279151395e-4, 1e-10));
  CHECK(SurroundingLayer::pair_conductance(R, R, 2 * R + 1e-4, 0.0, kf, closed) ==
        rel(1.15762618548e-4, 1e-10));
  // a sweep over size ratios, gaps (below S, at the kink, up to the layer) and contact radii
  int n = 0;
  for (double ratio : {1.0, 1.0 + 1e-9, 1.5, 3.0, 10.0}) {
    const double R1 = 1e-3, R2 = ratio * R1;
    for (double gap : {0.0, 1e-8, 2.75e-8, 1e-7, 1e-6, 1e-5, 1e-4, 0.3 * 0.4 * R2}) {
      CAPTURE(ratio);
      CAPTURE(gap);
      const double d = R1 + R2 + gap;
      CHECK(SurroundingLayer::pair_conductance(R1, R2, d, 0.0, kf, closed) ==
            rel(SurroundingLayer::pair_conductance(R1, R2, d, 0.0, kf, quad), 1e-11));
      ++n;
    }
    for (double a : {1e-7, 1e-5, 2e-4, 0.5e-3}) {
      CAPTURE(ratio);
      CAPTURE(a);
      const double d = std::sqrt(R1 * R1 - a * a) + std::sqrt(R2 * R2 - a * a);
      CHECK(SurroundingLayer::pair_conductance(R2, R1, d, a, kf, closed) ==
            rel(SurroundingLayer::pair_conductance(R1, R2, d, a, kf, quad), 1e-11));
      ++n;
    }
  }
  CHECK(n == 60);
  // through conductance()
  CHECK(H<SurroundingLayer>(geom<3>(R, 2 * R, 1e-5), props(1, 1, kf), apart(R, 2 * R, 1e-5),
                            closed) ==
        rel(H<SurroundingLayer>(geom<3>(R, 2 * R, 1e-5), props(1, 1, kf), apart(R, 2 * R, 1e-5)),
            1e-9));
}

// ---------------------------------------------------------------- Voronoi A and B

TEST_CASE("indirect conduction, Voronoi A and B: references (verification 4.7), k_s = k*") {
  // R = 1 mm, particles of k = 1 W/(m K) (k* = 0.5), k_f = 0.026, core 0.5 R (model B),
  // r_ij = 0.56 R (1 - 0.4)^(-1/3) = 0.6640 R, d = 2 sqrt(R^2 - a^2).
  // Printed references: 6 significant digits, tolerance 5e-6; 12-digit recomputation: 1e-8.
  const double R = 1e-3;
  const auto p = props(1.0, 1.0, kf_air);
  CHECK(p.conductivity_eff == 0.5);
  const double rij = cell_radius(R, 0.4);
  CHECK(rij / R == rel(0.66395341684, 1e-10));
  struct Case {
    double a, a6, a12, b6, b12;
  };
  for (const Case& k : {Case{10e-6, 1.83722e-4, 1.83721649513e-4, 1.63679e-4, 1.63678627977e-4},
                        Case{50e-6, 1.84288e-4, 1.84288477796e-4, 1.63188e-4, 1.63187683588e-4}}) {
    CAPTURE(k.a);
    const auto g = geom<3>(R, R, -(2 * R - 2 * std::sqrt(R * R - k.a * k.a)));
    const auto c = touching(R, R, k.a, rij);
    CHECK(H<VoronoiA>(g, p, c) == rel(k.a6, 5e-6));
    CHECK(H<VoronoiA>(g, p, c) == rel(k.a12, 1e-8));
    CHECK(H<VoronoiB>(g, p, c) == rel(k.b6, 5e-6));
    CHECK(H<VoronoiB>(g, p, c) == rel(k.b12, 1e-8));
    // Batchelor-O'Brien in parallel (verification 4.7 lists 2.0e-5 and 1.0e-4 W/K)
    using AB = conduction::Combined<conduction::BatchelorOBrien, VoronoiA>;
    CHECK(H<AB>(g, p, c) == rel(k.a12 + 2.0 * k.a, 1e-8));
  }
  // the same in 2D (disks use the sphere formulas)
  const auto g2 = geom<2>(R, R, 0.0);
  CHECK(H<VoronoiA, 2>(g2, p, touching(R, R, 10e-6, rij)) == rel(1.83721649513e-4, 1e-8));
  CHECK(H<VoronoiB, 2>(g2, p, touching(R, R, 10e-6, rij)) == rel(1.63678627977e-4, 1e-8));
}

TEST_CASE("indirect conduction, Voronoi A and B: k* = halves in series; wall = mid-plane") {
  const double R = 1e-3, kf = kf_air, rij = cell_radius(R, 0.4), a = 2e-5;
  const double d = 2 * std::sqrt(R * R - a * a);
  const VoronoiA::Params pa;
  const VoronoiB::Params pb;
  // mono-size with k_i != k_j: the multi-size forms with k_i, k_j at R_i = R_j equal the
  // mono-size forms with k* = k_i k_j/(k_i + k_j)
  const double ki = 1.0, kj = 4.0, ks = ki * kj / (ki + kj);
  CHECK(VoronoiA::multi(R, R, d, a, rij, ki, kj, kf, pa) ==
        rel(VoronoiA::mono(R, d, a, rij, ks, kf, pa), 1e-9));
  CHECK(VoronoiB::multi(R, R, d, a, rij, ki, kj, kf, pb) ==
        rel(VoronoiB::mono(R, d, a, rij, ks, kf, pb), 1e-12));
  // a pair of equal particles (k) is two particle-wall halves (k, wall at d/2) in series
  for (double aa : {0.0, a}) {
    const double dd = 2 * std::sqrt(R * R - aa * aa);
    CHECK(VoronoiA::wall(R, dd / 2, aa, rij, 2.0, kf, pa) ==
          rel(2.0 * VoronoiA::mono(R, dd, aa, rij, 1.0, kf, pa), 1e-9));
    CHECK(VoronoiB::wall(R, dd / 2, aa, rij, 2.0, kf, pb) ==
          rel(2.0 * VoronoiB::mono(R, dd, aa, rij, 1.0, kf, pb), 1e-12));
  }
  // through conductance(): the wall uses the particle's k (conductivity_i), not the wall's
  const auto gw = geom<3>(R, inf, -(R - std::sqrt(R * R - a * a)));
  const auto cw = touching(R, inf, a, rij);
  CHECK(H<VoronoiA>(gw, props(2.0, 50.0, kf), cw) ==
        rel(VoronoiA::wall(R, std::sqrt(R * R - a * a), a, rij, 2.0, kf, pa), 1e-14));
  CHECK(H<VoronoiA>(gw, props(2.0, 50.0, kf), cw) ==
        rel(H<VoronoiA>(gw, props(2.0, 0.5, kf), cw), 1e-14));
  CHECK(H<VoronoiB>(gw, props(2.0, 50.0, kf), cw) ==
        rel(VoronoiB::wall(R, std::sqrt(R * R - a * a), a, rij, 2.0, kf, pb), 1e-14));
  // wall across a gap
  const auto cg = apart(R, inf, 1e-4, rij);
  CHECK(H<VoronoiA>(geom<3>(R, inf, 1e-4), props(2.0, 50.0, kf), cg) ==
        rel(VoronoiA::wall(R, R + 1e-4, 0.0, rij, 2.0, kf, pa), 1e-14));
}

TEST_CASE("indirect conduction, Voronoi A: multi-size (Gan, Zhou & Yu), symmetry, mono limit") {
  const double R1 = 1e-3, R2 = 1.5e-3, kf = kf_air;
  const double rij = cell_radius(0.5 * (R1 + R2), 0.4);
  const VoronoiA::Params p;
  const double a = 2e-5;
  const double dt = std::sqrt(R1 * R1 - a * a) + std::sqrt(R2 * R2 - a * a);
  // 12-digit references (30-digit arithmetic) of the same integral
  CHECK(VoronoiA::multi(R1, R2, dt, a, rij, 1.0, 2.0, kf, p) == rel(2.37667247227e-4, 1e-8));
  CHECK(VoronoiA::multi(R1, R2, R1 + R2 + 5e-5, 0.0, rij, 1.0, 2.0, kf, p) ==
        rel(1.59551312588e-4, 1e-8));
  // through conductance(), and symmetric under swapping i and j (radii and materials)
  const auto g12 = geom<3>(R1, R2, dt - R1 - R2), g21 = geom<3>(R2, R1, dt - R1 - R2);
  const double h12 = H<VoronoiA>(g12, props(1.0, 2.0, kf), touching(R1, R2, a, rij));
  const double h21 = H<VoronoiA>(g21, props(2.0, 1.0, kf), touching(R2, R1, a, rij));
  CHECK(h12 == rel(2.37667247227e-4, 1e-8));
  CHECK(h12 == rel(h21, 1e-14));
  // tends to the mono-size value as R_j -> R_i (also with k_i != k_j)
  for (double ki : {1.0, 0.3}) {
    const double kj = 1.0, ks = ki * kj / (ki + kj);
    const double mono = VoronoiA::mono(R1, 2 * std::sqrt(R1 * R1 - a * a), a, rij, ks, kf, p);
    for (double eps : {1e-3, 1e-6, 1e-9}) {
      const double Rj = R1 * (1.0 + eps);
      const double d = std::sqrt(R1 * R1 - a * a) + std::sqrt(Rj * Rj - a * a);
      CAPTURE(eps);
      CHECK(VoronoiA::pair_conductance(R1, Rj, d, a, rij, ki, kj, ks, kf, p) ==
            rel(mono, 2.0 * eps + 1e-8));
    }
  }
  // the cone of the smaller particle carries r_ij: a larger partner conducts more
  CHECK(VoronoiA::multi(R1, 2 * R1, 3 * R1, 0.0, rij, 1.0, 1.0, kf, p) >
        VoronoiA::mono(R1, 2 * R1, 0.0, rij, 0.5, kf, p));
}

namespace {
/// Voronoi B conductance of the ray model integrated over the polar angle at centre i, with the
/// separating surface |O_i P| - R_i = |O_j P| - R_j found on each ray (independent of the
/// closed form and of its delta variable).
double voronoi_b_rays(double ri, double rj, double d, double a, double rij, double ki, double kj,
                      double kf, double c) {
  const double dr = rj - ri;
  auto t_of = [&](double th) { return (d * d - dr * dr) / (2.0 * (dr + d * std::cos(th))); };
  auto rho_of = [&](double th) { return t_of(th) * std::sin(th); };
  auto theta_at = [&](double rho) { // bisection: rho_of is increasing on the range used
    double lo = 0.0, hi = dr < 0.0 ? std::acos(-dr / d) : 0.5 * pi; // t -> inf at acos(-dr/d)
    for (int it = 0; it < 200; ++it) {
      const double m = 0.5 * (lo + hi);
      (rho_of(m) < rho ? lo : hi) = m;
    }
    return 0.5 * (lo + hi);
  };
  auto shell = [&](double R, double k, double rho) { // per steradian, core to rho
    return (1.0 / (c * R) - 1.0 / R) / k + (1.0 / R - 1.0 / rho) / kf;
  };
  auto f = [&](double th) {
    const double t = t_of(th), s = t + dr; // |O_i P|, |O_j P|
    const double dt = (d * d - dr * dr) * d * std::sin(th) /
                      (2.0 * std::pow(dr + d * std::cos(th), 2)); // dt/dtheta
    // cos(theta_j) = (d - t cos th)/s; its derivative in theta
    const double num = d - t * std::cos(th);
    const double dnum = -dt * std::cos(th) + t * std::sin(th);
    const double dcj = (dnum * s - num * dt) / (s * s);
    return 2.0 * pi / (shell(ri, ki, t) / std::sin(th) + shell(rj, kj, s) / std::abs(dcj));
  };
  const double lo = a > 0.0 ? theta_at(a) : 0.0;
  return detail::integrate(f, lo, theta_at(rij), {.abs_tol = 0.0, .rel_tol = 1e-12}).value;
}
} // namespace

TEST_CASE("indirect conduction, Voronoi B: multi-size (Chen et al. 2019), three Lambda cases") {
  const double R1 = 1e-3, R2 = 1.5e-3, R3 = 3e-3, kf = kf_air;
  const double rij = cell_radius(0.5 * (R1 + R2), 0.4);
  const VoronoiB::Params p;
  const double a = 2e-5;
  const double dt = std::sqrt(R1 * R1 - a * a) + std::sqrt(R2 * R2 - a * a);
  // Lambda > 0 (12-digit references, 30-digit arithmetic)
  CHECK(VoronoiB::multi(R1, R2, dt, a, rij, 1.0, 2.0, kf, p) == rel(2.29235324357e-4, 1e-9));
  CHECK(VoronoiB::multi(R1, R2, R1 + R2 + 5e-5, 0.0, rij, 1.0, 2.0, kf, p) ==
        rel(1.66711207477e-4, 1e-9));
  // Lambda < 0 (k_j = k_f) and Lambda = 0 (k_j = 2 k_f) for R_j = 3 R_i
  const double d3 = R1 + R3 + 1e-5;
  CHECK(VoronoiB::multi(R1, R3, d3, 0.0, rij, 1.0, kf, kf, p) == rel(1.52842055778e-5, 1e-9));
  CHECK(VoronoiB::multi(R1, R3, d3, 0.0, rij, 1.0, 2 * kf, kf, p) == rel(2.84824703988e-5, 1e-9));
  // continuous across Lambda = 0
  const double h0 = VoronoiB::multi(R1, R3, d3, 0.0, rij, 1.0, 2 * kf, kf, p);
  CHECK(VoronoiB::multi(R1, R3, d3, 0.0, rij, 1.0, 2 * kf * (1 + 1e-9), kf, p) == rel(h0, 1e-8));
  CHECK(VoronoiB::multi(R1, R3, d3, 0.0, rij, 1.0, 2 * kf * (1 - 1e-9), kf, p) == rel(h0, 1e-8));
  // the closed form equals the ray model integrated numerically, in all three cases
  struct Case {
    double ri, rj, d, a, ki, kj;
  };
  for (const Case& k : {Case{R1, R2, dt, a, 1.0, 2.0}, Case{R2, R1, dt, a, 2.0, 1.0},
                        Case{R1, R2, R1 + R2 + 5e-5, 0.0, 1.0, 2.0}, Case{R1, R3, d3, 0.0, 1.0, kf},
                        Case{R3, R1, d3, 0.0, kf, 1.0}, Case{R1, R3, d3, 0.0, 1.0, 2 * kf},
                        Case{R1, R1, 2 * R1, 0.0, 1.0, 3.0}}) {
    CAPTURE(k.ri);
    CAPTURE(k.rj);
    CAPTURE(k.kj);
    CHECK(VoronoiB::multi(k.ri, k.rj, k.d, k.a, rij, k.ki, k.kj, kf, p) ==
          rel(voronoi_b_rays(k.ri, k.rj, k.d, k.a, rij, k.ki, k.kj, kf, p.core_ratio), 1e-9));
  }
  // symmetric under swapping i and j, through conductance()
  const auto g12 = geom<3>(R1, R2, dt - R1 - R2), g21 = geom<3>(R2, R1, dt - R1 - R2);
  CHECK(H<VoronoiB>(g12, props(1.0, 2.0, kf), touching(R1, R2, a, rij)) ==
        rel(H<VoronoiB>(g21, props(2.0, 1.0, kf), touching(R2, R1, a, rij)), 1e-12));
  // tends to the mono-size value as R_j -> R_i
  const double mono = VoronoiB::mono(R1, 2 * std::sqrt(R1 * R1 - a * a), a, rij, 0.25, kf, p);
  for (double eps : {1e-3, 1e-6, 1e-9}) {
    const double Rj = R1 * (1.0 + eps);
    const double d = std::sqrt(R1 * R1 - a * a) + std::sqrt(Rj * Rj - a * a);
    CAPTURE(eps);
    CHECK(VoronoiB::pair_conductance(R1, Rj, d, a, rij, 1.0 / 3.0, 1.0, 0.25, kf, p) ==
          rel(mono, 2.0 * eps + 1e-9));
  }
}

TEST_CASE("indirect conduction, Voronoi A and B: cell radius, gap cutoff, degenerate inputs") {
  const double R = 1e-3, rij = cell_radius(R, 0.4);
  const auto p = props(1.0, 1.0, kf_air);
  const auto gt = geom<3>(R, R, 0.0);
  for (double cell : {0.0, -1.0, inf, std::numeric_limits<double>::quiet_NaN(), 1e-5}) {
    CAPTURE(cell);
    // H = 0 if r_ij <= a (a = 10 um), r_ij = 0 or infinite
    CHECK(H<VoronoiA>(gt, p, touching(R, R, 1e-5, cell)) == 0.0);
    CHECK(H<VoronoiB>(gt, p, touching(R, R, 1e-5, cell)) == 0.0);
  }
  CHECK(H<VoronoiA>(gt, p, touching(R, R, 1e-5, 1.0001e-5)) > 0.0);
  CHECK(H<VoronoiB>(gt, p, touching(R, R, 1e-5, 1.0001e-5)) > 0.0);
  // no fluid, or an insulating solid: nothing flows
  CHECK(H<VoronoiA>(gt, props(1, 1, 0.0), touching(R, R, 1e-5, rij)) == 0.0);
  CHECK(H<VoronoiB>(gt, props(1, 1, 0.0), touching(R, R, 1e-5, rij)) == 0.0);
  CHECK(H<VoronoiA>(gt, props(0, 1, kf_air), touching(R, R, 1e-5, rij)) == 0.0);
  CHECK(H<VoronoiB>(gt, props(0, 1, kf_air), touching(R, R, 1e-5, rij)) == 0.0);
  // across a gap: conducts up to max_gap_ratio * max(R_i, R_j), decreasing with the gap
  const VoronoiA::Params pa;
  const VoronoiB::Params pb;
  CHECK(VoronoiA::cutoff(pa, R) == doctest::Approx(0.5 * R));
  CHECK(VoronoiB::cutoff(pb, 2 * R) == doctest::Approx(1.0 * R));
  double la = inf, lb = inf;
  for (double gap : {0.0, 1e-6, 1e-5, 1e-4, 0.499e-3}) {
    CAPTURE(gap);
    const auto g = geom<3>(R, R, gap);
    const auto c = gap == 0.0 ? touching(R, R, 0.0, rij) : apart(R, R, gap, rij);
    const double ha = H<VoronoiA>(g, p, c), hb = H<VoronoiB>(g, p, c);
    CHECK(ha > 0.0);
    CHECK(ha < la);
    CHECK(hb > 0.0);
    CHECK(hb < lb);
    la = ha;
    lb = hb;
  }
  CHECK(H<VoronoiA>(geom<3>(R, R, 0.501e-3), p, apart(R, R, 0.501e-3, rij)) == 0.0);
  CHECK(H<VoronoiB>(geom<3>(R, R, 0.501e-3), p, apart(R, R, 0.501e-3, rij)) == 0.0);
  VoronoiA::Params wide = pa;
  wide.max_gap_ratio = 1.0;
  CHECK(H<VoronoiA>(geom<3>(R, R, 0.501e-3), p, apart(R, R, 0.501e-3, rij), wide) > 0.0);
  // continuous from gap to contact (a = 0)
  const double h0 = H<VoronoiA>(gt, p, touching(R, R, 0.0, rij));
  CHECK(H<VoronoiA>(geom<3>(R, R, 1e-13), p, apart(R, R, 1e-13, rij)) == rel(h0, 1e-8));
  const double b0 = H<VoronoiB>(gt, p, touching(R, R, 0.0, rij));
  CHECK(H<VoronoiB>(geom<3>(R, R, 1e-13), p, apart(R, R, 1e-13, rij)) == rel(b0, 1e-8));
  // Voronoi B: a larger isothermal core conducts more
  CHECK(H<VoronoiB>(gt, p, touching(R, R, 1e-5, rij), {.core_ratio = 0.8}) >
        H<VoronoiB>(gt, p, touching(R, R, 1e-5, rij), {.core_ratio = 0.5}));
}

TEST_CASE("indirect conduction, validation: bad parameters raise InputError") {
  CHECK(error_of([] { VoronoiA::validate({}); }).empty());
  CHECK(error_of([] { VoronoiB::validate({}); }).empty());
  CHECK(error_of([] { SurroundingLayer::validate({}); }).empty());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK(has(error_of([] { VoronoiA::validate({.max_gap_ratio = -0.1}); }),
            {"conduction::VoronoiA", "max_gap_ratio = -0.1", "[0, inf)"}));
  CHECK(has(error_of([] { VoronoiA::validate({.abs_tolerance = -1.0}); }),
            {"conduction::VoronoiA", "abs_tolerance = -1", "[0, inf)"}));
  CHECK(has(error_of([] { VoronoiA::validate({.rel_tolerance = 1.5}); }),
            {"conduction::VoronoiA", "rel_tolerance = 1.5", "[0, 1)"}));
  CHECK(has(error_of([] { VoronoiA::validate({.abs_tolerance = 0.0, .rel_tolerance = 0.0}); }),
            {"conduction::VoronoiA", "rel_tolerance = 0", "when abs_tolerance = 0"}));
  CHECK(has(error_of([] { VoronoiB::validate({.core_ratio = 0.0}); }),
            {"conduction::VoronoiB", "core_ratio = 0", "(0, 1]"}));
  CHECK(has(error_of([] { VoronoiB::validate({.core_ratio = 1.2}); }),
            {"conduction::VoronoiB", "core_ratio = 1.2", "(0, 1]"}));
  CHECK(has(error_of([&] { VoronoiB::validate({.max_gap_ratio = nan}); }),
            {"conduction::VoronoiB", "max_gap_ratio = nan"}));
  CHECK(has(error_of([] { SurroundingLayer::validate({.layer_ratio = 0.0}); }),
            {"conduction::SurroundingLayer", "layer_ratio = 0", "(0, inf)"}));
  CHECK(has(error_of([] { SurroundingLayer::validate({.min_gap = 0.0}); }),
            {"conduction::SurroundingLayer", "min_gap = 0", "(0, inf) m"}));
  CHECK(has(error_of([] { SurroundingLayer::validate({.rel_tolerance = -1e-6}); }),
            {"conduction::SurroundingLayer", "rel_tolerance = -1e-06", "[0, 1)"}));
  // through Combined
  using C = conduction::Combined<conduction::BatchelorOBrien, SurroundingLayer>;
  CHECK(has(error_of([] { C::validate({.indirect = {.layer_ratio = -1.0}}); }),
            {"conduction::SurroundingLayer", "layer_ratio = -1"}));
  CHECK(C::cutoff({}, 2e-3) == doctest::Approx(0.8e-3));
  CHECK(ContactVA::cutoff({.conduction = {.indirect = {.max_gap_ratio = 1.0}}}, 2e-3) ==
        doctest::Approx(2e-3));
}
