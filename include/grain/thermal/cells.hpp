#pragma once
/// \file cells.hpp
/// Fluid-cell ("conduction") radius r_ij [m] of the indirect-conduction models of Cheng, Yu &
/// Zulli (1999): the radius of the fluid cell a pair of particles shares, read by the Voronoi A
/// and B conduction models (0 or infinite: no indirect conduction for that pair). Three ways to
/// get it:
///
/// - Voronoi diagram (`voronoi.hpp`, needs qhull): r_ij = L_ij / 2 in 2D (L_ij the edge the two
///   cells share), r_ij = sqrt(A_ij / pi) in 3D (A_ij the area of the shared face);
/// - local porosity: r_ij = 0.56 R (1 - phi)^(-1/3), phi the mean of the two particles' local
///   porosities (2D here, 3D in `voronoi.hpp`);
/// - global porosity: the same with the porosity of the whole packing (2D here, 3D in
///   `voronoi.hpp`).
///
/// This header needs nothing beyond grain::grain. Everything operates on plain arrays: centres
/// x [m], radii R [m] and a half neighbour list (`NeighborList`, row i holds partners j > i);
/// per-pair results are aligned with `NeighborList::partners`, per-wall results with
/// `NeighborList::walls`.
///
/// Porosity relation (Yang, Zou & Yu 2000, fitted to 3D sphere packings and used unchanged for
/// disks): r = 0.56 R (1 - phi)^(-1/3), with R the particle radius (the mean radius of the pair
/// for unequal particles, the particle's radius for a particle-wall pair).
///
/// Porosity of a point set: phi = 1 - V_s / V_h, with V_h the area (2D) or volume (3D) of the
/// convex hull of the centres and V_s the part of the disks (in-plane area pi R^2) or balls
/// (4/3 pi R^3) that lies inside the hull, computed exactly (not by the interior-angle rule): the
/// intersection of a disk (ball) of centre c with a polygon (triangulated polyhedron) is a signed
/// sum over its edges (faces) of the disk (ball) inside the triangle (pyramid) spanned by c and
/// that edge (face); each of those splits into two right triangles with closed forms (below).
/// The interior-angle rule counts a disk on a hull vertex of interior angle theta as
/// theta R^2 / 2, on a hull edge as one half and inside as a whole disk; it is exact only when a
/// disk is cut by no hull edge other than those through its centre, which the exact form does not
/// need. For touching disks on a square lattice and balls on a cubic lattice, hulls of whole
/// lattice blocks give exactly 1 - pi/4 and 1 - pi/6 for any block size.
///
/// Local porosity of particle i: the same with the hull of the centres of i and its neighbours
/// (both directions of the half list). `LocalRule::interior_angle` gives the 2D formula of the
/// reference program instead, phi_i = 1 - (N - 2) pi Rbar^2 / 2 / A with N the number of centres
/// and Rbar their mean radius: it gives every centre the share of a hull vertex (the interior
/// angles of an N-gon add up to (N - 2) pi), although particle i itself usually lies inside the
/// hull with its whole disk, so it undercounts the solid by about half a disk (1 - 3 pi/16 = 0.41
/// instead of 1 - pi/4 = 0.21 for a square lattice with 4 neighbours). Degenerate hulls (fewer
/// than 3 non-collinear centres, zero area) give phi = 1. Porosities are clamped to [0, 1]
/// (overlapping particles can count more solid than the hull holds).
///
/// Closed forms. Right triangle in a plane at distance h >= 0 from the ball centre c: right angle
/// at G, the foot F of c in the plane as one corner (|FG| = g), angle phi at F. With
/// r0 = sqrt(max(R^2 - h^2, 0)) the radius of the ball's section, phi* = min(phi, acos(g / r0))
/// if g < r0 else 0, and rho = sqrt(h^2 + g^2):
///   area of the section inside the triangle  A  = g^2 tan(phi*) / 2 + r0^2 (phi - phi*) / 2,
///   solid angle of the triangle seen from c  Om = phi - asin(h sin(phi) / rho),
///   solid angle of the section in it         Oi = phi* - asin(h sin(phi*) / rho)
///                                                 + (1 - h / R) (phi - phi*)   (0 if r0 = 0),
///   ball inside the pyramid over it          V  = h A / 3 + R^3 (Om - Oi) / 3.
/// The disk inside a planar right triangle is A with h = 0, r0 = R. A face whose plane is at
/// least R from c contributes R^3 Om_face / 3 with the solid angle of the whole triangle (Van
/// Oosterom & Strackee 1983).
///
/// Cost: global porosity O(N H) (H hull edges or faces; particles farther than R from every hull
/// face plane take a shortcut), local porosity O(sum of k log k + k H_i) over the neighbour
/// counts k. Loops over particles run in parallel (OpenMP).
///
/// References: Cheng G.J., Yu A.B., Zulli P. (1999), Chem. Eng. Sci. 54, 4199-4209; Yang R.Y.,
/// Zou R.P., Yu A.B. (2000), Phys. Rev. E 62, 3900-3908; Van Oosterom A., Strackee J. (1983),
/// IEEE Trans. Biomed. Eng. 30, 125-126 (solid angle of a triangle).

