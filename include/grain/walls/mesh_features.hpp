#pragma once
/// \file mesh_features.hpp
/// Contact features of a triangle mesh: which triangle of an obstacle reports the contact of a
/// sphere with a face, an edge or a vertex, so that every contact is counted once.
///
/// A sphere whose centre x is near a triangle mesh touches it where the distance from x to the
/// mesh has a local minimum: inside a face, inside an edge or at a vertex. Treated as independent
/// triangles, a mesh reports some of those minima twice (a sphere over the shared edge of two
/// coplanar triangles) and some points that are no minimum at all (the edge of the neighbouring
/// triangle, tilted, next to the face that is really touched). `MeshFeatures` is computed once
/// from the connectivity and answers, for a point and one triangle, whether that triangle
/// reports a contact, and which. Everything is done in the obstacle's body frame (the mesh as
/// given, with the reference point at the origin), where the data never change; all triangles
/// of an obstacle then evaluate the same tests on the same numbers and agree to the last bit.
///
/// Regions. y is the sphere centre in the body frame; s_fk = (y - P_e0) . m_fk is how far y's
/// projection lies inside face f across its edge k (m_fk the in-plane unit normal of the edge,
/// pointing into f; P_e0 the edge's first vertex); tol = 1e-12 times the diagonal of the mesh's
/// bounding box [m] absorbs round-off.
/// - Face f: s_fk >= -tol for k = 0, 1, 2 (the closed face, widened by tol). Distance
///   |(y - P_f0) . n_f|, normal -n_f above the face and +n_f below it. Where faces that lie in
///   one plane (within `flat_angle`) and share a vertex both contain y, the one of lowest index
///   reports: a point whose projection falls on a shared edge or vertex of a flat patch is a face
///   contact of exactly one triangle.
/// - Edge e: s_fk < -tol for every face f of the edge (y lies outside all of them, i.e. in the
///   wedge between their face normals on the convex side), and y between the planes through the
///   edge's ends perpendicular to it. A flat edge, or a fold seen from its concave side, has an
///   empty wedge: its faces cover it. A boundary edge (one face) reports everything beyond it.
///   The contact point is the nearest point of the edge.
/// - Vertex v: y behind the end plane of every edge of v (its normal cone: the directions d with
///   d . t <= 0 for every edge direction t leaving v) and in none of v's faces. The cone has an
///   interior only at a convex vertex; at a flat, saddle or concave vertex the faces and edges
///   cover everything.
/// Each edge and each vertex is reported by its owner, the face of lowest index that contains
/// it. Where two edges go on in a straight line through a vertex (a straight boundary, a crease
/// that continues), they share one end plane, and a point on it belongs to exactly one of them.
/// Neighbouring regions are separated by the same numbers (a face's s_fk is also its edge's test,
/// an edge's end test is also its vertex's), so they neither overlap nor leave gaps, apart from
/// slivers of width tol near a vertex.
///
/// Both sides of the mesh are touched (a thin sheet); convexity is judged from the side of the
/// point. A fold seen from its concave side gives two face contacts where both faces are touched,
/// as two walls meeting at an angle would. Triangles that share an edge must share its two
/// vertices (a conforming mesh): a vertex in the middle of another triangle's edge, or two
/// meshes that touch, are not joined.

#include <grain/core/error.hpp>
#include <grain/core/vector.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace grain::walls {

/// A triangle surface: vertex coordinates [m] and triangles as triples of vertex indices. Any
/// orientation (the triangles are touched from both sides); triangles that share an edge must
/// share its two vertices (a conforming mesh).
struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

/// A contact of a point with a mesh, in the body frame: the unit normal from the point towards
/// the mesh, the distance [m], and the feature that reports it (`none`: this triangle reports no
/// contact; the distance is then infinite).
struct MeshContact {
  enum class Feature : std::uint8_t { none, face, edge, vertex };
  Vec3 normal = Vec3::UnitZ();
  double distance = std::numeric_limits<double>::infinity();
  Feature feature = Feature::none;
  std::uint32_t index = 0; ///< the face, edge or vertex index
};

