#pragma once
/// \file voronoi.hpp
/// Fluid-cell radii from a Voronoi or power diagram of the particle centres, and 3D porosities
/// (convex-hull volumes), with qhull (reentrant C library libqhull_r; link `grain::voronoi`).
/// The porosity relation and the 2D porosities are in cells.hpp, which needs no qhull.
///
/// Pair radius (Cheng, Yu & Zulli 1999): the fluid cell of a pair (i, j) is the double cone from
/// the two centres to the face their cells share; r_ij [m] is the radius of its base,
///   2D: r_ij = L_ij / 2           (L_ij [m] the length of the shared edge),
///   3D: r_ij = sqrt(A_ij / pi)    (A_ij [m^2] the area of the shared face, as a circle),
/// and r_ij = 0 if the cells of i and j do not share an edge (face), e.g. diagonal neighbours of
/// a square lattice, or share only a point (edge). A face smaller than 1e-9 |x_j - x_i| in r is
/// the round-off of a degenerate configuration (four or more cocircular/cospherical centres) and
/// is reported as 0.
///
/// Diagram. `Diagram::power` (default): the power (radical, Laguerre) diagram of the disks or
/// balls, cell_i = { y : |y - x_i|^2 - R_i^2 <= |y - x_j|^2 - R_j^2 for all j }; the face
/// between two touching particles of unequal radii passes through their contact point, and for
/// equal radii it is the Voronoi diagram. `Diagram::voronoi`: the plain Voronoi diagram of the
/// centres (cells of small particles next to large ones extend past the large particles'
/// surfaces). Both come from one convex hull in D + 1 dimensions of the lifted points
/// (x_i, |x_i|^2 - w_i), w_i = R_i^2 (power) or 0 (Voronoi): each lower facet
/// n . (x, z) + b = 0 (n_z < 0) joins the particles whose cells meet at the point
/// y = -n_x / (2 n_z), and the face shared by i and j is the convex hull of the points y of all
/// facets that contain both i and j. A particle whose cell is empty (its lifted point not on the
/// lower hull: a power cell swallowed by larger neighbours, or a duplicate centre) gets 0 for all
/// its pairs and walls.
///
/// Boundary. Cells of particles on the boundary of the packing are unbounded. Every face is
/// clipped to the box B = bounding box of the centres enlarged by `margin` (default: the
/// largest radius R_max), i.e. to the space the particles themselves occupy: for touching
/// particles on a lattice, boundary pairs then get the same r as interior ones (a square lattice
/// of touching disks has r = s/2 everywhere). To bound the cells, 2^D auxiliary generators are
/// added at the corners of a box 8 times as large (half-width 8 S around the centre of B, S the
/// largest half-width of B); their power exceeds that of the nearest particle everywhere in B
/// enlarged by `margin`, so they change no face inside that region, and every particle lies
/// strictly inside their hull, so every cell is bounded. No radius is ever infinite or NaN;
/// boundary pairs get finite radii that depend on `margin`, not on the far generators.
///
/// Walls. A particle-wall pair is described by the wall's plane (3D) or line (2D): a point on
/// it and its normal (the tangent plane at the closest point for a curved wall). r_iw is the
/// radius of the face that cell_i shares with the mirror image of particle i across the plane,
/// i.e. of the part of the plane that is nearer (in power) to particle i than to any other
/// particle: the plane clipped by the half-spaces of i's diagram neighbours and by B enlarged to
/// reach the foot of i on the plane by `margin` (but not beyond B enlarged by `margin`).
/// Mirroring every particle instead gives the same face (a particle's mirror is never nearer to
/// a point on the particles' side of the plane than the particle itself). A wall outside B
/// enlarged by `margin` (more than 2 margin beyond the bounding box of the centres), or beyond
/// the cell of i, gets r_iw = 0.
///
/// Porosities (3D, definitions in cells.hpp): `global_porosity` uses the convex hull of all
/// centres; `local_porosity` that of particle i and its neighbours (one qhull call per
/// particle). Balls inside a hull are counted exactly. Hulls without volume (fewer than 4
/// centres, coplanar centres, or qhull reporting singular or imprecise input) give phi = 1.
///
/// Cost: one qhull run of N + 2^D points in D + 1 dimensions (O(N log N) expected), then
/// O(k log k) per listed pair with k the number of diagram vertices of its face; memory about
/// 6 (2D) or 40 (3D) records per particle. The per-pair and per-particle loops run in parallel
/// (OpenMP); qhull runs are independent per thread.
///
/// References: Cheng G.J., Yu A.B., Zulli P. (1999), Chem. Eng. Sci. 54, 4199-4209; Aurenhammer
/// F. (1987), SIAM J. Comput. 16, 78-96 (power diagrams and the lifting map); Barber C.B.,
/// Dobkin D.P., Huhdanpaa H. (1996), ACM Trans. Math. Softw. 22, 469-483 (qhull).