#include <grain/core/error.hpp>
#include <grain/core/vector.hpp>
#include <grain/search/neighbor_list.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace grain::cells {

/// Fluid-cell radii of a neighbour list [m]: `pair[k]` for the pair (i, partners[k]) and
/// `wall[k]` for the particle-wall pair (i, walls[k]). 0 or infinite: no indirect conduction.
struct CellRadii {
  std::vector<double> pair;
  std::vector<double> wall;
};

/// How local porosity counts the solid inside the hull of a particle and its neighbours.
enum class LocalRule {
  overlap,       ///< exact area of each disk inside the hull (default)
  interior_angle ///< the reference program's phi = 1 - (N - 2) pi Rbar^2 / 2 / A (2D only)
};

/// Corner indices of a triangle of a closed surface, counter-clockwise seen from outside.
using TriangleIndices = std::array<std::uint32_t, 3>;

/// Cell radius r = 0.56 R (1 - phi)^(-1/3) [m] of a particle of radius R [m] in a packing of
/// porosity phi in [0, 1] (Yang, Zou & Yu 2000); +infinity for phi = 1 (no solid around: no
/// indirect conduction).
inline double cell_radius_from_porosity(double R, double phi) {
  grain::detail::require_non_negative("cells::cell_radius_from_porosity", "R", R);
  grain::detail::require_in("cells::cell_radius_from_porosity", "phi", phi, 0.0, 1.0, "[0, 1]");
  if (phi >= 1.0) return std::numeric_limits<double>::infinity();
  return 0.56 * R / std::cbrt(1.0 - phi);
}