/// The features of a triangle mesh computed once from its connectivity (see the file comment).
/// Body-frame coordinates are relative to the reference point given to `build`.
class MeshFeatures {
public:
  /// What an edge is to the mesh.
  enum class EdgeKind : std::uint8_t {
    boundary,   ///< one face: reports what lies beyond it
    flat,       ///< two faces in one plane (within flat_angle): its faces cover it
    fold,       ///< two faces at an angle: convex from one side (reports in its wedge)
    nonmanifold ///< three or more faces: reports outside all of them
  };

  /// Builds the features of `mesh` with body-frame origin `reference` [m]. Faces whose planes
  /// differ by at most `flat_angle` [rad] count as one plane. Throws InputError naming `object`
  /// (e.g. "Obstacle 'hopper'") for an empty mesh, a non-finite vertex, a vertex index out of
  /// range, a triangle with a repeated vertex or a degenerate (zero-area) triangle.
  static std::shared_ptr<const MeshFeatures> build(const TriangleMesh& mesh, const Vec3& reference,
                                                   const std::string& object,
                                                   double flat_angle = 1e-6);

  std::size_t face_count() const { return faces_.size(); }
  std::size_t edge_count() const { return edges_.size(); }
  std::size_t vertex_count() const { return vertices_.size(); }
  /// Body-frame position of a vertex [m] (relative to the reference point).
  const Vec3& vertex(std::uint32_t v) const { return vertices_[v].p; }
  /// Vertex indices of a face, in the order given.
  const std::array<std::uint32_t, 3>& face_vertices(std::uint32_t f) const { return faces_[f].v; }
  /// Unit normal of a face, (b - a) x (c - a) / |...| in the body frame.
  const Vec3& face_normal(std::uint32_t f) const { return faces_[f].normal; }
  /// Edge indices of a face: edge k joins its vertices k and k + 1 (mod 3).
  const std::array<std::uint32_t, 3>& face_edges(std::uint32_t f) const { return faces_[f].e; }
  /// The two vertices of an edge (ascending).
  std::array<std::uint32_t, 2> edge_vertices(std::uint32_t e) const {
    return {edges_[e].v[0], edges_[e].v[1]};
  }
  /// The faces that contain an edge (ascending).
  std::vector<std::uint32_t> edge_faces(std::uint32_t e) const {
    std::vector<std::uint32_t> out;
    for (auto k = edges_[e].faces_begin; k < edges_[e].faces_end; ++k)
      out.push_back(edge_faces_[k].first);
    return out;
  }
  EdgeKind edge_kind(std::uint32_t e) const { return edges_[e].kind; }
  /// The face that reports an edge's contacts (the lowest index among its faces).
  std::uint32_t edge_owner(std::uint32_t e) const { return edges_[e].owner; }
  /// The face that reports a vertex's contacts (the lowest index among its faces).
  std::uint32_t vertex_owner(std::uint32_t v) const { return vertices_[v].owner; }
  /// Convexity margin of a vertex: the largest c such that some unit d has d . t <= -c for every
  /// edge direction t leaving the vertex (when positive, the distance from 0 to the convex hull
  /// of those directions). > 0: a convex vertex, whose normal cone has an interior; ~0: flat, or
  /// on a straight line of edges; < 0: saddle or concave (the hull contains 0).
  double vertex_margin(std::uint32_t v) const { return vertices_[v].margin; }
  /// Round-off tolerance tol of the region tests [m].
  double tolerance() const { return tol_; }
  /// The flat-angle tolerance the features were built with [rad].
  double flat_angle() const { return flat_angle_; }