#include <grain/thermal/cells.hpp>

#include <libqhull_r/libqhull_r.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace grain::cells {

/// A wall as indirect conduction sees it: a point on the plane (3D) or line (2D) [m] and its
/// normal (any length > 0, either sense).
template <int D>
struct WallPlane {
  Vec<D> point = Vec<D>::Zero();
  Vec<D> normal = Vec<D>::UnitX();
};

/// Which cell diagram `voronoi_radii` builds.
enum class Diagram {
  power,  ///< power (radical, Laguerre) diagram of the disks/balls (default)
  voronoi ///< Voronoi diagram of the centres
};

/// Options of `voronoi_radii`.
struct VoronoiOptions {
  Diagram diagram = Diagram::power;
  /// Faces are clipped to the bounding box of the centres enlarged by this [m]; < 0: the largest
  /// radius.
  double margin = -1.0;
};

namespace detail {

/// One qhull computation (reentrant library): owns the qhull state and a scratch file for its
/// messages, and frees the state before the next run and at destruction.
class Qhull {
public:
  Qhull() : qh_(std::make_unique<qhT>()), err_(std::tmpfile()) {}
  ~Qhull() {
    release();
    if (err_) std::fclose(err_);
  }
  Qhull(const Qhull&) = delete;
  Qhull& operator=(const Qhull&) = delete;

  /// Runs qhull on n points of dimension dim stored row by row (kept alive by the caller until
  /// the next run) with the given options; returns qhull's exit code (0 on success).
  int run(int dim, int n, double* points, const std::string& options) {
    release();
    if (err_) std::rewind(err_);
    qh_zero(qh_.get(), err_);
    std::string cmd = "qhull " + options;
    active_ = true;
    return qh_new_qhull(qh_.get(), dim, n, points, False, cmd.data(), nullptr, err_);
  }
  qhT* get() const { return qh_.get(); }

  /// First line of qhull's last message (empty if none was kept).
  std::string message() const {
    if (!err_) return {};
    std::fflush(err_);
    std::rewind(err_);
    char line[512] = {};
    if (!std::fgets(line, sizeof line, err_)) return {};
    std::string s(line);
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r'))
      s.pop_back();
    return s;
  }