namespace detail {

using grain::detail::require;

/// Section of a ball of radius R in a right triangle (see the file comment): area A inside the
/// triangle and the pyramid volume V; odd in phi (phi in (-pi/2, pi/2)).
struct SectorTerms {
  double area;
  double volume;
};

inline SectorTerms right_triangle_terms(double R, double h, double g, double phi) {
  const double a = std::abs(phi);
  const double s = phi < 0 ? -1.0 : 1.0;
  const double r0sq = std::max(R * R - h * h, 0.0);
  const double r0 = std::sqrt(r0sq);
  const double pstar = g < r0 ? std::min(a, std::acos(g / r0)) : 0.0;
  const double area = 0.5 * (g * g * std::tan(pstar) + r0sq * (a - pstar));
  if (h <= 0.0) return {s * area, 0.0};
  const double rho = std::sqrt(h * h + g * g);
  auto asin_clamped = [](double v) { return std::asin(std::clamp(v, -1.0, 1.0)); };
  const double om = a - asin_clamped(h * std::sin(a) / rho);
  const double oi =
      r0 > 0.0 ? pstar - asin_clamped(h * std::sin(pstar) / rho) + (1.0 - h / R) * (a - pstar)
               : 0.0;
  const double volume = h * area / 3.0 + R * R * R * (om - oi) / 3.0;
  return {s * area, s * volume};
}

inline double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Signed area of the disk (c, R) inside the triangle (c, p, q): positive if c is left of p->q.
inline double disk_edge_term(const Vec2& c, double R, const Vec2& p, const Vec2& q) {
  const Vec2 e = q - p;
  const double len = e.norm();
  if (!(len > 0.0)) return 0.0;
  const Vec2 u = e / len;
  const double g = cross2(u, c - p);
  if (g == 0.0) return 0.0;
  const double ag = std::abs(g);
  const double tp = (p - c).dot(u), tq = (q - c).dot(u);
  const double v = right_triangle_terms(R, 0.0, ag, std::atan2(tq, ag)).area -
                   right_triangle_terms(R, 0.0, ag, std::atan2(tp, ag)).area;
  return g > 0 ? v : -v;
}

/// Signed volume of the ball (c, R) inside the pyramid (c, triangle abc): positive if c lies on
/// the side opposite to the normal (b - a) x (c - a).
inline double ball_triangle_term(const Vec3& c, double R, const Vec3& a, const Vec3& b,
                                 const Vec3& cc) {
  Vec3 n = (b - a).cross(cc - a);
  const double nn = n.norm();
  if (!(nn > 0.0)) return 0.0;
  n /= nn;
  const double h = n.dot(a - c);
  if (h == 0.0) return 0.0;
  const double ah = std::abs(h);
  if (ah >= R) {
    // the plane misses the ball: a cone of the triangle's solid angle (signed like h),
    // tan(Om/2) = p.(q x r) / (|p||q||r| + (p.q)|r| + (p.r)|q| + (q.r)|p|) (Van Oosterom &
    // Strackee 1983)
    const Vec3 p = a - c, q = b - c, r = cc - c;
    const double lp = p.norm(), lq = q.norm(), lr = r.norm();
    const double den = lp * lq * lr + p.dot(q) * lr + p.dot(r) * lq + q.dot(r) * lp;
    return R * R * R / 3.0 * 2.0 * std::atan2(p.dot(q.cross(r)), den);
  }
  const Vec3 f = c + h * n; // foot of c in the plane
  const std::array<const Vec3*, 4> v{&a, &b, &cc, &a};
  double sum = 0.0;
  for (int k = 0; k < 3; ++k) {
    const Vec3& p = *v[k];
    const Vec3& q = *v[k + 1];
    const Vec3 e = q - p;
    const double len = e.norm();
    if (!(len > 0.0)) continue;
    const Vec3 u = e / len;
    const double g = n.cross(u).dot(f - p);
    if (g == 0.0) continue;
    const double ag = std::abs(g);
    const double tp = (p - f).dot(u), tq = (q - f).dot(u);
    const double t = right_triangle_terms(R, ah, ag, std::atan2(tq, ag)).volume -
                     right_triangle_terms(R, ah, ag, std::atan2(tp, ag)).volume;
    sum += g > 0 ? t : -t;
  }
  return h > 0 ? sum : -sum;
}

/// Full (symmetric) neighbour rows of a half list: row i lists every j with (i, j) or (j, i).
struct FullRows {
  std::vector<std::uint32_t> offsets, items;
};

inline FullRows full_rows(const NeighborList& nl, std::size_t n) {
  FullRows r;
  r.offsets.assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i)
    for (const auto k : nl.pair_entries(i)) {
      ++r.offsets[i + 1];
      ++r.offsets[nl.partners[k] + 1];
    }
  for (std::size_t i = 0; i < n; ++i)
    r.offsets[i + 1] += r.offsets[i];
  r.items.resize(r.offsets[n]);
  std::vector<std::uint32_t> fill(r.offsets.begin(), r.offsets.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    for (const auto k : nl.pair_entries(i)) {
      const std::uint32_t j = nl.partners[k];
      r.items[fill[i]++] = j;
      r.items[fill[j]++] = static_cast<std::uint32_t>(i);
    }
  return r;
}

/// Checks that positions, radii and a neighbour list describe the same n particles.
template <class P>
void check_particles(const char* who, std::span<const P> x, std::span<const double> radius,
                     const NeighborList* nl) {
  const std::string object = std::string("cells::") + who;
  require(radius.size() == x.size(), object, "radius.size()", radius.size(),
          "the number of positions");
  for (std::size_t i = 0; i < x.size(); ++i) {
    require(x[i].allFinite(), object, "position index", i, "finite coordinates");
    require(std::isfinite(radius[i]) && radius[i] >= 0.0, object, "radius", radius[i],
            "[0, inf) m");
  }
  if (nl) {
    require(!nl->offsets.empty() && nl->rows() == x.size(), object, "neighbour list rows",
            nl->offsets.empty() ? 0 : nl->rows(), "the number of positions");
    require(nl->offsets.back() == nl->partners.size(), object, "neighbour list offsets.back()",
            nl->offsets.back(), "partners.size()");
    for (std::uint32_t j : nl->partners)
      require(j < x.size(), object, "neighbour index", j, "[0, number of positions)");
  }
}

/// Porosity 1 - solid / volume, clamped to [0, 1]; 1 for an empty (zero-measure) hull.
inline double porosity_from(double solid, double volume) {
  if (!(volume > 0.0)) return 1.0;
  return std::clamp(1.0 - solid / volume, 0.0, 1.0);
}

/// A convex counter-clockwise polygon with its inward edge normals, for disk overlaps.
class ConvexPolygon {
public:
  explicit ConvexPolygon(std::vector<Vec2> v) : v_(std::move(v)) {
    const std::size_t m = v_.size();
    normal_.resize(m);
    offset_.resize(m);
    for (std::size_t e = 0; e < m; ++e) {
      const Vec2 d = v_[(e + 1) % m] - v_[e];
      const double len = d.norm();
      normal_[e] = len > 0 ? Vec2(-d.y() / len, d.x() / len) : Vec2::Zero();
      offset_[e] = normal_[e].dot(v_[e]);
    }
  }
  double area() const {
    double a = 0.0;
    for (std::size_t k = 0; k < v_.size(); ++k)
      a += cross2(v_[k], v_[(k + 1) % v_.size()]);
    return 0.5 * a;
  }
  /// Area of the disk (c, R) inside the polygon; the whole disk when no edge line is within R.
  double disk_inside(const Vec2& c, double R) const {
    const std::size_t m = v_.size();
    bool clear = true;
    for (std::size_t e = 0; e < m && clear; ++e)
      clear = normal_[e].dot(c) - offset_[e] >= R;
    if (clear) return std::numbers::pi * R * R;
    double s = 0.0;
    for (std::size_t e = 0; e < m; ++e)
      s += disk_edge_term(c, R, v_[e], v_[(e + 1) % m]);
    return std::abs(s);
  }

private:
  std::vector<Vec2> v_, normal_;
  std::vector<double> offset_;
};

} // namespace detail

