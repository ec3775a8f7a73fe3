#pragma once
/// \file union_mass.hpp
/// Volume, centroid and second moments of a union of overlapping spheres (3D) or disks (2D),
/// the mass properties of a clump (overlaps counted once).
///
/// 3D: the moments int_U {1, x, y, z, x^2, y^2, z^2, xy, xz, yz} dV are integrated as
///
///     int dx int dy int_{U(x, y)} dz,
///
/// the inner integral exactly over the union U(x, y) of the z-intervals the spheres cut from the
/// line (x, y); the two outer ones piecewise with Gauss-Legendre rules after the substitution
/// s = a + (b - a)(1 - cos t)/2, which takes away the square-root behaviour of the integrand at
/// the ends of a piece. The pieces end where the integrand stops being analytic: in x at the
/// ends of the spheres, at the x-extents of the circles in which two spheres meet and at the points
/// common to three spheres; in y (for a slice x) at the ends of the slice circles and at their
/// pairwise intersections. Within a piece the integrand is analytic, so the rule converges fast:
/// a single sphere and a union of two spheres come out to round-off (tests: 1e-12).
///
/// 2D: int_U {1, x, y, x^2, y^2, xy} dA, the inner integral exact over y-intervals, the outer one
/// piecewise in x (ends of the disks and their pairwise intersections).
///
/// Units: lengths in m; volume m^3 (area m^2 in 2D); the inertia is returned per unit density,
/// J / rho = int (|r|^2 I - r r^T) dV about the centroid [m^5] (2D: the polar moment
/// int |r|^2 dA [m^4]).

#include <grain/core/error.hpp>
#include <grain/core/vector.hpp>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

