#pragma once
/// \file surrounding_layer.hpp
/// Indirect conduction through a fluid layer around each particle (Rong & Horio, 2nd Int. Conf.
/// CFD in the Minerals and Process Industries, CSIRO, 1999; Musser, PhD thesis, West Virginia
/// University, 2011, for unequal sizes; Morris et al., Int. J. Heat Mass Transfer 89 (2015)
/// 1277, analytic wall form): heat crosses the fluid between the two surfaces along lines
/// parallel to the axis of the pair, inside the layer of thickness L = lambda R_l around the
/// larger particle (lambda = `layer_ratio`); the fluid gap is never taken below S (`min_gap`):
///
///   particle-particle (R_s <= R_l the two radii, d the centre distance, a the contact radius):
///     g(r) = d - sqrt(R_i^2 - r^2) - sqrt(R_j^2 - r^2)             (local fluid gap)
///     H = k_f int_a^r_sf 2 pi r dr / max(S, g(r))                                     [W/K]
///     r_sf = R_s                                   if d <= sqrt((R_l + L)^2 - R_s^2)
///          = radius of the circle where the sphere R_l + L meets the sphere R_s, otherwise
///   H = 0 once the layer no longer reaches the smaller sphere (gap >= L). The integral is
///   evaluated by adaptive Gauss-Kronrod quadrature (core/quadrature.hpp) in the polar angle of
///   the smaller sphere, split where g(r) = S (the kink of max), so that S is honoured exactly;
///   or, with `closed_form = true` (the default), exactly (see `pair_closed_form`: with u = d - g the lens
///   relations make 2 pi r dr a rational function of g), to round-off and about 100 times
///   faster.
///
///   particle-wall (flat wall at distance d from the centre, R the particle's radius), in closed
///   form: with r_out = min(R, sqrt((R + L)^2 - d^2)) (where the layer meets the wall),
///   s(r) = sqrt(R^2 - r^2), and r_in the radius where d - s(r) = S (r_in = a if the gap d - R
///   is >= S):
///     H = k_f pi (r_in^2 - a^2)/S
///       + 2 pi k_f [ d ln((d - s(r_out))/(d - s(r_in))) + s(r_out) - s(r_in) ]
///   (both terms up to r_out only). This is the integral k_f int_a^r_out 2 pi r dr /
///   max(S, d - s(r)); the logarithmic term is the form of Morris et al.,
///   2 pi k_f R [(a'+1) ln(|b - a' - 1|/|a' - c + 1|) + b - c], a' = (d - R)/R, b = s(r_out)/R,
///   c = s(r_in)/R. The first term, the disc r < r_in where the gap is held at S, is missing
///   from the wall form of DEMLab's formula sheet; it matters only for gaps below S (contact).
///
/// Inputs (SI): a [m] (0 across a gap), d [m] (for a wall the centre-to-surface distance),
/// k_f [W/(m K)] = `PairProperties::fluid_conductivity` (H = 0 if it is 0). The solids'
/// conductivities do not enter (the solid resistance is neglected: k_s >> k_f).
///
/// Validity: k_s >> k_f; S << R (S stands for surface roughness or the mean free path of a gas;
/// H at contact grows like ln(R/S)); continuum fluid. 2D disks use the sphere formulas
/// unchanged (`HeatContext::length` is not used); walls are flat (a circle wall counts as its
/// tangent plane). Direct conduction through the contact area is not included; combine with a
/// direct model, e.g. `Combined<BatchelorOBrien, SurroundingLayer>`.

#include <algorithm>
#include <cmath>
#include <grain/core/error.hpp>
#include <grain/core/quadrature.hpp>
#include <grain/models/concepts.hpp>
#include <numbers>

namespace grain::conduction {

struct SurroundingLayer {
  static constexpr Slot slot = Slot::conduction;
  static constexpr const char* name = "surrounding layer";
  static constexpr const char* object = "conduction::SurroundingLayer";
  static constexpr bool thermal = true;
  static constexpr bool indirect = true;
  static constexpr bool uses_cell_radius = false;

  struct Params {
    double layer_ratio = 0.4;     ///< lambda = L/R_l, layer thickness over the larger radius
    double min_gap = 2.75e-8;     ///< S, smallest fluid gap [m]
    double abs_tolerance = 1e-15; ///< absolute tolerance of the quadrature [W/K]
    double rel_tolerance = 1e-9;  ///< relative tolerance of the quadrature
    /// Particle-particle integral in closed form (`pair_closed_form`, the default) or by
    /// quadrature (false): the same value (to 1e-11 relative for R_l/R_s <= 100); the closed form
    /// is about 100 times faster.
    bool closed_form = true;
  };
  template <int D>
  struct History {};