  /// Exception for a failed run.
  std::runtime_error failure(const char* who, int code) const {
    return std::runtime_error(std::string("cells::") + who + ": qhull failed with exit code " +
                              std::to_string(code) + ": " + message());
  }

private:
  void release() {
    if (!active_) return;
    qh_freeqhull(qh_.get(), !qh_ALL);
    int curlong = 0, totlong = 0;
    qh_memfreeshort(qh_.get(), &curlong, &totlong);
    active_ = false;
  }
  std::unique_ptr<qhT> qh_;
  std::FILE* err_ = nullptr;
  bool active_ = false;
};

/// Calls f(facet) for every facet of the last run.
template <class F>
void for_each_facet(qhT* qh, F&& f) {
  for (facetT* facet = qh->facet_list; facet && facet->next; facet = facet->next)
    f(facet);
}

/// Calls f(point index) for every vertex of a facet.
template <class F>
void for_each_vertex(qhT* qh, facetT* facet, F&& f) {
  if (!facet->vertices) return;
  for (setelemT* e = &facet->vertices->e[0]; e->p; ++e)
    f(qh_pointid(qh, static_cast<vertexT*>(e->p)->point));
}

/// True for qhull's exit codes of degenerate input (flat hull, precision).
inline bool degenerate_input(int code) { return code == qh_ERRsingular || code == qh_ERRprec; }

/// Axis-aligned box [lo, hi].
template <int D>
struct Box {
  Vec<D> lo, hi;
  bool empty() const { return (hi.array() < lo.array()).any(); }
};

/// Half-space { y : a . y <= b }.
template <int D>
struct HalfSpace {
  Vec<D> a;
  double b;
};

/// Clips the segment p + t (q - p), t in [t0, t1], to a half-space; false if nothing is left.
inline bool clip_segment(const Vec2& p, const Vec2& q, double& t0, double& t1,
                         const HalfSpace<2>& h) {
  const double s = h.a.dot(p) - h.b, ds = h.a.dot(q - p);
  if (ds == 0.0) return s <= 0.0;
  const double t = -s / ds;
  if (ds > 0.0)
    t1 = std::min(t1, t);
  else
    t0 = std::max(t0, t);
  return t0 < t1;
}

/// Clips a convex polygon to a half-space (Sutherland-Hodgman); `out` may not alias `in`.
inline void clip_polygon(const std::vector<Vec3>& in, std::vector<Vec3>& out,
                         const HalfSpace<3>& h) {
  out.clear();
  const std::size_t m = in.size();
  for (std::size_t k = 0; k < m; ++k) {
    const Vec3& p = in[k];
    const Vec3& q = in[(k + 1) % m];
    const double sp = h.a.dot(p) - h.b, sq = h.a.dot(q) - h.b;
    if (sp <= 0.0) out.push_back(p);
    if ((sp < 0.0 && sq > 0.0) || (sp > 0.0 && sq < 0.0))
      out.push_back(p + (sp / (sp - sq)) * (q - p));
  }
}

/// The 2D half-spaces of a box.
template <int D>
std::vector<HalfSpace<D>> box_sides(const Box<D>& b) {
  std::vector<HalfSpace<D>> h;
  for (int d = 0; d < D; ++d) {
    h.push_back({Vec<D>::Unit(d), b.hi[d]});
    h.push_back({-Vec<D>::Unit(d), -b.lo[d]});
  }
  return h;
}

/// Area of a planar polygon in 3D [m^2].
inline double polygon_area_3d(const std::vector<Vec3>& p) {
  Vec3 s = Vec3::Zero();
  for (std::size_t k = 1; k + 1 < p.size(); ++k)
    s += (p[k] - p[0]).cross(p[k + 1] - p[0]);
  return 0.5 * s.norm();
}

/// Measure (length in 2D, area in 3D) of the convex hull of the diagram points `c` of the face
/// between centres xi and xj, clipped to the half-spaces `sides`.
inline double face_measure(const Vec2& xi, const Vec2& xj, const std::vector<Vec2>& c,
                           const std::vector<HalfSpace<2>>& sides) {
  if (c.size() < 2) return 0.0;
  Vec2 e(xi.y() - xj.y(), xj.x() - xi.x()); // along the face
  e.normalize();
  std::size_t kmin = 0, kmax = 0;
  for (std::size_t k = 1; k < c.size(); ++k) {
    if (c[k].dot(e) < c[kmin].dot(e)) kmin = k;
    if (c[k].dot(e) > c[kmax].dot(e)) kmax = k;
  }
  const Vec2 p = c[kmin], q = c[kmax];
  double t0 = 0.0, t1 = 1.0;
  for (const auto& h : sides)
    if (!clip_segment(p, q, t0, t1, h)) return 0.0;
  return (t1 - t0) * (q - p).norm();
}

inline double face_measure(const Vec3& xi, const Vec3& xj, const std::vector<Vec3>& c,
                           const std::vector<HalfSpace<3>>& sides) {
  if (c.size() < 3) return 0.0;
  const Vec3 u = (xj - xi).normalized();
  Eigen::Index axis = 0;
  u.cwiseAbs().minCoeff(&axis);
  const Vec3 e1 = u.cross(Vec3::Unit(axis)).normalized();
  const Vec3 e2 = u.cross(e1);
  std::vector<Vec2> q(c.size());
  for (std::size_t k = 0; k < c.size(); ++k)
    q[k] = Vec2((c[k] - xi).dot(e1), (c[k] - xi).dot(e2));
  const auto hull = convex_hull(q);
  if (hull.size() < 3) return 0.0;
  std::vector<Vec3> poly, tmp;
  for (std::uint32_t k : hull)
    poly.push_back(c[k]);
  for (const auto& h : sides) {
    clip_polygon(poly, tmp, h);
    poly.swap(tmp);
    if (poly.size() < 3) return 0.0;
  }
  return polygon_area_3d(poly);
}

/// The face of cell_i on a wall plane (line): the plane clipped by `sides` (half-spaces of the
/// cell and of the box); `size` bounds the box's extent. Returns its length (2D) or area (3D).
inline double wall_face_measure(const Vec2& foot, const Vec2& normal, double size,
                                const std::vector<HalfSpace<2>>& sides) {
  const Vec2 t(-normal.y(), normal.x());
  const Vec2 p = foot - size * t, q = foot + size * t;
  double t0 = 0.0, t1 = 1.0;
  for (const auto& h : sides)
    if (!clip_segment(p, q, t0, t1, h)) return 0.0;
  return (t1 - t0) * (q - p).norm();
}

inline double wall_face_measure(const Vec3& foot, const Vec3& normal, double size,
                                const std::vector<HalfSpace<3>>& sides) {
  Eigen::Index axis = 0;
  normal.cwiseAbs().minCoeff(&axis);
  const Vec3 e1 = normal.cross(Vec3::Unit(axis)).normalized();
  const Vec3 e2 = normal.cross(e1);
  std::vector<Vec3> poly{foot - size * (e1 + e2), foot + size * (e1 - e2), foot + size * (e1 + e2),
                         foot - size * (e1 - e2)},
      tmp;
  for (const auto& h : sides) {
    clip_polygon(poly, tmp, h);
    poly.swap(tmp);
    if (poly.size() < 3) return 0.0;
  }
  return polygon_area_3d(poly);
}

/// r from a face measure: L/2 (2D), sqrt(A/pi) (3D).
template <int D>
double radius_of_face(double measure) {
  if constexpr (D == 2)
    return 0.5 * measure;
  else
    return std::sqrt(measure / std::numbers::pi);
}

/// Checks the arguments of `voronoi_radii`: the particles and the neighbour list, and, if walls
/// are given, one plane with a finite point and a finite non-zero normal per wall entry of the
/// list.
template <int D>
void check_voronoi_input(std::span<const Vec<D>> x, std::span<const double> radius,
                         const NeighborList& nl, std::span<const WallPlane<D>> walls) {
  check_particles<Vec<D>>("voronoi_radii", x, radius, &nl);
  const std::string object = "cells::voronoi_radii";
  require(walls.empty() || walls.size() == nl.walls.size(), object, "walls.size()", walls.size(),
          "0 or the number of wall entries of the neighbour list");
  if (!walls.empty())
    require(nl.wall_offsets.size() == nl.offsets.size() &&
                nl.wall_offsets.back() == nl.walls.size(),
            object, "neighbour list wall_offsets.size()", nl.wall_offsets.size(),
            "the number of particles + 1");
  for (std::size_t k = 0; k < walls.size(); ++k)
    require(walls[k].point.allFinite() && walls[k].normal.allFinite() &&
                walls[k].normal.norm() > 0.0,
            object, "wall entry", k, "a finite point and a finite non-zero normal");
}

/// The weight w_i of particle i in the lifted points [m^2]: R_i^2 (power diagram) or 0
/// (Voronoi diagram).
inline double lift_weight(std::span<const double> radius, bool power, std::size_t i) {
  return power ? radius[i] * radius[i] : 0.0;
}

/// The bounding box of the centres enlarged by `margin` [m] on every side.
template <int D>
Box<D> margin_box(std::span<const Vec<D>> x, double margin) {
  Box<D> box{x[0], x[0]};
  for (const auto& p : x) {
    box.lo = box.lo.cwiseMin(p);
    box.hi = box.hi.cwiseMax(p);
  }
  box.lo.array() -= margin;
  box.hi.array() += margin;
  return box;
}

/// The qhull input, row by row: the lifted points (y, |y|^2 - w / scale^2) of the centres
/// normalised as y = (x - centre) / scale, then the 2^D far generators (+-1, ..., +-1, D).
template <int D>
std::vector<double> lifted_points(std::span<const Vec<D>> x, std::span<const double> radius,
                                  bool power, const Vec<D>& centre, double scale) {
  const std::size_t n = x.size();
  constexpr int corners = 1 << D;
  const std::size_t total = n + corners;
  std::vector<double> pts(total * (D + 1));
  for (std::size_t i = 0; i < n; ++i) {
    const Vec<D> y = (x[i] - centre) / scale;
    for (int d = 0; d < D; ++d)
      pts[i * (D + 1) + d] = y[d];
    pts[i * (D + 1) + D] = y.squaredNorm() - lift_weight(radius, power, i) / (scale * scale);
  }
  for (int c = 0; c < corners; ++c) {
    double* p = &pts[(n + c) * (D + 1)];
    for (int d = 0; d < D; ++d)
      p[d] = (c >> d) & 1 ? 1.0 : -1.0;
    p[D] = D;
  }
  return pts;
}

/// A power or Voronoi diagram as the lower convex hull of the lifted points gives it.
template <int D>
struct CellDiagram {
  std::vector<Vec<D>> point; ///< diagram points of the lower facets [m]
  /// (i << 32 | j, point index) for every pair i < j of particles of a facet, sorted
  std::vector<std::pair<std::uint64_t, std::uint32_t>> rec;
  std::vector<char> in_diagram; ///< 1 for a particle whose cell is not empty