  /// The contact that face f reports for the body-frame point y (feature `none` if f reports
  /// none: another face does, or no feature of the mesh has y in its region).
  MeshContact contact(std::uint32_t f, const Vec3& y) const {
    const Face& F = faces_[f];
    if (candidate(f, y)) {
      for (auto k = F.flat_begin; k < F.flat_end; ++k) {
        const std::uint32_t g = flat_[k];
        if (g >= f) break; // ascending: only lower faces take precedence
        if (candidate(g, y)) return none(f);
      }
      const double h = (y - vertices_[F.v[0]].p).dot(F.normal);
      return {h > 0.0 ? Vec3(-F.normal) : F.normal, std::abs(h), MeshContact::Feature::face, f};
    }
    for (int k = 0; k < 3; ++k) {
      if (!(F.owned_edges & (1u << k))) continue;
      const std::uint32_t e = F.e[k];
      if (in_edge(e, y)) {
        const Edge& E = edges_[e];
        const Vec3& p0 = vertices_[E.v[0]].p;
        const Vec3 d = Vec3(p0 + (y - p0).dot(E.t) * E.t) - y;
        return with_normal(d, f, MeshContact::Feature::edge, e);
      }
    }
    for (int k = 0; k < 3; ++k) {
      if (!(F.owned_vertices & (1u << k))) continue;
      const std::uint32_t v = F.v[k];
      if (in_vertex(v, y))
        return with_normal(Vec3(vertices_[v].p - y), f, MeshContact::Feature::vertex, v);
    }
    return none(f);
  }

private:
  struct Face {
    std::array<std::uint32_t, 3> v{}, e{};
    Vec3 normal = Vec3::UnitZ();
    std::array<Vec3, 3> inward{}; ///< unit in-plane normal of edge k, pointing into the face
    std::uint8_t owned_edges = 0, owned_vertices = 0; ///< bit k: edge k / vertex k is this face's
    std::uint32_t flat_begin = 0, flat_end = 0;       ///< coplanar faces sharing a vertex
  };
  struct Edge {
    std::array<std::uint32_t, 2> v{};
    Vec3 t = Vec3::UnitX();           ///< unit direction from v[0] to v[1]
    std::array<Vec3, 2> end_dir{};    ///< end test at v[j]: (y - P) . end_dir[j] > 0 (>= 0)
    std::array<bool, 2> end_closed{}; ///< true: >= 0
    std::uint32_t owner = 0;
    std::uint32_t faces_begin = 0, faces_end = 0;   ///< (face, local edge) in edge_faces_
    std::uint32_t guards_begin = 0, guards_end = 0; ///< faces coplanar with a face of the edge
    EdgeKind kind = EdgeKind::boundary;
  };
  struct Vertex {
    Vec3 p = Vec3::Zero();
    std::uint32_t owner = 0;
    double margin = 0.0;
    std::uint32_t edges_begin = 0, edges_end = 0; ///< (edge, end) in vertex_edges_
    std::uint32_t faces_begin = 0, faces_end = 0; ///< faces in vertex_faces_
  };