/// Indices of the convex hull of 2D points, counter-clockwise, starting at the point of smallest
/// x (then y); points on hull edges and duplicates are left out (Andrew's monotone chain,
/// O(n log n)). Fewer than 3 indices for fewer than 3 distinct or for collinear points (then the
/// two extreme points).
inline std::vector<std::uint32_t> convex_hull(std::span<const Vec2> p) {
  std::vector<std::uint32_t> order(p.size());
  for (std::size_t i = 0; i < p.size(); ++i)
    order[i] = static_cast<std::uint32_t>(i);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return p[a].x() < p[b].x() || (p[a].x() == p[b].x() && p[a].y() < p[b].y());
  });
  order.erase(std::unique(order.begin(), order.end(),
                          [&](std::uint32_t a, std::uint32_t b) { return p[a] == p[b]; }),
              order.end());
  const std::size_t n = order.size();
  if (n < 3) return order;
  std::vector<std::uint32_t> h(2 * n);
  std::size_t k = 0;
  auto turn = [&](std::uint32_t o, std::uint32_t a, std::uint32_t b) {
    return detail::cross2(p[a] - p[o], p[b] - p[o]);
  };
  for (std::size_t i = 0; i < n; ++i) { // lower chain
    while (k >= 2 && turn(h[k - 2], h[k - 1], order[i]) <= 0)
      --k;
    h[k++] = order[i];
  }
  for (std::size_t i = n - 1, lower = k + 1; i-- > 0;) { // upper chain
    while (k >= lower && turn(h[k - 2], h[k - 1], order[i]) <= 0)
      --k;
    h[k++] = order[i];
  }
  h.resize(k - 1); // the last point repeats the first
  return h;
}