  /// The records [first, second) of the pair (i, j), in either order.
  auto range(std::uint32_t i, std::uint32_t j) const {
    const std::uint64_t key = std::uint64_t(std::min(i, j)) << 32 | std::max(i, j);
    const auto lo = std::lower_bound(rec.begin(), rec.end(), std::make_pair(key, std::uint32_t(0)));
    auto hi = lo;
    while (hi != rec.end() && hi->first == key)
      ++hi;
    return std::make_pair(lo, hi);
  }
};

/// Runs qhull on the lifted points and collects the diagram points of the lower facets and the
/// pairs of particles that meet at each (see the file comment); throws on a qhull failure.
template <int D>
CellDiagram<D> cell_diagram(std::span<const Vec<D>> x, std::span<const double> radius, bool power,
                            const Vec<D>& centre, double scale, const char* who) {
  const std::size_t n = x.size();
  std::vector<double> pts = lifted_points<D>(x, radius, power, centre, scale);
  Qhull q;
  const int code = q.run(D + 1, static_cast<int>(pts.size() / (D + 1)), pts.data(), "");
  if (code != 0) throw q.failure(who, code);

  CellDiagram<D> g;
  g.in_diagram.assign(n, 0);
  std::vector<std::uint32_t> ids;
  qhT* qh = q.get();
  for_each_facet(qh, [&](facetT* f) {
    const double nz = f->normal[D];
    if (!(nz < 0.0)) return; // upper or vertical facet: no finite diagram point
    ids.clear();
    for_each_vertex(qh, f, [&](int id) {
      if (id >= 0 && static_cast<std::size_t>(id) < n)
        ids.push_back(static_cast<std::uint32_t>(id));
    });
    for (std::uint32_t id : ids)
      g.in_diagram[id] = 1;
    if (ids.size() < 2) return;
    Vec<D> y;
    for (int d = 0; d < D; ++d)
      y[d] = -f->normal[d] / (2.0 * nz);
    const Vec<D> c = centre + scale * y;
    if (!c.allFinite()) return;
    const auto fid = static_cast<std::uint32_t>(g.point.size());
    g.point.push_back(c);
    std::sort(ids.begin(), ids.end());
    for (std::size_t a = 0; a < ids.size(); ++a)
      for (std::size_t b = a + 1; b < ids.size(); ++b)
        g.rec.push_back({std::uint64_t(ids[a]) << 32 | ids[b], fid});
  });
  std::sort(g.rec.begin(), g.rec.end());
  return g;
}

/// r_ij of every pair of the neighbour list from the diagram's faces clipped to the half-spaces
/// `sides` (0 below 1e-9 |x_j - x_i|), into `pair`.
template <int D>
void pair_radii(std::span<const Vec<D>> x, const NeighborList& nl, const CellDiagram<D>& g,
                const std::vector<HalfSpace<D>>& sides, std::vector<double>& pair) {
  const std::size_t n = x.size();
#pragma omp parallel if (n > 1024)
  {
    std::vector<Vec<D>> c;
#pragma omp for schedule(dynamic, 256)
    for (std::size_t i = 0; i < n; ++i) {
      for (const auto k : nl.pair_entries(i)) {
        const std::uint32_t j = nl.partners[k];
        if (j == i) continue;
        const auto [lo, hi] = g.range(static_cast<std::uint32_t>(i), j);
        c.clear();
        for (auto it = lo; it != hi; ++it)
          c.push_back(g.point[it->second]);
        const double r = radius_of_face<D>(face_measure(x[i], x[j], c, sides));
        pair[k] = r > 1e-9 * (x[j] - x[i]).norm() ? r : 0.0;
      }
    }
  }
}

/// The diagram neighbours of each of n particles (the half-spaces that bound its cell) from the
/// sorted pair records: row i lists every j whose cell shares a facet point with i's.
inline FullRows diagram_neighbours(const std::vector<std::pair<std::uint64_t, std::uint32_t>>& rec,
                                   std::size_t n) {
  FullRows r;
  r.offsets.assign(n + 1, 0);
  std::uint64_t last = ~std::uint64_t(0);
  for (const auto& [key, fid] : rec) {
    if (key == last) continue;
    last = key;
    ++r.offsets[(key >> 32) + 1];
    ++r.offsets[(key & 0xffffffffu) + 1];
  }
  for (std::size_t i = 0; i < n; ++i)
    r.offsets[i + 1] += r.offsets[i];
  r.items.resize(r.offsets[n]);
  std::vector<std::uint32_t> fill(r.offsets.begin(), r.offsets.end() - 1);
  last = ~std::uint64_t(0);
  for (const auto& [key, fid] : rec) {
    if (key == last) continue;
    last = key;
    const auto a = static_cast<std::uint32_t>(key >> 32), b = static_cast<std::uint32_t>(key);
    r.items[fill[a]++] = b;
    r.items[fill[b]++] = a;
  }
  return r;
}

/// The clipping boxes of the wall faces: `box` (the centres' box enlarged by `margin` [m]), the
/// limit `outer` (enlarged by 2 margin), and the margin.
template <int D>
struct WallClip {
  Box<D> box, outer;
  double margin = 0.0;
};

/// r_iw of every particle-wall entry of the neighbour list (see the file comment), into `wall`;
/// particles with an empty cell keep 0.
template <int D>
void wall_radii(std::span<const Vec<D>> x, std::span<const double> radius, bool power,
                const NeighborList& nl, std::span<const WallPlane<D>> walls,
                const CellDiagram<D>& g, const WallClip<D>& clip, std::vector<double>& wall) {
  const std::size_t n = x.size();
  const FullRows adj = diagram_neighbours(g.rec, n);
  const Box<D>& box = clip.box;
  const Box<D>& outer = clip.outer;
  const double margin = clip.margin;
#pragma omp parallel if (n > 1024)
  {
    std::vector<HalfSpace<D>> h;
#pragma omp for schedule(dynamic, 256)
    for (std::size_t i = 0; i < n; ++i) {
      if (!g.in_diagram[i]) continue;
      for (const auto k : nl.wall_entries(i)) {
        const Vec<D> nrm = walls[k].normal.normalized();
        const Vec<D> foot = x[i] - (x[i] - walls[k].point).dot(nrm) * nrm;
        const Vec<D> flo = foot.array() - margin, fhi = foot.array() + margin;
        const Box<D> bw{box.lo.cwiseMin(flo).cwiseMax(outer.lo),
                        box.hi.cwiseMax(fhi).cwiseMin(outer.hi)};
        if (bw.empty()) continue;
        h = box_sides(bw);
        for (std::uint32_t a = adj.offsets[i]; a < adj.offsets[i + 1]; ++a) {
          const std::uint32_t j = adj.items[a];
          const Vec<D> d = x[j] - x[i];
          h.push_back({2.0 * d, d.squaredNorm() + lift_weight(radius, power, i) -
                                    lift_weight(radius, power, j) + 2.0 * d.dot(x[i])});
        }
        const double size = 2.0 * ((bw.hi - bw.lo).norm() + (foot - 0.5 * (bw.lo + bw.hi)).norm());
        wall[k] = radius_of_face<D>(wall_face_measure(foot, nrm, size, h));
      }
    }
  }
}

/// `voronoi_radii` in D dimensions (see the public functions and the file comment).
template <int D>
CellRadii voronoi_radii(std::span<const Vec<D>> x, std::span<const double> radius,
                        const NeighborList& nl, std::span<const WallPlane<D>> walls,
                        const VoronoiOptions& opt) {
  const char* who = "voronoi_radii";
  check_voronoi_input<D>(x, radius, nl, walls);
  const std::string object = "cells::voronoi_radii";
  const std::size_t n = x.size();
  CellRadii out;
  out.pair.assign(nl.partners.size(), 0.0);
  out.wall.assign(walls.size(), 0.0);
  if (n == 0) return out;
  require(n < (std::size_t(1) << 31), object, "number of particles", n, "below 2^31");

  const bool power = opt.diagram == Diagram::power;
  const double rmax = *std::max_element(radius.begin(), radius.end());
  const double margin = opt.margin >= 0.0 ? opt.margin : rmax;
  require(std::isfinite(margin) && margin > 0.0, object, "margin", margin,
          "(0, inf) m (the default, the largest radius, must then be > 0)");
  const Box<D> box = margin_box<D>(x, margin);
  const Box<D> outer{(box.lo.array() - margin).matrix(), (box.hi.array() + margin).matrix()};
  const Vec<D> centre = 0.5 * (box.lo + box.hi);
  const double scale = 8.0 * (0.5 * (box.hi - box.lo)).maxCoeff();

  const CellDiagram<D> g = cell_diagram<D>(x, radius, power, centre, scale, who);
  pair_radii<D>(x, nl, g, box_sides(box), out.pair);
  if (walls.empty()) return out;
  wall_radii<D>(x, radius, power, nl, walls, g, WallClip<D>{box, outer, margin}, out.wall);
  return out;
}

/// Outward triangles of the convex hull of 3D points (qhull 'Qt'). Returns qhull's exit code;
/// `tri` is empty on failure.
inline int hull_triangles(Qhull& q, std::span<const Vec3> p, std::vector<double>& buf,
                          std::vector<TriangleIndices>& tri) {
  tri.clear();
  buf.resize(3 * p.size());
  for (std::size_t i = 0; i < p.size(); ++i)
    for (int d = 0; d < 3; ++d)
      buf[3 * i + d] = p[i][d];
  const int code = q.run(3, static_cast<int>(p.size()), buf.data(), "Qt");
  if (code != 0) return code;
  qhT* qh = q.get();
  for_each_facet(qh, [&](facetT* f) {
    TriangleIndices t{};
    int k = 0;
    for_each_vertex(qh, f, [&](int id) {
      if (k < 3) t[k] = static_cast<std::uint32_t>(id);
      ++k;
    });
    if (k != 3) return;
    const Vec3 nf(f->normal[0], f->normal[1], f->normal[2]);
    if ((p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).dot(nf) < 0.0) std::swap(t[1], t[2]);
    tri.push_back(t);
  });
  return 0;
}

/// A triangulated convex polyhedron with its face planes, for ball overlaps.
class ConvexPolyhedron {
public:
  ConvexPolyhedron(std::span<const Vec3> v, std::vector<TriangleIndices> tri)
      : v_(v), tri_(std::move(tri)) {
    for (const auto& t : tri_) {
      const Vec3 nn = (v_[t[1]] - v_[t[0]]).cross(v_[t[2]] - v_[t[0]]);
      const double len = nn.norm();
      if (!(len > 0.0)) continue;
      normal_.push_back(nn / len);
      offset_.push_back(normal_.back().dot(v_[t[0]]));
    }
  }
  double volume() const { return polyhedron_volume(v_, tri_); }
  /// Volume of the ball (c, R) inside; the whole ball when no face plane is within R.
  double ball_inside(const Vec3& c, double R) const {
    bool clear = true;
    for (std::size_t e = 0; e < normal_.size() && clear; ++e)
      clear = offset_[e] - normal_[e].dot(c) >= R;
    if (clear) return 4.0 / 3.0 * std::numbers::pi * R * R * R;
    return ball_polyhedron_overlap(c, R, v_, tri_);
  }

private:
  std::span<const Vec3> v_;
  std::vector<TriangleIndices> tri_;
  std::vector<Vec3> normal_;
  std::vector<double> offset_;
};

/// Porosity of the hull of points p (balls idx in x/radius), or 1 if the hull is degenerate.
inline double hull_porosity(Qhull& q, std::span<const Vec3> p, std::span<const Vec3> x,
                            std::span<const double> radius, std::span<const std::uint32_t> idx,
                            std::vector<double>& buf, const char* who) {
  if (p.size() < 4) return 1.0;
  std::vector<TriangleIndices> tri;
  const int code = hull_triangles(q, p, buf, tri);
  if (degenerate_input(code)) return 1.0;
  if (code != 0) throw q.failure(who, code);
  const ConvexPolyhedron hull(p, std::move(tri));
  const double volume = hull.volume();
  Vec3 lo = p[0], hi = p[0];
  for (const auto& y : p) {
    lo = lo.cwiseMin(y);
    hi = hi.cwiseMax(y);
  }
  const double ext = (hi - lo).maxCoeff();
  if (!(volume > 1e-12 * ext * ext * ext)) return 1.0;
  double solid = 0.0;
  for (std::uint32_t k : idx)
    solid += hull.ball_inside(x[k], radius[k]);
  return porosity_from(solid, volume);
}

} // namespace detail