  /// s_fk: distance of y's projection inside face f across its edge k.
  double side(std::uint32_t f, int k, const Vec3& y) const {
    const Face& F = faces_[f];
    return (y - vertices_[edges_[F.e[k]].v[0]].p).dot(F.inward[k]);
  }
  /// True if y's projection lies in face f (closed, widened by tol).
  bool candidate(std::uint32_t f, const Vec3& y) const {
    return side(f, 0, y) >= -tol_ && side(f, 1, y) >= -tol_ && side(f, 2, y) >= -tol_;
  }
  /// True if y passes edge e's test at its end j (lies beyond the end plane, into the edge).
  bool past_end(std::uint32_t e, int j, const Vec3& y) const {
    const Edge& E = edges_[e];
    const double q = (y - vertices_[E.v[j]].p).dot(E.end_dir[j]);
    return E.end_closed[j] ? q >= 0.0 : q > 0.0;
  }
  bool in_edge(std::uint32_t e, const Vec3& y) const {
    const Edge& E = edges_[e];
    double nearest = -std::numeric_limits<double>::infinity();
    for (auto k = E.faces_begin; k < E.faces_end; ++k) {
      const double s = side(edge_faces_[k].first, edge_faces_[k].second, y);
      if (s >= -tol_) return false;
      nearest = std::max(nearest, s);
    }
    if (!past_end(e, 0, y) || !past_end(e, 1, y)) return false;
    // within a few tol of a face of the edge, a coplanar face widened by tol near an end of the
    // edge may claim y too: the face contact takes it
    if (nearest >= -8.0 * tol_)
      for (auto k = E.guards_begin; k < E.guards_end; ++k)
        if (candidate(guards_[k], y)) return false;
    return true;
  }
  bool in_vertex(std::uint32_t v, const Vec3& y) const {
    const Vertex& V = vertices_[v];
    for (auto k = V.edges_begin; k < V.edges_end; ++k)
      if (past_end(vertex_edges_[k].first, vertex_edges_[k].second, y)) return false;
    for (auto k = V.faces_begin; k < V.faces_end; ++k)
      if (candidate(vertex_faces_[k], y)) return false;
    return true;
  }
  MeshContact none(std::uint32_t f) const {
    return {faces_[f].normal, std::numeric_limits<double>::infinity(), MeshContact::Feature::none,
            f};
  }
  MeshContact with_normal(const Vec3& d, std::uint32_t f, MeshContact::Feature kind,
                          std::uint32_t index) const {
    const double dist = d.norm();
    return {dist > 0.0 ? Vec3(d / dist) : faces_[f].normal, dist, kind, index};
  }

  /// Distance from the origin to the convex hull of unit vectors t (> 0), or <= 0 if the hull
  /// contains the origin (then minus the best margin found).
  static double cone_margin(const std::vector<Vec3>& t);

  /// Checks the arguments of `build` (sizes, finite coordinates, flat_angle, vertex indices);
  /// throws InputError naming `object`.
  static void check_input(const TriangleMesh& mesh, const Vec3& reference,
                          const std::string& object, double flat_angle);
  /// Sets the body-frame vertex positions X - reference [m] and tol from the diagonal of the
  /// bounding box of X.
  void place_vertices(const std::vector<Vec3>& X, const Vec3& reference);
  /// Sets each face's vertices, unit normal and inward edge normals; throws InputError naming
  /// `object` for a triangle with a repeated vertex or without area.
  void build_faces(const TriangleMesh& mesh, const std::string& object);
  /// Joins the faces' edges by their vertex pairs: each edge's direction, end tests, faces,
  /// kind and owner, and each face's edge indices and owned edges. Two faces whose inward edge
  /// normals sum to at most `chord_flat` make a flat edge.
  void build_edges(double chord_flat);
  /// Lists each vertex's edges (with the end that is the vertex) and faces (ascending).
  void build_vertex_incidence();
  /// Sets each used vertex's owner and convexity margin, joins the end planes of edges that go
  /// on in a straight line through it, and marks it owned by its owner face if its cone has an
  /// interior.
  void build_vertex_cones(double chord_flat);
  /// Gives edges of vertex V that go on in a straight line (directions `dirs` leaving V, summing
  /// to at most `chord_flat`) one end plane: closed for the lower edge, open for the other.
  void pair_straight_edges(const Vertex& V, const std::vector<Vec3>& dirs, double chord_flat);
  /// Lists, for each face, the faces that share a vertex with it and lie in its plane (normals
  /// within `sin_flat`), ascending.
  void build_flat_neighbours(double sin_flat);
  /// Lists each edge's guards: the faces coplanar with one of its faces that do not contain it.
  void build_edge_guards();

  std::vector<Face> faces_;
  std::vector<Edge> edges_;
  std::vector<Vertex> vertices_;
  std::vector<std::pair<std::uint32_t, std::uint8_t>> edge_faces_;   ///< (face, local edge k)
  std::vector<std::pair<std::uint32_t, std::uint8_t>> vertex_edges_; ///< (edge, end j)
  std::vector<std::uint32_t> vertex_faces_, flat_, guards_;
  double tol_ = 0.0;
  double flat_angle_ = 0.0;
};