  static void validate(const Params& p) {
    detail::require_positive(object, "layer_ratio", p.layer_ratio);
    detail::require(std::isfinite(p.min_gap) && p.min_gap > 0.0, object, "min_gap", p.min_gap,
                    "(0, inf) m, well below the smallest radius");
    detail::require_non_negative(object, "abs_tolerance", p.abs_tolerance);
    detail::require(std::isfinite(p.rel_tolerance) && p.rel_tolerance >= 0.0 &&
                        p.rel_tolerance < 1.0,
                    object, "rel_tolerance", p.rel_tolerance, "[0, 1)");
    detail::require(p.abs_tolerance > 0.0 || p.rel_tolerance > 0.0, object, "rel_tolerance",
                    p.rel_tolerance, "(0, 1) when abs_tolerance = 0");
  }

  /// Largest gap [m] across which the model conducts, for particles of radius <= r_max [m].
  static double cutoff(const Params& p, double r_max) { return p.layer_ratio * r_max; }

  template <int D>
  static double conductance(const ContactGeometry<D>& g, const PairProperties& pair,
                            const HeatContext& c, const Params& p, History<D>&) {
    const double kf = pair.fluid_conductivity;
    if (!(kf > 0.0)) return 0.0;
    const double a = c.touching ? c.contact_radius : 0.0;
    if (g.wall) return wall(g.radius_i, c.distance, a, kf, p);
    return pair_conductance(g.radius_i, g.radius_j, c.distance, a, kf, p);
  }

  /// Particle-particle: radii ri, rj [m], centre distance d [m], contact radius a [m] (0 across
  /// a gap), fluid conductivity kf [W/(m K)]. H [W/K], by quadrature or, with
  /// `Params::closed_form`, in closed form (`pair_closed_form`).
  static double pair_conductance(double ri, double rj, double d, double a, double kf,
                                 const Params& p) {
    if (p.closed_form) return pair_closed_form(ri, rj, d, a, kf, p);
    const Setup s = setup(ri, rj, d, a, kf, p);
    if (!s.conducts) return 0.0;
    const double S = p.min_gap, Rs = s.Rs, Rl = s.Rl;
    const double half_pi = 0.5 * std::numbers::pi;
    // polar angles (on the smaller sphere, from the axis) of a, of r_sf and of the kink g = S
    const double phi_a = angle(Rs, a), phi_sf = s.sf_equator ? half_pi : std::atan2(s.r_sf, s.z_sf);
    double phi_S = phi_a; // no kink: g >= S everywhere
    if (s.g_a < S) phi_S = s.g_sf <= S ? half_pi : std::atan2(s.r_S, s.z_S);
    auto f = [&](double phi) {
      const double r = Rs * std::sin(phi), zs = Rs * std::cos(phi);
      const double zl = std::sqrt((Rl - r) * (Rl + r));
      return 2.0 * std::numbers::pi * r * zs / std::max(S, d - zs - zl);
    };
    const double h = kf * detail::integrate_split(f, phi_a, phi_sf, {phi_S}, options(p)).value;
    return std::isfinite(h) && h > 0.0 ? h : 0.0;
  }

  /// The particle-particle integral in closed form. Along a line at distance r from the axis
  /// the gap is g = d - z_i - z_j with z_k = sqrt(R_k^2 - r^2); with u = d - g = z_i + z_j and
  /// Delta = R_i^2 - R_j^2 the lens relations z_i = (u^2 + Delta)/(2u), z_j = (u^2 - Delta)/(2u)
  /// give 2 pi r dr = (pi/2) (u - Delta^2/u^3) dg, hence, between the gaps g_0 = max(S, g(a)) and
  /// g_1 = g(r_sf),
  ///   H = k_f pi (r_S^2 - a^2)/S + k_f (pi/2) [G(g_1) - G(g_0)],
  ///   G(g) = d ln g - g - Delta^2 [ (ln g - ln u)/d^3 + 1/(d^2 u) + 1/(2 d u^2) ],
  /// r_S the radius where g = S (the first term only where g(a) < S). Same value as the
  /// quadrature; the Delta^2 term cancels about log10(R_l/R_s) digits.
  static double pair_closed_form(double ri, double rj, double d, double a, double kf,
                                 const Params& p) {
    const Setup s = setup(ri, rj, d, a, kf, p);
    if (!s.conducts) return 0.0;
    const double S = p.min_gap, pi = std::numbers::pi;
    double h = 0.0, g0 = s.g_a;
    if (g0 < S) {
      const double r_S = s.g_sf <= S ? s.r_sf : s.r_S;
      h = kf * pi * (r_S * r_S - a * a) / S;
      g0 = S;
    }
    const double g1 = s.g_sf;
    if (g1 > g0) {
      const double dg = g1 - g0, u0 = d - g0, u1 = d - g1;
      const double lg = std::log(g1 / g0), lu = std::log1p(-dg / u0); // ln(u1/u0)
      const double delta = (ri - rj) * (ri + rj), delta2 = delta * delta;
      const double bracket = (lg - lu) / (d * d * d) + dg / (d * d * u1 * u0) +
                             dg * (u0 + u1) / (2.0 * d * u1 * u1 * u0 * u0);
      h += kf * 0.5 * pi * (d * lg - dg - delta2 * bracket);
    }
    return std::isfinite(h) && h > 0.0 ? h : 0.0;
  }