namespace grain {

/// Mass properties per unit density of a union of spheres or disks.
template <int D>
struct UnionMoments {
  double measure = 0.0;             ///< volume [m^3] (3D) or area [m^2] (2D)
  Vec<D> centroid = Vec<D>::Zero(); ///< [m]
  /// 3D: the inertia tensor per unit density about the centroid [m^5]; 2D: the polar moment of
  /// area about the centroid [m^4].
  std::conditional_t<D == 3, Eigen::Matrix3d, double> inertia{};
};

namespace detail {

/// Gauss-Legendre nodes and weights on [-1, 1] (Newton iteration on P_n).
template <int N>
const std::pair<std::array<double, N>, std::array<double, N>>& gauss_legendre() {
  static const auto rule = [] {
    std::pair<std::array<double, N>, std::array<double, N>> r{};
    for (int i = 0; i < N; ++i) {
      double x = std::cos(std::numbers::pi * (i + 0.75) / (N + 0.5));
      double dp = 1.0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1.0, p1 = x;
        for (int k = 2; k <= N; ++k) {
          const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        dp = N * (x * p1 - p0) / (x * x - 1.0);
        const double dx = p1 / dp;
        x -= dx;
        if (std::abs(dx) < 1e-16) break;
      }
      r.first[static_cast<std::size_t>(i)] = x;
      r.second[static_cast<std::size_t>(i)] = 2.0 / ((1.0 - x * x) * dp * dp);
    }
    return r;
  }();
  return rule;
}

/// Sum of f(s) w over [a, b] after s = a + (b - a)(1 - cos t)/2, t in [0, pi] (f: s -> adds its
/// own weighted contribution through the callback `add(s, weight)`).
template <int N, class Add>
void cosine_panel(double a, double b, Add&& add) {
  if (!(b > a)) return;
  const auto& [x, w] = gauss_legendre<N>();
  const double half_pi = 0.5 * std::numbers::pi;
  for (int k = 0; k < N; ++k) {
    const double t = half_pi * (x[static_cast<std::size_t>(k)] + 1.0);
    const double s = a + 0.5 * (b - a) * (1.0 - std::cos(t));
    add(s, w[static_cast<std::size_t>(k)] * half_pi * 0.5 * (b - a) * std::sin(t));
  }
}

/// Moments int_{union of [lo, hi]} {1, z, z^2} dz of a set of intervals (sorted and merged here).
inline std::array<double, 3> interval_union_moments(std::vector<std::pair<double, double>>& iv) {
  std::sort(iv.begin(), iv.end());
  std::array<double, 3> m{0.0, 0.0, 0.0};
  std::size_t k = 0;
  while (k < iv.size()) {
    double lo = iv[k].first, hi = iv[k].second;
    ++k;
    while (k < iv.size() && iv[k].first <= hi)
      hi = std::max(hi, iv[k++].second);
    m[0] += hi - lo;
    m[1] += 0.5 * (hi * hi - lo * lo);
    m[2] += (hi * hi * hi - lo * lo * lo) / 3.0;
  }
  return m;
}

/// The interior breakpoints of [a, b] from a list, sorted and with duplicates removed.
inline std::vector<double> pieces(double a, double b, std::vector<double> cuts) {
  cuts.push_back(a);
  cuts.push_back(b);
  std::sort(cuts.begin(), cuts.end());
  std::vector<double> out;
  const double tol = 1e-14 * (b - a);
  for (double c : cuts) {
    if (c < a || c > b) continue;
    if (out.empty() || c - out.back() > tol) out.push_back(c);
  }
  out.back() = b;
  return out;
}

/// y-coordinates of the intersection points of two circles (centres p, q, radii r, s).
template <class V2>
void circle_intersections_y(const V2& p, double r, const V2& q, double s, std::vector<double>& out,
                            int coordinate) {
  const V2 d = q - p;
  const double L = d.norm();
  if (!(L > 0.0) || L >= r + s || L <= std::abs(r - s)) return;
  const double a = (r * r - s * s + L * L) / (2.0 * L);
  const double h = std::sqrt(std::max(r * r - a * a, 0.0));
  const V2 m = p + (a / L) * d;
  const V2 n(-d[1] / L, d[0] / L);
  out.push_back((m + h * n)[coordinate]);
  out.push_back((m - h * n)[coordinate]);
}

template <class V>
void check_members(const std::string& object, const std::vector<V>& centres,
                   const std::vector<double>& radii) {
  if (centres.empty())
    throw InputError(object + ": members = 0 is invalid; valid range: at least one sphere or disk");
  if (centres.size() != radii.size())
    throw InputError(object + ": radii = " + std::to_string(radii.size()) +
                     " values is invalid; valid: one radius per member centre (" +
                     std::to_string(centres.size()) + ")");
  for (std::size_t k = 0; k < radii.size(); ++k) {
    const std::string member = object + " (member " + std::to_string(k) + ")";
    detail::require_positive(member, "radius", radii[k]);
    detail::require(centres[k].allFinite(), member, "centre", centres[k].transpose(),
                    "finite coordinates [m]");
  }
}

/// The x-range of the members' union and the cuts at each member's ends.
struct XExtent {
  double x0 = 1e300, x1 = -1e300;
  std::vector<double> cuts;
};
template <class V>
XExtent x_extent(const std::vector<V>& centres, const std::vector<double>& radii) {
  XExtent e;
  for (std::size_t i = 0; i < centres.size(); ++i) {
    e.x0 = std::min(e.x0, centres[i].x() - radii[i]);
    e.x1 = std::max(e.x1, centres[i].x() + radii[i]);
    e.cuts.push_back(centres[i].x() - radii[i]);
    e.cuts.push_back(centres[i].x() + radii[i]);
  }
  return e;
}

} // namespace detail

namespace detail {
/// Adds to `cuts` the x-coordinates of the points common to the spheres i, j and k
/// (trilateration in the frame of i, j, k): centre ci and radius ri of sphere i, unit direction
/// u from i to j at distance L [m] and radius rj of sphere j, centre ck and radius rk of sphere k.
inline void triple_point_cuts(const Vec3& ci, double ri, const Vec3& u, double L, double rj,
                              const Vec3& ck, double rk, std::vector<double>& cuts) {
  const Vec3 e1 = u;
  const Vec3 dk = ck - ci;
  const double ix = e1.dot(dk);
  Vec3 e2 = dk - ix * e1;
  const double e2n = e2.norm();
  if (!(e2n > 1e-14 * L)) return;
  e2 /= e2n;
  const Vec3 e3 = e1.cross(e2);
  const double jy = e2.dot(dk);
  const double x = (ri * ri - rj * rj + L * L) / (2.0 * L);
  const double y = (ri * ri - rk * rk + ix * ix + jy * jy) / (2.0 * jy) - ix / jy * x;
  const double z2 = ri * ri - x * x - y * y;
  if (z2 < 0.0) return;
  const double z = std::sqrt(z2);
  cuts.push_back((ci + x * e1 + y * e2 + z * e3).x());
  cuts.push_back((ci + x * e1 + y * e2 - z * e3).x());
}

/// The x-range of a union of spheres and its x-breakpoints: the ends of the spheres, the
/// x-extents of the circles in which two spheres meet and the points common to three spheres.
inline XExtent sphere_union_x_cuts(const std::vector<Vec3>& centres,
                                   const std::vector<double>& radii) {
  const std::size_t n = centres.size();
  XExtent ext = x_extent(centres, radii);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const Vec3 d = centres[j] - centres[i];
      const double L = d.norm();
      const double ri = radii[i], rj = radii[j];
      if (!(L > 0.0) || L >= ri + rj || L <= std::abs(ri - rj)) continue;
      const Vec3 u = d / L;
      const double a = (ri * ri - rj * rj + L * L) / (2.0 * L);
      const double rho = std::sqrt(std::max(ri * ri - a * a, 0.0));
      const double px = centres[i].x() + a * u.x();
      const double e = rho * std::sqrt(std::max(1.0 - u.x() * u.x(), 0.0));
      ext.cuts.push_back(px - e);
      ext.cuts.push_back(px + e);
      for (std::size_t k = j + 1; k < n; ++k)
        triple_point_cuts(centres[i], ri, u, L, rj, centres[k], radii[k], ext.cuts);
    }
  }
  return ext;
}