namespace detail {

/// Closest point to the origin on segment ab.
inline Vec3 origin_on_segment(const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double l2 = ab.squaredNorm();
  if (!(l2 > 0.0)) return a;
  const double s = std::clamp(-a.dot(ab) / l2, 0.0, 1.0);
  return a + s * ab;
}

/// Closest point to the origin on the plane triangle abc if the origin projects inside it
/// (false otherwise, and for a degenerate triangle: the edges cover those cases).
inline bool origin_on_triangle(const Vec3& a, const Vec3& b, const Vec3& c, Vec3& q) {
  const Vec3 n = (b - a).cross(c - a);
  const double n2 = n.squaredNorm();
  if (!(n2 > 1e-24)) return false;
  const Vec3 p = (a.dot(n) / n2) * n; // projection of the origin on the plane
  if ((b - a).cross(p - a).dot(n) < 0.0 || (c - b).cross(p - b).dot(n) < 0.0 ||
      (a - c).cross(p - c).dot(n) < 0.0)
    return false;
  q = p;
  return true;
}

/// "(x, y, z)" of a point, for error messages.
inline std::string mesh_point_text(const Vec3& p) {
  using grain::detail::to_text;
  return "(" + to_text(p.x()) + ", " + to_text(p.y()) + ", " + to_text(p.z()) + ")";
}

} // namespace detail

inline double MeshFeatures::cone_margin(const std::vector<Vec3>& t) {
  // The hull's point nearest the origin lies on a vertex, an edge or a triangle of the hull; for
  // each candidate q the margin of the direction d = -q/|q| is min_e (q . t_e)/|q|. If the hull
  // contains the origin every direction has a margin <= 0 (Gordan's alternative), otherwise the
  // nearest point gives the largest margin, |q|.
  double best = -std::numeric_limits<double>::infinity();
  auto consider = [&](const Vec3& q) {
    const double n = q.norm();
    if (!(n > 1e-300)) {
      best = std::max(best, 0.0);
      return;
    }
    double m = std::numeric_limits<double>::infinity();
    for (const auto& u : t)
      m = std::min(m, q.dot(u) / n);
    best = std::max(best, m);
  };
  const std::size_t k = t.size();
  for (std::size_t i = 0; i < k; ++i) {
    consider(t[i]);
    for (std::size_t j = i + 1; j < k; ++j) {
      consider(detail::origin_on_segment(t[i], t[j]));
      for (std::size_t l = j + 1; l < k; ++l) {
        Vec3 q;
        if (detail::origin_on_triangle(t[i], t[j], t[l], q)) consider(q);
      }
    }
  }
  return best;
}

inline std::shared_ptr<const MeshFeatures> MeshFeatures::build(const TriangleMesh& mesh,
                                                               const Vec3& reference,
                                                               const std::string& object,
                                                               double flat_angle) {
  check_input(mesh, reference, object, flat_angle);
  auto out = std::make_shared<MeshFeatures>();
  MeshFeatures& m = *out;
  m.flat_angle_ = flat_angle;
  m.place_vertices(mesh.vertices, reference);
  m.build_faces(mesh, object);
  const double sin_flat = std::max(std::sin(flat_angle), 1e-12);
  const double chord_flat = std::max(2.0 * std::sin(0.5 * flat_angle), 1e-12);
  m.build_edges(chord_flat);
  m.build_vertex_incidence();
  m.build_vertex_cones(chord_flat);
  m.build_flat_neighbours(sin_flat);
  m.build_edge_guards();
  return out;
}