/// Signed area of a simple polygon [m^2] (shoelace formula): positive if counter-clockwise.
inline double polygon_area(std::span<const Vec2> polygon) {
  double a = 0.0;
  const std::size_t m = polygon.size();
  for (std::size_t k = 0; k < m; ++k)
    a += detail::cross2(polygon[k], polygon[(k + 1) % m]);
  return 0.5 * a;
}

/// Area [m^2] of the disk of centre c and radius R [m] inside a simple polygon (either
/// orientation), exact.
inline double disk_polygon_overlap(const Vec2& c, double R, std::span<const Vec2> polygon) {
  double s = 0.0;
  const std::size_t m = polygon.size();
  for (std::size_t k = 0; k < m; ++k)
    s += detail::disk_edge_term(c, R, polygon[k], polygon[(k + 1) % m]);
  return std::abs(s);
}

/// Volume [m^3] enclosed by a closed triangulated surface (either orientation).
inline double polyhedron_volume(std::span<const Vec3> vertices,
                                std::span<const TriangleIndices> triangles) {
  double v = 0.0;
  for (const auto& t : triangles)
    v += vertices[t[0]].dot(vertices[t[1]].cross(vertices[t[2]]));
  return std::abs(v) / 6.0;
}

/// Volume [m^3] of the ball of centre c and radius R [m] inside a closed, consistently oriented
/// triangulated surface (either orientation), exact.
inline double ball_polyhedron_overlap(const Vec3& c, double R, std::span<const Vec3> vertices,
                                      std::span<const TriangleIndices> triangles) {
  double s = 0.0;
  for (const auto& t : triangles)
    s += detail::ball_triangle_term(c, R, vertices[t[0]], vertices[t[1]], vertices[t[2]]);
  return std::abs(s);
}

/// Porosity of a 2D packing [-]: 1 - (disk area inside the convex hull of the centres) / (hull
/// area); 1 if the hull has no area (fewer than 3 non-collinear centres).
inline double global_porosity(std::span<const Vec2> x, std::span<const double> radius) {
  detail::check_particles<Vec2>("global_porosity", x, radius, nullptr);
  const auto hull = convex_hull(x);
  if (hull.size() < 3) return 1.0;
  std::vector<Vec2> v;
  v.reserve(hull.size());
  for (std::uint32_t k : hull)
    v.push_back(x[k]);
  const detail::ConvexPolygon poly(std::move(v));
  const std::size_t n = x.size();
  double solid = 0.0;
#pragma omp parallel for reduction(+ : solid) schedule(static) if (n > 4096)
  for (std::size_t i = 0; i < n; ++i)
    solid += poly.disk_inside(x[i], radius[i]);
  return detail::porosity_from(solid, poly.area());
}

/// Local porosity of every particle of a 2D packing [-]: the porosity of the convex hull of the
/// centres of the particle and its neighbours (all partners of `nl`, both directions).
inline std::vector<double> local_porosity(std::span<const Vec2> x, std::span<const double> radius,
                                          const NeighborList& nl,
                                          LocalRule rule = LocalRule::overlap) {
  detail::check_particles<Vec2>("local_porosity", x, radius, &nl);
  const std::size_t n = x.size();
  const auto rows = detail::full_rows(nl, n);
  std::vector<double> phi(n, 1.0);
#pragma omp parallel if (n > 1024)
  {
    std::vector<Vec2> pts, v;
    std::vector<std::uint32_t> idx;
#pragma omp for schedule(dynamic, 64)
    for (std::size_t i = 0; i < n; ++i) {
      idx.assign(1, static_cast<std::uint32_t>(i));
      idx.insert(idx.end(), rows.items.begin() + rows.offsets[i],
                 rows.items.begin() + rows.offsets[i + 1]);
      if (idx.size() < 3) continue;
      pts.clear();
      for (std::uint32_t k : idx)
        pts.push_back(x[k]);
      const auto hull = convex_hull(pts);
      if (hull.size() < 3) continue;
      v.clear();
      for (std::uint32_t k : hull)
        v.push_back(pts[k]);
      const detail::ConvexPolygon poly(v);
      const double area = poly.area();
      if (rule == LocalRule::interior_angle) {
        double rbar = 0.0;
        for (std::uint32_t k : idx)
          rbar += radius[k];
        rbar /= static_cast<double>(idx.size());
        const double solid =
            static_cast<double>(idx.size() - 2) * std::numbers::pi * rbar * rbar / 2.0;
        phi[i] = detail::porosity_from(solid, area);
      } else {
        double solid = 0.0;
        for (std::uint32_t k : idx)
          solid += poly.disk_inside(x[k], radius[k]);
        phi[i] = detail::porosity_from(solid, area);
      }
    }
  }
  return phi;
}