  /// Particle (radius R [m]) and a flat wall at distance d [m] from its centre, contact radius a
  /// [m] (0 across a gap), fluid conductivity kf [W/(m K)]. H [W/K] in closed form.
  static double wall(double R, double d, double a, double kf, const Params& p) {
    const double L = p.layer_ratio * R, Ro = R + L, S = p.min_gap;
    if (!(R > 0.0 && d > 0.0 && kf > 0.0 && S > 0.0 && d < Ro)) return 0.0;
    // outer radius: where the layer meets the wall (or the particle's equator)
    double r_out = R, s_out = 0.0;
    if (d * d + R * R > Ro * Ro) {
      r_out = std::sqrt((Ro - d) * (Ro + d));
      s_out = std::sqrt(std::max(d * d - L * (R + Ro), 0.0));
    }
    if (!(r_out > a)) return 0.0;
    const double gap0 = d - R;
    const double pi = std::numbers::pi;
    // disc a <= r < r_in where the gap is held at S; s_in = sqrt(R^2 - r_in^2), gap_in = d - s_in
    double r_in = a, s_in = std::sqrt((R - a) * (R + a)), gap_in = d - s_in;
    if (gap0 < S) {
      const double s = d - S; // height of the circle where the gap equals S
      if (s <= 0.0) return kf * pi * (r_out * r_out - a * a) / S;
      const double r = std::sqrt(std::max((S - gap0) * (R + s), 0.0));
      if (r > a) {
        r_in = r;
        s_in = s;
        gap_in = S;
      }
    }
    if (r_in >= r_out) return kf * pi * (r_out * r_out - a * a) / S;
    const double clamped = kf * pi * (r_in * r_in - a * a) / S;
    const double layer = 2.0 * pi * kf * (d * std::log((d - s_out) / gap_in) + s_out - s_in);
    const double h = clamped + layer;
    return std::isfinite(h) && h > 0.0 ? h : 0.0;
  }

private:
  static detail::QuadratureOptions options(const Params& p) {
    detail::QuadratureOptions o;
    o.abs_tol = p.abs_tolerance;
    o.rel_tol = p.rel_tolerance;
    return o;
  }
  /// Geometry shared by both evaluations of the particle-particle integral.
  struct Setup {
    bool conducts = false;
    bool sf_equator = false; ///< r_sf = R_s (the layer reaches past the smaller equator)
    double Rs = 0, Rl = 0;
    double r_sf = 0, z_sf = 0; ///< r_sf and sqrt(R_s^2 - r_sf^2)
    double g_a = 0, g_sf = 0;  ///< gaps at r = a and at r = r_sf
    double r_S = 0, z_S = 0;   ///< where the gap is S (if g_a < S < g_sf)
  };
  static Setup setup(double ri, double rj, double d, double a, double kf, const Params& p) {
    Setup s;
    s.Rs = std::min(ri, rj);
    s.Rl = std::max(ri, rj);
    const double Rs = s.Rs, Rl = s.Rl, S = p.min_gap;
    const double Ro = Rl + p.layer_ratio * Rl; // outer radius of the layer
    if (!(Rs > 0.0 && d > 0.0 && kf > 0.0 && S > 0.0 && d < Ro + Rs && a < Rs)) return s;
    // r_sf: where the sphere R_l + L meets the smaller sphere, or its equator
    s.sf_equator = d * d + Rs * Rs <= Ro * Ro;
    if (s.sf_equator) {
      s.r_sf = Rs;
      s.z_sf = 0.0;
    } else {
      circle(Rs, Ro, d, Rs + Ro - d, s.r_sf, s.z_sf);
    }
    if (!(s.r_sf > a)) return s;
    const double gap0 = d - Rs - Rl; // gap on the axis (< 0 while touching)
    auto zl = [&](double r) { return std::sqrt((Rl - r) * (Rl + r)); };
    s.g_a = a > 0.0 ? d - std::sqrt((Rs - a) * (Rs + a)) - zl(a) : gap0;
    s.g_sf = d - s.z_sf - zl(s.r_sf);
    if (s.g_a < S && s.g_sf > S) circle(Rs, Rl, d - S, S - gap0, s.r_S, s.z_S);
    s.conducts = true;
    return s;
  }
  /// The circle where a sphere of radius r1 meets a sphere of radius r2 at centre distance u:
  /// its radius rho and the distance x of its plane from the centre of r1. `excess` = r1 + r2 - u
  /// > 0 is passed separately so that it keeps its digits when it is small (Heron's formula).
  static void circle(double r1, double r2, double u, double excess, double& rho, double& x) {
    rho = std::sqrt(std::max((r1 + r2 + u) * (u + r2 - r1) * (u + r1 - r2) * excess, 0.0)) /
          (2.0 * u);
    x = (r1 * r1 - r2 * r2 + u * u) / (2.0 * u);
  }
  /// Polar angle of the circle of radius a on a sphere of radius R.
  static double angle(double R, double a) {
    if (!(a > 0.0)) return 0.0;
    if (a >= R) return 0.5 * std::numbers::pi;
    return std::atan2(a, std::sqrt((R - a) * (R + a)));
  }
};

} // namespace grain::conduction