inline void MeshFeatures::check_input(const TriangleMesh& mesh, const Vec3& reference,
                                      const std::string& object, double flat_angle) {
  using grain::detail::require;
  const auto& X = mesh.vertices;
  const auto& T = mesh.triangles;
  const std::size_t nv = X.size(), nf = T.size();
  require(nf > 0, object, "number of triangles", nf, "[1, inf) (a mesh needs triangles)");
  require(nf < (std::size_t(1) << 31) && nv < (std::size_t(1) << 31), object, "mesh size",
          std::to_string(nv) + " vertices, " + std::to_string(nf) + " triangles",
          "below 2^31 of each");
  require(all_finite(reference), object, "reference point", detail::mesh_point_text(reference),
          "finite coordinates [m]");
  require(std::isfinite(flat_angle) && flat_angle >= 0.0 && flat_angle < 0.5 * std::numbers::pi,
          object, "flat_angle", flat_angle, "[0, pi/2) rad");
  for (std::size_t i = 0; i < nv; ++i)
    require(all_finite(X[i]), object, ("vertex " + std::to_string(i)).c_str(),
            detail::mesh_point_text(X[i]), "finite coordinates [m]");
  for (std::size_t f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k)
      require(T[f][k] < nv, object,
              ("triangle " + std::to_string(f) + " vertex index " + std::to_string(k)).c_str(),
              T[f][k], "[0, " + std::to_string(nv) + ") (the mesh's vertices)");
}

inline void MeshFeatures::place_vertices(const std::vector<Vec3>& X, const Vec3& reference) {
  const std::size_t nv = X.size();
  vertices_.resize(nv);
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::size_t i = 0; i < nv; ++i) {
    vertices_[i].p = X[i] - reference;
    lo = lo.cwiseMin(X[i]);
    hi = hi.cwiseMax(X[i]);
  }
  tol_ = 1e-12 * std::max((hi - lo).norm(), std::numeric_limits<double>::min());
}

inline void MeshFeatures::build_faces(const TriangleMesh& mesh, const std::string& object) {
  using grain::detail::require;
  using grain::detail::to_text;
  const auto& X = mesh.vertices;
  const auto& T = mesh.triangles;
  const std::size_t nf = T.size();
  faces_.resize(nf);
  for (std::size_t f = 0; f < nf; ++f) {
    Face& F = faces_[f];
    F.v = T[f];
    // the messages are built with += only when a check fails (GCC 12 reports a false -Wrestrict
    // for "literal" + std::string&& here)
    if (F.v[0] == F.v[1] || F.v[1] == F.v[2] || F.v[2] == F.v[0]) {
      std::string what = "triangle ", value = std::to_string(F.v[0]);
      what += std::to_string(f);
      what += " vertex indices";
      value += ", ";
      value += std::to_string(F.v[1]);
      value += ", ";
      value += std::to_string(F.v[2]);
      require(false, object, what.c_str(), value, "three different vertices");
    }
    const Vec3 &a = X[F.v[0]], &b = X[F.v[1]], &c = X[F.v[2]];
    const Vec3 n = (b - a).cross(c - a);
    const double longest =
        std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    if (!(n.norm() > 1e-10 * longest)) {
      std::string what = "triangle ", range = "(";
      what += std::to_string(f);
      what += " area";
      range += to_text(0.5e-10 * longest);
      range += ", inf) m^2 (above 1e-10 times half its longest edge squared: corners ";
      range += detail::mesh_point_text(a);
      range += ", ";
      range += detail::mesh_point_text(b);
      range += ", ";
      range += detail::mesh_point_text(c);
      range += " are collinear)";
      require(false, object, what.c_str(), 0.5 * n.norm(), range);
    }
    const auto& P = vertices_;
    F.normal = (P[F.v[1]].p - P[F.v[0]].p).cross(P[F.v[2]].p - P[F.v[0]].p).normalized();
    for (int k = 0; k < 3; ++k) {
      const Vec3 t = P[F.v[(k + 1) % 3]].p - P[F.v[k]].p;
      F.inward[k] = F.normal.cross(t).normalized();
    }
  }
}

