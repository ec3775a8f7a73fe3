#pragma once
/// \file voronoi_a.hpp
/// Indirect conduction through the interstitial fluid, model A of Cheng, Yu & Zulli (Int. J.
/// Heat Mass Transfer 42 (1999) 2565): the fluid cell shared by a pair is a double cone with
/// its apexes at the two centres and a base of radius r_ij in the plane between them; the cone
/// surfaces are isothermal and the heat flows parallel to the axis. A tube at distance r from the
/// axis crosses solid (cone surface to sphere surface), fluid (sphere to sphere) and solid again:
///
///   mono-size pair (R_i = R_j = R, D = d/2, k_s = k* = k_i k_j/(k_i + k_j)):
///     r_sf = R r_ij / sqrt(r_ij^2 + D^2)
///     H = int_a^r_sf 2 pi r dr / [ (sqrt(R^2 - r^2) - D r/r_ij)/k_s
///                                  + 2 (D - sqrt(R^2 - r^2))/k_f ]                  [W/K]
///
///   With k_s = k* the solid term is exactly the two halves in series,
///   (...)/k_i + (...)/k_j = (...)/k*; for equal materials k* = k/2.
///
///   multi-size pair (Gan, Zhou & Yu), s = the smaller sphere, l = the larger, d the centre
///   distance; the plane is the radical plane, D_s = (R_s^2 - R_l^2 + d^2)/(2 d), D_l = d - D_s
///   (while touching, the contact plane: D_s = sqrt(R_s^2 - a^2)). The cone of the
///   smaller sphere has the base r_ij, that of the larger one meets its sphere at the same radius
///   r_sf (base r_l), so that both cones end on the same flux tube:
///     r_sf = R_s r_ij / sqrt(r_ij^2 + D_s^2),  r_l = D_l r_sf / sqrt(R_l^2 - r_sf^2)
///     H = int_a^r_sf 2 pi r dr / [ (sqrt(R_s^2 - r^2) - D_s r/r_ij)/k_s
///                                  + (sqrt(R_l^2 - r^2) - D_l r/r_l)/k_l
///                                  + (d - sqrt(R_s^2 - r^2) - sqrt(R_l^2 - r^2))/k_f ]
///   with k_s, k_l the conductivities of the smaller and the larger particle. The result is
///   symmetric in i and j and tends to the mono-size value as R_j -> R_i. (Anchoring r_ij at the
///   smaller sphere keeps r_sf < R_s, so both cones always meet their spheres.) Radii that differ
///   by less than 1e-12 relative count as mono-size.
///
///   particle-wall (the wall is a flat isothermal plane at distance d from the centre, k_p the
///   particle's conductivity; the wall's own conductivity does not enter):
///     r_sf = R r_ij / sqrt(r_ij^2 + d^2)
///     H = int_a^r_sf 2 pi r dr / [ (sqrt(R^2 - r^2) - d r/r_ij)/k_p + (d - sqrt(R^2 - r^2))/k_f ]
///
/// Inputs (SI): a [m] the contact radius (0 across a gap), d [m] the centre distance (for a
/// wall the centre-to-surface distance), r_ij [m] the fluid-cell radius supplied by the
/// simulation (`HeatContext::cell_radius`: half a Voronoi edge, or 0.56 R (1 - phi)^(-1/3) from a
/// porosity phi, Yang, Zou & Yu), k [W/(m K)] from `PairProperties` and k_f its
/// `fluid_conductivity`. H = 0 if r_ij <= a, r_ij is 0 or infinite, k_f = 0, a solid has k = 0, or
/// the gap exceeds `max_gap_ratio` max(R_i, R_j) (walls: R_i).
///
/// The integrals are evaluated by adaptive Gauss-Kronrod quadrature (core/quadrature.hpp) in the
/// polar angle phi of the smaller sphere (r = R_s sin phi), which keeps the integrand smooth.
///
/// Validity: a fluid much less conductive than the solid, particles in a dense packing (the
/// double-cone cell), k_f continuum (no Knudsen or radiation correction). 2D disks use the sphere
/// formulas unchanged (the conductance of the equivalent spheres; `HeatContext::length` is not
/// used). Walls are flat: a circle wall is treated as its tangent plane. Direct conduction
/// through the contact area is not included; combine with a direct model, e.g.
/// `Combined<BatchelorOBrien, VoronoiA>`.

#include <algorithm>
#include <cmath>
#include <grain/core/error.hpp>
#include <grain/core/quadrature.hpp>
#include <grain/models/concepts.hpp>
#include <numbers>

namespace grain::conduction {

struct VoronoiA {
  static constexpr Slot slot = Slot::conduction;
  static constexpr const char* name = "Voronoi A";
  static constexpr const char* object = "conduction::VoronoiA";
  static constexpr bool thermal = true;
  static constexpr bool indirect = true;
  static constexpr bool uses_cell_radius = true;

  struct Params {
    /// Largest gap across which a pair conducts, as a fraction of the larger radius; also sizes
    /// the neighbour search (`cutoff`).
    double max_gap_ratio = 0.5;
    double abs_tolerance = 1e-15; ///< absolute tolerance of the quadrature [W/K]
    double rel_tolerance = 1e-9;  ///< relative tolerance of the quadrature
  };
  template <int D>
  struct History {};

