#pragma once
/// \file voronoi_b.hpp
/// Indirect conduction through the interstitial fluid, model B of Cheng, Yu & Zulli (Int. J.
/// Heat Mass Transfer 42 (1999) 2565): each particle has an isothermal core of radius
/// r_c = c R (c = `core_ratio`), and the heat flows along rays from the core centre, through
/// the solid shell (r_c to R) and the fluid up to the surface that separates the pair. The rays
/// that reach that surface between the contact radius a and the fluid-cell radius r_ij conduct.
/// Closed forms:
///
///   mono-size pair (R_i = R_j = R, D = d/2, k_s = k* = k_i k_j/(k_i + k_j)):
///     A = (1/r_c - 1/R)/(2 k_s) + 1/(k_f R),  B = 1/(k_f D)
///     c_0 = D/sqrt(r_ij^2 + D^2),  c_1 = D/sqrt(a^2 + D^2)
///     H = (pi/B) ln[(A - B c_0)/(A - B c_1)]                                         [W/K]
///   (summing the two shells in series gives (1/r_c - 1/R)(1/k_i + 1/k_j) = (1/r_c - 1/R)/k*,
///   hence k_s = k*, = k/2 for equal materials).
///
///   particle-wall (flat isothermal wall at distance d from the centre, k_p of the particle):
///     A = (1/r_c - 1/R)/(2 k_p) + 1/(2 k_f R),  B = 1/(2 k_f d),  c_0, c_1 as above with d
///     H = (pi/B) ln[(A - B c_0)/(A - B c_1)]
///
///   multi-size pair (Chen et al. 2019): the separating surface is the hyperboloid on which the
///   fluid gaps to both spheres are equal, |O_i P| - R_i = |O_j P| - R_j; a point P of it is
///   labelled by delta = |O_i P|/d. With gamma_k = R_k/d, dgamma = gamma_j - gamma_i,
///     A' = (k_i + k_f (1/c - 1))/(k_i gamma_i),  B' = (k_j + k_f (1/c - 1))/(k_j gamma_j)
///   the ray pair through P has the resistance per ring of
///     Q(delta) = delta (A' delta - 1) + (delta + dgamma)(B' (delta + dgamma) - 1)
///              = (A' + B') delta^2 + 2 (dgamma B' - 1) delta - dgamma (1 - dgamma B')
///     H = pi k_f d (1 - dgamma^2) int_delta_min^delta_max d delta / Q(delta)
///     delta_max,min = [sqrt(4 rho^2/(d^2 (1 - dgamma^2)) + 1) - dgamma]/2,  rho = r_ij, a
///   (rho is the distance of P from the axis). With X = ((A' + B') delta + dgamma B' - 1)/sqrt|L|
///   and L = (1 + dgamma A')(1 - dgamma B'):
///     L > 0: H = pi k_f d (1 - dgamma^2) ln|(1 - Y1)/(1 + Y1)| / (2 sqrt L),
///            Y1 = (X_max - X_min)/(1 - X_max X_min)
///     L < 0: H = pi k_f d (1 - dgamma^2) [atan X_max - atan X_min] / sqrt|L|
///     L = 0: H = pi k_f d (1 - dgamma^2) [1/y_min - 1/y_max],  y = (A' + B') delta + dgamma B' - 1
///   These are the exact antiderivatives of 1/Q; they are evaluated in one form that is
///   continuous in L and free of cancellation near L = 0. (The formula sheet of DEMLab has
///   atan(Y2)/(2 sqrt|L|) for L < 0, half the integral, and 1/delta in place of 1/y for L = 0,
///   which holds only when dgamma B' = 1; both are corrected here.) H is symmetric in i and j and
///   equals the mono-size value at R_i = R_j (with k_i, k_j in series as above). Radii that
///   differ by less than 1e-12 relative count as mono-size.
///
/// Inputs (SI): a [m] the contact radius (0 across a gap), d [m] the centre distance (for a wall
/// the centre-to-surface distance), r_ij [m] the fluid-cell radius supplied by the simulation
/// (`HeatContext::cell_radius`: half a Voronoi edge, or 0.56 R (1 - phi)^(-1/3) from a porosity
/// phi), k [W/(m K)] from `PairProperties` and k_f its `fluid_conductivity`. H = 0 if r_ij <= a,
/// r_ij is 0 or infinite, k_f = 0, a solid has k = 0, or the gap exceeds `max_gap_ratio`
/// max(R_i, R_j) (walls: R_i).
///
/// Validity: as model A (Cheng et al.): k_f << k_s, dense packings, continuum fluid. Model B is
/// meant for k_s/k_f not too large (the isothermal core replaces the solid's own resistance
/// distribution). 2D disks use the sphere formulas unchanged (`HeatContext::length` is not
/// used); walls are flat (a circle wall counts as its tangent plane). Direct conduction through
/// the contact area is not included; combine with a direct model.