inline void MeshFeatures::build_edges(double chord_flat) {
  // sort the face edges by their vertex pair
  struct Record {
    std::uint32_t lo, hi, face;
    std::uint8_t k;
  };
  const std::size_t nf = faces_.size();
  std::vector<Record> rec;
  rec.reserve(3 * nf);
  for (std::uint32_t f = 0; f < nf; ++f)
    for (std::uint8_t k = 0; k < 3; ++k) {
      const auto a = faces_[f].v[k], b = faces_[f].v[(k + 1) % 3];
      rec.push_back({std::min(a, b), std::max(a, b), f, k});
    }
  std::sort(rec.begin(), rec.end(), [](const Record& x, const Record& y) {
    return std::tie(x.lo, x.hi, x.face, x.k) < std::tie(y.lo, y.hi, y.face, y.k);
  });
  for (std::size_t r = 0; r < rec.size();) {
    std::size_t s = r;
    while (s < rec.size() && rec[s].lo == rec[r].lo && rec[s].hi == rec[r].hi)
      ++s;
    Edge E;
    E.v = {rec[r].lo, rec[r].hi};
    E.t = (vertices_[E.v[1]].p - vertices_[E.v[0]].p).normalized();
    E.end_dir = {E.t, Vec3(-E.t)};
    E.end_closed = {false, false};
    E.owner = rec[r].face;
    E.faces_begin = static_cast<std::uint32_t>(edge_faces_.size());
    const auto e = static_cast<std::uint32_t>(edges_.size());
    for (std::size_t q = r; q < s; ++q) {
      edge_faces_.push_back({rec[q].face, rec[q].k});
      faces_[rec[q].face].e[rec[q].k] = e;
    }
    E.faces_end = static_cast<std::uint32_t>(edge_faces_.size());
    const std::size_t count = s - r;
    if (count == 1) {
      E.kind = EdgeKind::boundary;
    } else if (count == 2) {
      const Face &F = faces_[rec[r].face], &G = faces_[rec[r + 1].face];
      const bool flat = (F.inward[rec[r].k] + G.inward[rec[r + 1].k]).norm() <= chord_flat;
      E.kind = flat ? EdgeKind::flat : EdgeKind::fold;
    } else {
      E.kind = EdgeKind::nonmanifold;
    }
    faces_[E.owner].owned_edges |= static_cast<std::uint8_t>(1u << rec[r].k);
    edges_.push_back(E);
    r = s;
  }
}

inline void MeshFeatures::build_vertex_incidence() {
  const std::size_t nv = vertices_.size();
  std::vector<std::uint32_t> ecount(nv, 0), fcount(nv, 0);
  for (const auto& E : edges_) {
    ++ecount[E.v[0]];
    ++ecount[E.v[1]];
  }
  for (const auto& F : faces_)
    for (auto v : F.v)
      ++fcount[v];
  std::uint32_t eo = 0, fo = 0;
  for (std::size_t i = 0; i < nv; ++i) {
    vertices_[i].edges_begin = vertices_[i].edges_end = eo;
    vertices_[i].faces_begin = vertices_[i].faces_end = fo;
    eo += ecount[i];
    fo += fcount[i];
  }
  vertex_edges_.resize(eo);
  vertex_faces_.resize(fo);
  for (std::uint32_t e = 0; e < edges_.size(); ++e)
    for (std::uint8_t j = 0; j < 2; ++j) {
      Vertex& V = vertices_[edges_[e].v[j]];
      vertex_edges_[V.edges_end++] = {e, j};
    }
  for (std::uint32_t f = 0; f < faces_.size(); ++f)
    for (auto v : faces_[f].v) {
      Vertex& V = vertices_[v];
      vertex_faces_[V.faces_end++] = f; // ascending: faces are visited in order
    }
}