/// Fluid-cell radii r_ij [m] of every pair of a 2D neighbour list (half the shared edge of the
/// power or Voronoi diagram) and, if `walls` is given (one plane per entry of `nl.walls`), of every
/// particle-wall pair. See the file comment for boundaries and walls.
inline CellRadii voronoi_radii(std::span<const Vec2> x, std::span<const double> radius,
                               const NeighborList& nl, std::span<const WallPlane<2>> walls = {},
                               const VoronoiOptions& options = {}) {
  return detail::voronoi_radii<2>(x, radius, nl, walls, options);
}

/// Fluid-cell radii r_ij = sqrt(A_ij / pi) [m] of every pair of a 3D neighbour list (A_ij the
/// area of the shared face) and, if `walls` is given, of every particle-wall pair.
inline CellRadii voronoi_radii(std::span<const Vec3> x, std::span<const double> radius,
                               const NeighborList& nl, std::span<const WallPlane<3>> walls = {},
                               const VoronoiOptions& options = {}) {
  return detail::voronoi_radii<3>(x, radius, nl, walls, options);
}

/// Volume [m^3] of the convex hull of 3D points; 0 if they do not span a volume.
inline double hull_volume(std::span<const Vec3> p) {
  if (p.size() < 4) return 0.0;
  detail::Qhull q;
  std::vector<double> buf;
  std::vector<TriangleIndices> tri;
  const int code = detail::hull_triangles(q, p, buf, tri);
  if (detail::degenerate_input(code)) return 0.0;
  if (code != 0) throw q.failure("hull_volume", code);
  return polyhedron_volume(p, tri);
}