#include <algorithm>
#include <cmath>
#include <grain/core/error.hpp>
#include <grain/models/concepts.hpp>
#include <numbers>

namespace grain::conduction {

struct VoronoiB {
  static constexpr Slot slot = Slot::conduction;
  static constexpr const char* name = "Voronoi B";
  static constexpr const char* object = "conduction::VoronoiB";
  static constexpr bool thermal = true;
  static constexpr bool indirect = true;
  static constexpr bool uses_cell_radius = true;

  struct Params {
    double core_ratio = 0.5; ///< c = r_c/R, isothermal core radius over particle radius
    /// Largest gap across which a pair conducts, as a fraction of the larger radius; also sizes
    /// the neighbour search (`cutoff`).
    double max_gap_ratio = 0.5;
  };
  template <int D>
  struct History {};

  static void validate(const Params& p) {
    detail::require(std::isfinite(p.core_ratio) && p.core_ratio > 0.0 && p.core_ratio <= 1.0,
                    object, "core_ratio", p.core_ratio, "(0, 1]");
    detail::require_non_negative(object, "max_gap_ratio", p.max_gap_ratio);
  }

  /// Largest gap [m] across which the model conducts, for particles of radius <= r_max [m].
  static double cutoff(const Params& p, double r_max) { return p.max_gap_ratio * r_max; }

  template <int D>
  static double conductance(const ContactGeometry<D>& g, const PairProperties& pair,
                            const HeatContext& c, const Params& p, History<D>&) {
    const double kf = pair.fluid_conductivity;
    const double a = c.touching ? c.contact_radius : 0.0;
    const double rij = c.cell_radius;
    if (!(kf > 0.0) || !(std::isfinite(rij) && rij > a)) return 0.0;
    const double r_ref = g.wall ? g.radius_i : std::max(g.radius_i, g.radius_j);
    if (!c.touching && !(c.gap <= p.max_gap_ratio * r_ref)) return 0.0;
    if (g.wall) return wall(g.radius_i, c.distance, a, rij, pair.conductivity_i, kf, p);
    return pair_conductance(g.radius_i, g.radius_j, c.distance, a, rij, pair.conductivity_i,
                            pair.conductivity_j, pair.conductivity_eff, kf, p);
  }

  /// True if two radii count as equal (relative difference <= 1e-12).
  static bool same_size(double ri, double rj) {
    return std::abs(ri - rj) <= 1e-12 * std::max(std::abs(ri), std::abs(rj));
  }

  /// Mono-size pair: radius R [m], centre distance d [m], contact radius a [m] (0 across a
  /// gap), cell radius rij [m], solid conductivity ks = k* [W/(m K)], fluid kf. H [W/K].
  static double mono(double R, double d, double a, double rij, double ks, double kf,
                     const Params& p) {
    const double D = 0.5 * d;
    if (!(R > 0.0 && D > 0.0 && ks > 0.0 && kf > 0.0 && rij > a)) return 0.0;
    const double rc = p.core_ratio * R;
    const double A = (1.0 / rc - 1.0 / R) / (2.0 * ks) + 1.0 / (kf * R);
    const double B = 1.0 / (kf * D);
    return closed_form(A, B, D, a, rij);
  }

  /// Particle (radius R [m], conductivity kp) and a flat wall at distance d [m] from its centre.
  static double wall(double R, double d, double a, double rij, double kp, double kf,
                     const Params& p) {
    if (!(R > 0.0 && d > 0.0 && kp > 0.0 && kf > 0.0 && rij > a)) return 0.0;
    const double rc = p.core_ratio * R;
    const double A = (1.0 / rc - 1.0 / R) / (2.0 * kp) + 1.0 / (2.0 * kf * R);
    const double B = 1.0 / (2.0 * kf * d);
    return closed_form(A, B, d, a, rij);
  }