/// Scratch space of the slice integration of a union of spheres (reused between slices).
struct SphereSliceScratch {
  std::vector<std::pair<double, double>> iv;    ///< z-intervals on a line (x, y) [m]
  std::vector<std::pair<Vec2, double>> circles; ///< slice circles: centre (y, z), radius [m]
  std::vector<double> ycuts;                    ///< y-breakpoints of the slice [m]
};

/// Adds to m (1, x, y, z, xx, yy, zz, xy, xz, yz) the weight w times the moments of the union of
/// the z-intervals that the slice circles cut from the line (x, y).
inline void add_line_moments(double x, double y, double w, SphereSliceScratch& sc,
                             std::array<double, 10>& m) {
  auto& iv = sc.iv;
  iv.clear();
  for (const auto& [c, rho] : sc.circles) {
    const double dy = y - c.x();
    const double h2 = rho * rho - dy * dy;
    if (h2 > 0.0) {
      const double h = std::sqrt(h2);
      iv.push_back({c.y() - h, c.y() + h});
    }
  }
  if (iv.empty()) return;
  const auto z = interval_union_moments(iv);
  m[0] += w * z[0];
  m[1] += w * x * z[0];
  m[2] += w * y * z[0];
  m[3] += w * z[1];
  m[4] += w * x * x * z[0];
  m[5] += w * y * y * z[0];
  m[6] += w * z[2];
  m[7] += w * x * y * z[0];
  m[8] += w * x * z[1];
  m[9] += w * y * z[1];
}

/// Adds to m the weight wx times the moments of the union's slice at x: the slice circles,
/// integrated piecewise in y between their ends and pairwise intersections.
inline void add_slice_moments(const std::vector<Vec3>& centres, const std::vector<double>& radii,
                              double x, double wx, SphereSliceScratch& sc,
                              std::array<double, 10>& m) {
  sc.circles.clear();
  sc.ycuts.clear();
  double y0 = 1e300, y1 = -1e300;
  for (std::size_t i = 0; i < centres.size(); ++i) {
    const double dx = x - centres[i].x();
    const double r2 = radii[i] * radii[i] - dx * dx;
    if (r2 <= 0.0) continue;
    const double rho = std::sqrt(r2);
    const Vec2 c(centres[i].y(), centres[i].z());
    for (const auto& [q, s] : sc.circles)
      circle_intersections_y(c, rho, q, s, sc.ycuts, 0);
    sc.circles.push_back({c, rho});
    sc.ycuts.push_back(c.x() - rho);
    sc.ycuts.push_back(c.x() + rho);
    y0 = std::min(y0, c.x() - rho);
    y1 = std::max(y1, c.x() + rho);
  }
  if (sc.circles.empty()) return;
  const auto ys = pieces(y0, y1, sc.ycuts);
  for (std::size_t q = 0; q + 1 < ys.size(); ++q)
    cosine_panel<24>(ys[q], ys[q + 1],
                     [&](double y, double wy) { add_line_moments(x, y, wx * wy, sc, m); });
}