/// Porosity of a 3D packing [-]: 1 - (ball volume inside the convex hull of the centres) /
/// (hull volume); 1 if the hull has no volume.
inline double global_porosity(std::span<const Vec3> x, std::span<const double> radius) {
  detail::check_particles<Vec3>("global_porosity", x, radius, nullptr);
  if (x.size() < 4) return 1.0;
  detail::Qhull q;
  std::vector<double> buf;
  std::vector<TriangleIndices> tri;
  const int code = detail::hull_triangles(q, x, buf, tri);
  if (detail::degenerate_input(code)) return 1.0;
  if (code != 0) throw q.failure("global_porosity", code);
  const detail::ConvexPolyhedron hull(x, std::move(tri));
  const double volume = hull.volume();
  const std::size_t n = x.size();
  double solid = 0.0;
#pragma omp parallel for reduction(+ : solid) schedule(dynamic, 256) if (n > 4096)
  for (std::size_t i = 0; i < n; ++i)
    solid += hull.ball_inside(x[i], radius[i]);
  return detail::porosity_from(solid, volume);
}

/// Local porosity of every particle of a 3D packing [-]: the porosity of the convex hull of the
/// centres of the particle and its neighbours (all partners of `nl`, both directions), balls
/// counted exactly.
inline std::vector<double> local_porosity(std::span<const Vec3> x, std::span<const double> radius,
                                          const NeighborList& nl) {
  detail::check_particles<Vec3>("local_porosity", x, radius, &nl);
  const std::size_t n = x.size();
  const auto rows = detail::full_rows(nl, n);
  std::vector<double> phi(n, 1.0);
  std::exception_ptr error;
#pragma omp parallel if (n > 256)
  {
    detail::Qhull q;
    std::vector<double> buf;
    std::vector<Vec3> pts;
    std::vector<std::uint32_t> idx;
#pragma omp for schedule(dynamic, 16)
    for (std::size_t i = 0; i < n; ++i) {
      idx.assign(1, static_cast<std::uint32_t>(i));
      idx.insert(idx.end(), rows.items.begin() + rows.offsets[i],
                 rows.items.begin() + rows.offsets[i + 1]);
      pts.clear();
      for (std::uint32_t k : idx)
        pts.push_back(x[k]);
      try {
        phi[i] = detail::hull_porosity(q, pts, x, radius, idx, buf, "local_porosity");
      } catch (...) {
#pragma omp critical(grain_cells_error)
        if (!error) error = std::current_exception();
      }
    }
  }
  if (error) std::rethrow_exception(error);
  return phi;
}