/// Cell radii from per-particle (local) porosities: r_ij = 0.56 R_ij (1 - phi_ij)^(-1/3) with
/// R_ij = (R_i + R_j)/2, phi_ij = (phi_i + phi_j)/2; particle-wall pairs use R_i and phi_i.
inline CellRadii porosity_radii(std::span<const double> radius, std::span<const double> phi,
                                const NeighborList& nl) {
  grain::detail::require(phi.size() == radius.size(), "cells::porosity_radii", "phi.size()",
                         phi.size(), "the number of radii");
  grain::detail::require(!nl.offsets.empty() && nl.rows() == radius.size() &&
                             nl.wall_offsets.size() == nl.offsets.size(),
                         "cells::porosity_radii", "neighbour list rows",
                         nl.offsets.empty() ? 0 : nl.rows(), "the number of radii");
  CellRadii r;
  r.pair.resize(nl.partners.size());
  r.wall.resize(nl.walls.size());
  for (std::size_t i = 0; i < radius.size(); ++i) {
    for (const auto k : nl.pair_entries(i)) {
      const std::uint32_t j = nl.partners[k];
      r.pair[k] = cell_radius_from_porosity(0.5 * (radius[i] + radius[j]), 0.5 * (phi[i] + phi[j]));
    }
    for (const auto k : nl.wall_entries(i))
      r.wall[k] = cell_radius_from_porosity(radius[i], phi[i]);
  }
  return r;
}

/// Cell radii from one (global) porosity phi: r_ij = 0.56 R_ij (1 - phi)^(-1/3) with
/// R_ij = (R_i + R_j)/2 (R_i for particle-wall pairs).
inline CellRadii porosity_radii(std::span<const double> radius, double phi,
                                const NeighborList& nl) {
  const std::vector<double> all(radius.size(), phi);
  return porosity_radii(radius, all, nl);
}

// ------------------------------------------------------------------ simulation options
/// Convex hulls of 2D packings (no qhull). 3D hulls are `QhullHulls` in voronoi.hpp.
struct PlanarHulls {
  template <int D>
  static constexpr bool available = D == 2;
  static double global_porosity(std::span<const Vec2> x, std::span<const double> r) {
    return cells::global_porosity(x, r);
  }
  static std::vector<double> local_porosity(std::span<const Vec2> x, std::span<const double> r,
                                            const NeighborList& nl, LocalRule rule) {
    return cells::local_porosity(x, r, nl, rule);
  }
};

namespace detail {
inline void require_frequency(const char* who, long f) {
  grain::detail::require(f >= 0, who, "update_frequency", f,
                         "[0, inf) steps (0 = at every neighbour-list rebuild)");
}

/// The pairs of `nl` closer than r_i + r_j + reach (the neighbours a local porosity counts: the
/// list itself also holds pairs within the search skin).
template <int D>
NeighborList pairs_within(std::span<const Vec<D>> x, std::span<const double> r,
                          const NeighborList& nl, double reach) {
  NeighborList out;
  out.clear(x.size());
  for (std::size_t i = 0; i + 1 < nl.offsets.size(); ++i) {
    for (const auto e : nl.pair_entries(i)) {
      const auto j = nl.partners[e];
      const double rs = r[i] + r[j] + reach;
      if ((x[j] - x[i]).squaredNorm() < rs * rs) out.partners.push_back(j);
    }
    out.offsets.push_back(static_cast<std::uint32_t>(out.partners.size()));
    out.wall_offsets.push_back(0);
  }
  return out;
}
} // namespace detail