/// union_moments about the origin of the given centres (see the public functions).
inline UnionMoments<3> union_moments_here(const std::vector<Vec3>& centres,
                                          const std::vector<double>& radii,
                                          const std::string& object = "clump") {
  detail::check_members(object, centres, radii);
  // x pieces: sphere ends, x-extents of pairwise intersection circles, triple points
  auto [x0, x1, cuts] = detail::sphere_union_x_cuts(centres, radii);
  const auto xs = detail::pieces(x0, x1, cuts);
  std::array<double, 10> m{}; // 1, x, y, z, xx, yy, zz, xy, xz, yz
  SphereSliceScratch sc;
  for (std::size_t p = 0; p + 1 < xs.size(); ++p)
    detail::cosine_panel<24>(xs[p], xs[p + 1], [&](double x, double wx) {
      detail::add_slice_moments(centres, radii, x, wx, sc, m);
    });
  UnionMoments<3> u;
  u.measure = m[0];
  u.centroid = Vec3(m[1], m[2], m[3]) / m[0];
  Eigen::Matrix3d s; // int r r^T about the centroid
  s << m[4], m[7], m[8], m[7], m[5], m[9], m[8], m[9], m[6];
  s -= m[0] * u.centroid * u.centroid.transpose();
  u.inertia = s.trace() * Eigen::Matrix3d::Identity() - s;
  return u;
}
} // namespace detail

namespace detail {
inline UnionMoments<2> union_moments_here(const std::vector<Vec2>& centres,
                                          const std::vector<double>& radii,
                                          const std::string& object = "clump") {
  detail::check_members(object, centres, radii);
  const std::size_t n = centres.size();
  auto [x0, x1, cuts] = detail::x_extent(centres, radii);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < i; ++j)
      detail::circle_intersections_y(centres[i], radii[i], centres[j], radii[j], cuts, 0);
  }
  const auto xs = detail::pieces(x0, x1, cuts);
  std::array<double, 6> m{}; // 1, x, y, xx, yy, xy
  std::vector<std::pair<double, double>> iv;
  for (std::size_t p = 0; p + 1 < xs.size(); ++p) {
    detail::cosine_panel<32>(xs[p], xs[p + 1], [&](double x, double w) {
      iv.clear();
      for (std::size_t i = 0; i < n; ++i) {
        const double dx = x - centres[i].x();
        const double h2 = radii[i] * radii[i] - dx * dx;
        if (h2 > 0.0) {
          const double h = std::sqrt(h2);
          iv.push_back({centres[i].y() - h, centres[i].y() + h});
        }
      }
      if (iv.empty()) return;
      const auto y = detail::interval_union_moments(iv);
      m[0] += w * y[0];
      m[1] += w * x * y[0];
      m[2] += w * y[1];
      m[3] += w * x * x * y[0];
      m[4] += w * y[2];
      m[5] += w * x * y[1];
    });
  }
  UnionMoments<2> u;
  u.measure = m[0];
  u.centroid = Vec2(m[1], m[2]) / m[0];
  u.inertia = m[3] + m[4] - m[0] * u.centroid.squaredNorm();
  return u;
}

/// The moments computed about the mean of the centres (the second moments about a far origin
/// minus V c c^T would cancel digits: a relative error of eps |c|^2 / r^2), then moved back.
template <int D>
UnionMoments<D> union_moments_centred(const std::vector<Vec<D>>& centres,
                                      const std::vector<double>& radii, const std::string& object) {
  check_members(object, centres, radii);
  Vec<D> mean = Vec<D>::Zero();
  for (const auto& c : centres)
    mean += c;
  mean /= static_cast<double>(centres.size());
  std::vector<Vec<D>> local;
  local.reserve(centres.size());
  for (const auto& c : centres)
    local.push_back(c - mean);
  UnionMoments<D> u = union_moments_here(local, radii, object);
  u.centroid += mean;
  return u;
}
} // namespace detail

/// Volume, centroid and inertia per unit density of the union of spheres (centres c_k, radii
/// r_k) [m]; any origin (computed about the mean of the centres). Throws InputError for no
/// members, a radius that is not > 0 or a non-finite centre.
inline UnionMoments<3> union_moments(const std::vector<Vec3>& centres,
                                     const std::vector<double>& radii,
                                     const std::string& object = "clump") {
  return detail::union_moments_centred<3>(centres, radii, object);
}
/// Area, centroid and polar moment of area of the union of disks (centres c_k, radii r_k) [m];
/// any origin (computed about the mean of the centres). Throws InputError as the 3D one.
inline UnionMoments<2> union_moments(const std::vector<Vec2>& centres,
                                     const std::vector<double>& radii,
                                     const std::string& object = "clump") {
  return detail::union_moments_centred<2>(centres, radii, object);
}

} // namespace grain