  static void validate(const Params& p) {
    detail::require_non_negative(object, "max_gap_ratio", p.max_gap_ratio);
    detail::require_non_negative(object, "abs_tolerance", p.abs_tolerance);
    detail::require(std::isfinite(p.rel_tolerance) && p.rel_tolerance >= 0.0 &&
                        p.rel_tolerance < 1.0,
                    object, "rel_tolerance", p.rel_tolerance, "[0, 1)");
    detail::require(p.abs_tolerance > 0.0 || p.rel_tolerance > 0.0, object, "rel_tolerance",
                    p.rel_tolerance, "(0, 1) when abs_tolerance = 0");
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
    const double phi_a = lower_angle(R, a);
    const double phi_sf = std::atan2(rij, D); // the cone meets the sphere at r = R sin(phi_sf)
    if (!(phi_sf > phi_a)) return 0.0;
    auto f = [&](double phi) {
      const double r = R * std::sin(phi), z = R * std::cos(phi);
      const double den = (z - D * r / rij) / ks + 2.0 * (D - z) / kf;
      return 2.0 * std::numbers::pi * r * z / den; // 2 pi r dr/den, dr = z dphi
    };
    return finite_or_zero(detail::integrate(f, phi_a, phi_sf, options(p)).value);
  }

  /// Pair of any sizes (Gan, Zhou & Yu): radii ri, rj [m], centre distance d [m], contact radius
  /// a [m], cell radius rij [m], conductivities ki, kj, kf [W/(m K)]. H [W/K], symmetric in i, j.
  static double multi(double ri, double rj, double d, double a, double rij, double ki, double kj,
                      double kf, const Params& p) {
    const bool i_small = ri <= rj;
    const double Rs = i_small ? ri : rj, Rl = i_small ? rj : ri;
    const double ks = i_small ? ki : kj, kl = i_small ? kj : ki;
    if (!(Rs > 0.0 && d > 0.0 && ks > 0.0 && kl > 0.0 && kf > 0.0 && rij > a)) return 0.0;
    const double Ds = (Rs * Rs - Rl * Rl + d * d) / (2.0 * d); // radical plane
    const double Dl = d - Ds;
    if (!(Ds > 0.0 && Dl > 0.0)) return 0.0;
    const double phi_a = lower_angle(Rs, a);
    const double phi_sf = std::atan2(rij, Ds);
    if (!(phi_sf > phi_a)) return 0.0;
    const double r_sf = Rs * std::sin(phi_sf);
    const double rl = Dl * r_sf / std::sqrt((Rl - r_sf) * (Rl + r_sf)); // base of the l cone
    auto f = [&](double phi) {
      const double r = Rs * std::sin(phi), zs = Rs * std::cos(phi);
      const double zl = std::sqrt((Rl - r) * (Rl + r));
      const double den = (zs - Ds * r / rij) / ks + (zl - Dl * r / rl) / kl + (d - zs - zl) / kf;
      return 2.0 * std::numbers::pi * r * zs / den;
    };
    return finite_or_zero(detail::integrate(f, phi_a, phi_sf, options(p)).value);
  }

  /// Mono-size (with k* = `k_eff`) or multi-size (with ki, kj) as the radii decide. H [W/K].
  static double pair_conductance(double ri, double rj, double d, double a, double rij, double ki,
                                 double kj, double k_eff, double kf, const Params& p) {
    return same_size(ri, rj) ? mono(ri, d, a, rij, k_eff, kf, p)
                             : multi(ri, rj, d, a, rij, ki, kj, kf, p);
  }

  /// Particle (radius R [m], conductivity kp) and a flat wall at distance d [m] from its centre.
  static double wall(double R, double d, double a, double rij, double kp, double kf,
                     const Params& p) {
    if (!(R > 0.0 && d > 0.0 && kp > 0.0 && kf > 0.0 && rij > a)) return 0.0;
    const double phi_a = lower_angle(R, a);
    const double phi_sf = std::atan2(rij, d);
    if (!(phi_sf > phi_a)) return 0.0;
    auto f = [&](double phi) {
      const double r = R * std::sin(phi), z = R * std::cos(phi);
      const double den = (z - d * r / rij) / kp + (d - z) / kf;
      return 2.0 * std::numbers::pi * r * z / den;
    };
    return finite_or_zero(detail::integrate(f, phi_a, phi_sf, options(p)).value);
  }

private:
  static detail::QuadratureOptions options(const Params& p) {
    detail::QuadratureOptions o;
    o.abs_tol = p.abs_tolerance;
    o.rel_tol = p.rel_tolerance;
    return o;
  }
  /// Polar angle of the contact circle of radius a on a sphere of radius R.
  static double lower_angle(double R, double a) {
    if (!(a > 0.0)) return 0.0;
    if (a >= R) return 0.5 * std::numbers::pi;
    return std::atan2(a, std::sqrt((R - a) * (R + a)));
  }
  static double finite_or_zero(double h) { return std::isfinite(h) && h > 0.0 ? h : 0.0; }
};

} // namespace grain::conduction