inline void MeshFeatures::build_vertex_cones(double chord_flat) {
  std::vector<Vec3> dirs;
  for (std::uint32_t i = 0; i < vertices_.size(); ++i) {
    Vertex& V = vertices_[i];
    if (V.faces_begin == V.faces_end) continue; // unused vertex
    V.owner = vertex_faces_[V.faces_begin];
    dirs.clear();
    for (auto k = V.edges_begin; k < V.edges_end; ++k) {
      const auto [e, j] = vertex_edges_[k];
      dirs.push_back(j == 0 ? edges_[e].t : Vec3(-edges_[e].t));
    }
    V.margin = cone_margin(dirs);
    pair_straight_edges(V, dirs, chord_flat);
    // a vertex whose cone has no interior (margin < 0 beyond round-off) never reports
    if (V.margin >= -1e-9) {
      Face& F = faces_[V.owner];
      for (int k = 0; k < 3; ++k)
        if (F.v[k] == i) F.owned_vertices |= static_cast<std::uint8_t>(1u << k);
    }
  }
}

inline void MeshFeatures::pair_straight_edges(const Vertex& V, const std::vector<Vec3>& dirs,
                                              double chord_flat) {
  // edges that go on in a straight line through the vertex share one end plane: the lower
  // edge takes the points on it (>= 0), the other the rest (> 0 of the opposite direction)
  std::vector<bool> paired(dirs.size(), false);
  for (std::size_t a = 0; a < dirs.size(); ++a) {
    if (paired[a]) continue;
    for (std::size_t b = a + 1; b < dirs.size(); ++b) {
      if (paired[b] || (dirs[a] + dirs[b]).norm() > chord_flat) continue;
      const auto [ea, ja] = vertex_edges_[V.edges_begin + a];
      const auto [eb, jb] = vertex_edges_[V.edges_begin + b];
      const auto first = std::min(ea, eb) == ea ? std::pair{ea, ja} : std::pair{eb, jb};
      const auto second = std::min(ea, eb) == ea ? std::pair{eb, jb} : std::pair{ea, ja};
      Edge& A = edges_[first.first];
      Edge& B = edges_[second.first];
      A.end_closed[first.second] = true;
      B.end_dir[second.second] = -A.end_dir[first.second];
      B.end_closed[second.second] = false;
      paired[a] = paired[b] = true;
      break;
    }
  }
}

inline void MeshFeatures::build_flat_neighbours(double sin_flat) {
  std::vector<std::uint32_t> near;
  for (std::uint32_t f = 0; f < faces_.size(); ++f) {
    Face& F = faces_[f];
    near.clear();
    for (auto v : F.v) {
      const Vertex& V = vertices_[v];
      for (auto k = V.faces_begin; k < V.faces_end; ++k) {
        const auto g = vertex_faces_[k];
        if (g != f && F.normal.cross(faces_[g].normal).norm() <= sin_flat) near.push_back(g);
      }
    }
    std::sort(near.begin(), near.end());
    near.erase(std::unique(near.begin(), near.end()), near.end());
    F.flat_begin = static_cast<std::uint32_t>(flat_.size());
    flat_.insert(flat_.end(), near.begin(), near.end());
    F.flat_end = static_cast<std::uint32_t>(flat_.size());
  }
}

inline void MeshFeatures::build_edge_guards() {
  std::vector<std::uint32_t> near;
  for (auto& E : edges_) {
    near.clear();
    for (auto k = E.faces_begin; k < E.faces_end; ++k) {
      const Face& F = faces_[edge_faces_[k].first];
      near.insert(near.end(), flat_.begin() + F.flat_begin, flat_.begin() + F.flat_end);
    }
    std::sort(near.begin(), near.end());
    near.erase(std::unique(near.begin(), near.end()), near.end());
    E.guards_begin = static_cast<std::uint32_t>(guards_.size());
    for (auto g : near) {
      bool of_edge = false;
      for (auto k = E.faces_begin; k < E.faces_end; ++k)
        of_edge |= edge_faces_[k].first == g;
      if (!of_edge) guards_.push_back(g);
    }
    E.guards_end = static_cast<std::uint32_t>(guards_.size());
  }
}

} // namespace grain::walls