/// Cell-size method "global porosity" (a `Simulation` option for the Voronoi conduction models):
/// r_ij = 0.56 R_ij (1 - phi)^(-1/3) with one porosity phi for the whole packing, given, or
/// estimated from the convex hull of the particle centres by `Hulls` (2D: `GlobalPorosity`; 3D:
/// `HullGlobalPorosity` of voronoi.hpp, with qhull).
template <class Hulls>
struct BasicGlobalPorosity {
  static constexpr bool cell_size_method = true;
  static constexpr const char* name = "global porosity";
  struct Params {
    double porosity = -1.0;    ///< phi in [0, 1); < 0 = estimated from the convex hull
    long update_frequency = 0; ///< recompute every n steps; 0 = at every neighbour rebuild
  };
  static void validate(const Params& p) {
    grain::detail::require(p.porosity < 1.0 && std::isfinite(p.porosity), "cells::GlobalPorosity",
                           "porosity", p.porosity, "[0, 1), or < 0 to estimate it");
    detail::require_frequency("cells::GlobalPorosity", p.update_frequency);
  }
  template <int D, class Walls>
  static CellRadii compute(const Params& p, std::span<const Vec<D>> x, std::span<const double> r,
                           const NeighborList& nl, const Walls&, double) {
    double phi = p.porosity;
    if (phi < 0.0) {
      if constexpr (Hulls::template available<D>) {
        phi = Hulls::global_porosity(x, r);
      } else {
        throw InputError("cells::GlobalPorosity: porosity = " + grain::detail::to_text(phi) +
                         " (estimate) needs the convex hull of a 3D packing; valid: a porosity in "
                         "[0, 1), or cells::HullGlobalPorosity from <grain/thermal/voronoi.hpp> "
                         "(link grain::voronoi)");
      }
    }
    return porosity_radii(r, phi, nl);
  }
};

/// Cell-size method "local porosity": r_ij = 0.56 R_ij (1 - phi_ij)^(-1/3), phi_ij the mean of
/// the local porosities of i and j (the porosity of the convex hull of each particle and its
/// neighbours: the partners that touch it or lie within the conduction cutoff). 2D:
/// `LocalPorosity`; 3D: `HullLocalPorosity` of voronoi.hpp (qhull).
template <class Hulls>
struct BasicLocalPorosity {
  static constexpr bool cell_size_method = true;
  static constexpr const char* name = "local porosity";
  struct Params {
    LocalRule rule = LocalRule::overlap; ///< how the solid inside a 2D hull is counted
    long update_frequency = 0; ///< recompute every n steps; 0 = at every neighbour rebuild
  };
  static void validate(const Params& p) {
    detail::require_frequency("cells::LocalPorosity", p.update_frequency);
  }
  /// `reach`: the conduction cutoff [m]; neighbours are the pairs closer than R_i + R_j + reach.
  template <int D, class Walls>
  static CellRadii compute(const Params& p, std::span<const Vec<D>> x, std::span<const double> r,
                           const NeighborList& nl, const Walls&, double reach) {
    static_assert(Hulls::template available<D>,
                  "grain::cells::LocalPorosity works in 2D; in 3D use cells::HullLocalPorosity "
                  "from <grain/thermal/voronoi.hpp> and link grain::voronoi");
    const auto near = detail::pairs_within<D>(x, r, nl, reach);
    const auto phi = Hulls::local_porosity(x, r, near, p.rule);
    return porosity_radii(r, phi, nl);
  }
};

/// Global porosity with 2D hulls (3D: a given porosity only).
using GlobalPorosity = BasicGlobalPorosity<PlanarHulls>;
/// Local porosity with 2D hulls.
using LocalPorosity = BasicLocalPorosity<PlanarHulls>;

/// A cell-size method: a type with `cell_size_method`, `Params` (with `update_frequency`),
/// `validate` and `compute(params, positions, radii, list, walls, reach)`.
template <class T>
concept CellSizeMethod = requires {
  requires T::cell_size_method;
  typename T::Params;
};

} // namespace grain::cells