// ------------------------------------------------------------------ simulation options
/// Convex hulls of 2D (cells.hpp) and 3D (qhull) packings for the porosity cell-size methods.
struct QhullHulls : PlanarHulls {
  template <int D>
  static constexpr bool available = D == 2 || D == 3;
  using PlanarHulls::global_porosity;
  using PlanarHulls::local_porosity;
  static double global_porosity(std::span<const Vec3> x, std::span<const double> r) {
    return cells::global_porosity(x, r);
  }
  static std::vector<double> local_porosity(std::span<const Vec3> x, std::span<const double> r,
                                            const NeighborList& nl, LocalRule) {
    return cells::local_porosity(x, r, nl);
  }
};

/// Global porosity estimated from the convex hull of the centres, in 2D and 3D.
using HullGlobalPorosity = BasicGlobalPorosity<QhullHulls>;
/// Local porosity from the convex hulls of each particle and its neighbours, in 2D and 3D.
using HullLocalPorosity = BasicLocalPorosity<QhullHulls>;

/// Cell-size method "Voronoi diagram" (a `Simulation` option for the Voronoi conduction
/// models): r_ij from the face shared by the cells of i and j in a power (default) or Voronoi
/// diagram of the centres; particle-wall radii from the face a particle's cell shares with its
/// mirror image across the wall (a circle wall is replaced by its tangent at the point nearest
/// the particle).
struct VoronoiDiagram {
  static constexpr bool cell_size_method = true;
  static constexpr const char* name = "Voronoi diagram";
  struct Params {
    Diagram diagram = Diagram::power;
    double margin = -1.0;      ///< clipping margin [m] around the packing; < 0 = largest radius
    long update_frequency = 0; ///< recompute every n steps; 0 = at every neighbour rebuild
  };
  static void validate(const Params& p) {
    grain::detail::require(std::isfinite(p.margin), "cells::VoronoiDiagram", "margin", p.margin,
                           "a finite length [m] (< 0 = the largest radius)");
    detail::require_frequency("cells::VoronoiDiagram", p.update_frequency);
  }
  template <int D, class Walls>
  static CellRadii compute(const Params& p, std::span<const Vec<D>> x, std::span<const double> r,
                           const NeighborList& nl, const Walls& walls, double) {
    std::vector<WallPlane<D>> planes(nl.walls.size());
    for (std::size_t i = 0; i + 1 < nl.wall_offsets.size(); ++i)
      for (const auto e : nl.wall_entries(i)) {
        const auto prox = walls[nl.walls[e]].nearest(x[i]);
        planes[e].normal = -prox.normal;
        planes[e].point = x[i] + prox.distance * prox.normal;
      }
    return voronoi_radii(x, r, nl, std::span<const WallPlane<D>>(planes),
                         VoronoiOptions{p.diagram, p.margin});
  }
};

} // namespace grain::cells