  /// Pair of any sizes (Chen et al. 2019): radii ri, rj [m], centre distance d [m], contact
  /// radius a [m], cell radius rij [m], conductivities ki, kj, kf [W/(m K)]. H [W/K].
  static double multi(double ri, double rj, double d, double a, double rij, double ki, double kj,
                      double kf, const Params& p) {
    if (!(ri > 0.0 && rj > 0.0 && d > 0.0 && ki > 0.0 && kj > 0.0 && kf > 0.0 && rij > a))
      return 0.0;
    const double gi = ri / d, gj = rj / d, dg = gj - gi;
    const double one_m = 1.0 - dg * dg; // 1 - dgamma^2 > 0 unless one sphere holds the other
    if (!(one_m > 0.0)) return 0.0;
    const double core = kf * (1.0 / p.core_ratio - 1.0);
    const double Ap = (ki + core) / (ki * gi), Bp = (kj + core) / (kj * gj);
    const double L = (1.0 + dg * Ap) * (1.0 - dg * Bp);
    auto delta_at = [&](double rho) {
      return 0.5 * (std::sqrt(4.0 * rho * rho / (d * d * one_m) + 1.0) - dg);
    };
    const double P = Ap + Bp, q = dg * Bp - 1.0;
    const double y0 = P * delta_at(a) + q, y1 = P * delta_at(rij) + q;
    const double h = std::numbers::pi * kf * d * one_m * inverse_quadratic_integral(y0, y1, L);
    return std::isfinite(h) && h > 0.0 ? h : 0.0;
  }

  /// Mono-size (with k* = `k_eff`) or multi-size (with ki, kj) as the radii decide. H [W/K].
  static double pair_conductance(double ri, double rj, double d, double a, double rij, double ki,
                                 double kj, double k_eff, double kf, const Params& p) {
    return same_size(ri, rj) ? mono(ri, d, a, rij, k_eff, kf, p)
                             : multi(ri, rj, d, a, rij, ki, kj, kf, p);
  }

  /// int_y0^y1 dy / (y^2 - L) for y^2 > L on [y0, y1]: (atanh(s/y0) - atanh(s/y1))/s with
  /// s = sqrt(L) for L > 0, (atan(y1/s) - atan(y0/s))/s with s = sqrt(-L) for L < 0,
  /// 1/y0 - 1/y1 for L = 0; written as F(s/y0)/y0 - F(s/y1)/y1 with F(z) = atanh(z)/z or
  /// atan(z)/z (F(0) = 1), continuous in L.
  static double inverse_quadratic_integral(double y0, double y1, double L) {
    const double s = std::sqrt(std::abs(L));
    if (L < 0.0 && !(y0 * y1 > 0.0)) return (std::atan(y1 / s) - std::atan(y0 / s)) / s;
    auto F = [&](double z) {
      const double z2 = z * z;
      if (std::abs(z) < 1e-4) // series, error < z^8/9
        return L > 0.0 ? 1.0 + z2 * (1.0 / 3.0 + z2 * (1.0 / 5.0 + z2 / 7.0))
                       : 1.0 - z2 * (1.0 / 3.0 - z2 * (1.0 / 5.0 - z2 / 7.0));
      return L > 0.0 ? std::atanh(z) / z : std::atan(z) / z;
    };
    return F(s / y0) / y0 - F(s / y1) / y1;
  }

private:
  /// (pi/B) ln[(A - B c0)/(A - B c1)] with c0 = D/sqrt(rij^2 + D^2), c1 = D/sqrt(a^2 + D^2).
  static double closed_form(double A, double B, double D, double a, double rij) {
    const double c0 = D / std::hypot(rij, D), c1 = D / std::hypot(a, D);
    const double den = A - B * c1;
    if (!(den > 0.0 && c1 > c0)) return 0.0;
    const double h = std::numbers::pi / B * std::log1p(B * (c1 - c0) / den);
    return std::isfinite(h) && h > 0.0 ? h : 0.0;
  }
};

} // namespace grain::conduction
