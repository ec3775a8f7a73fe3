#pragma once
/// \file mesh.hpp
/// Mass, centre of mass and inertia of a rigid body made of first-order solid elements
/// (tetrahedra, pyramids, wedges, hexahedra), each with its own density, computed exactly by
/// splitting every element into tetrahedra and summing closed-form tetrahedron moments.
///
/// Units (SI): coordinates m, density kg/m^3, volume m^3, mass kg, inertia kg m^2; colours are
/// integer labels >= 0.
///
/// ## Node ordering (VTK linear cells)
/// Node numbers as in the VTK linear cells (types 10, 14, 13, 12), positive orientation:
/// - tetrahedron, 4 nodes: the right-hand normal of triangle (0,1,2) points towards node 3;
/// - pyramid, 5 nodes: the right-hand normal of the base quadrilateral (0,1,2,3) points towards
///   the apex 4;
/// - wedge, 6 nodes: triangles (0,1,2) and (3,4,5) joined by the edges 0-3, 1-4, 2-5; the
///   right-hand normal of (0,1,2) points *away from* (3,4,5) (VTK's wedge convention, opposite
///   to that of its other cells);
/// - hexahedron, 8 nodes: the right-hand normal of quadrilateral (0,1,2,3) points towards
///   (4,5,6,7), joined by the edges 0-4, 1-5, 2-6, 3-7.
///
/// An element given in the opposite orientation has a negative volume and is rejected
/// (`InputError` naming the element, its kind and the volume).
///
/// ## Decomposition into tetrahedra
/// A tetrahedron is used as is. Every other element is split into tetrahedra that join its
/// centre c (the mean of its nodes) to a triangulation of its boundary: a triangular face gives
/// one tetrahedron; a quadrilateral face (n0,n1,n2,n3) is split into four triangles about its
/// face centre f = (n0+n1+n2+n3)/4 and gives four. So a pyramid is split into 4 + 4 = 8
/// tetrahedra, a wedge into 2 + 3*4 = 14 and a hexahedron into 6*4 = 24.
///
/// With planar faces the union of the tetrahedra is exactly the element, so mass, centre and
/// inertia are exact (to round-off), whatever the split. A quadrilateral face that is not planar
/// does not define a unique surface; the four-triangle split
/// - depends only on the face's nodes, so two elements sharing a face use the same surface and
///   the mesh has no gaps or overlaps;
/// - does not depend on the numbering of the face's nodes, unlike a split along one diagonal;
/// - encloses exactly the volume of the trilinear (isoparametric) element, so the mass is that
///   of the isoparametric element. Its centre and inertia differ from the isoparametric
///   element's by terms that vanish with the face warp (a unit cube whose nodes are moved at
///   random by up to 0.15: the centre moves by about 2e-4, the second moments by about 0.3 %).
///
/// ## Tetrahedron moments
/// For a tetrahedron with vertices x0..x3, signed volume V = (x1-x0) x (x2-x0) . (x3-x0) / 6,
/// S = x0 + x1 + x2 + x3:
///
///     int dV = V,   int x dV = V S / 4,
///     int x x^T dV = V/20 (x0 x0^T + x1 x1^T + x2 x2^T + x3 x3^T + S S^T)
///
/// (exact for a linear simplex; F. Tonon, Explicit exact formulas for the 3-D tetrahedron
/// inertia tensor in terms of its vertex coordinates, J. Math. Stat. 1 (2005) 8-11). With
/// C = sum over elements of rho int x x^T dV, mass m and centre c, the inertia about the centre is
///
///     J = (tr C' ) 1 - C',   C' = C - m c c^T.
///
/// ## Boundary surface and face colours
/// `mesh_surface` gives the faces of the elements that belong to exactly one element (faces are
/// compared by their sets of nodes), as triangles and quadrilaterals numbered as in the element's
/// outward face table (`detail::element_faces`: right-hand normals out of the element, hence out
/// of the body), with the nodes they use in local coordinates about the centre of mass. Each face
/// has a colour (Parmec's MESH `colors`, `FaceColors`): the global colour, or that of a listed
/// face with the same set of nodes.
///
/// References: VTK file formats (Kitware), linear cell types 10, 12, 13, 14.

#include <grain/bodies/rigid_body.hpp>
#include <grain/core/error.hpp>
#include <grain/core/vector.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace grain::bodies {

/// One element: 4, 5, 6 or 8 node indices (see the ordering table) and its density [kg/m^3].
struct Element {
  std::vector<std::size_t> nodes;
  double density = 0.0;
};

/// A meshed body: node coordinates [m] and elements.
struct Mesh {
  std::vector<Vec3> nodes;
  std::vector<Element> elements;
};

/// Mass properties of a body: volume [m^3], mass [kg], centre of mass [m] and inertia tensor
/// about the centre in the mesh's axes [kg m^2].
struct MassProperties {
  double volume = 0.0;
  double mass = 0.0;
  Vec3 centre = Vec3::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
};

/// Inertia about a point displaced by d from the centre of mass (parallel-axis theorem):
/// J_d = J_c + m (d.d 1 - d d^T).
inline Eigen::Matrix3d parallel_axis(const Eigen::Matrix3d& j_centre, double mass, const Vec3& d) {
  return j_centre + mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
}

namespace detail {

/// Raw moments: int dV, int x dV, int x x^T dV.
struct Moments {
  double v = 0.0;
  Vec3 first = Vec3::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  Moments& operator+=(const Moments& o) {
    v += o.v;
    first += o.first;
    second += o.second;
    return *this;
  }
};

inline double tet_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (b - a).cross(c - a).dot(d - a) / 6.0;
}

/// Closed-form moments of the tetrahedron (a, b, c, d) with its signed volume.
inline Moments tet_moments(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  Moments m;
  m.v = tet_volume(a, b, c, d);
  const Vec3 s = a + b + c + d;
  m.first = m.v * 0.25 * s;
  m.second = (m.v / 20.0) * (a * a.transpose() + b * b.transpose() + c * c.transpose() +
                             d * d.transpose() + s * s.transpose());
  return m;
}

inline const char* element_kind(std::size_t n) {
  switch (n) {
  case 4:
    return "tetrahedron";
  case 5:
    return "pyramid";
  case 6:
    return "wedge";
  case 8:
    return "hexahedron";
  default:
    return "unknown element";
  }
}

/// Outward faces (right-hand normals pointing out of the element) in local node numbers; a
/// triangle has its fourth entry equal to -1.
inline std::span<const std::array<int, 4>> element_faces(std::size_t n) {
  static constexpr std::array<std::array<int, 4>, 4> tetrahedron{
      {{0, 2, 1, -1}, {0, 1, 3, -1}, {1, 2, 3, -1}, {2, 0, 3, -1}}};
  static constexpr std::array<std::array<int, 4>, 5> pyramid{
      {{0, 3, 2, 1}, {0, 1, 4, -1}, {1, 2, 4, -1}, {2, 3, 4, -1}, {3, 0, 4, -1}}};
  static constexpr std::array<std::array<int, 4>, 5> wedge{
      {{0, 1, 2, -1}, {3, 5, 4, -1}, {0, 3, 4, 1}, {1, 4, 5, 2}, {2, 5, 3, 0}}};
  static constexpr std::array<std::array<int, 4>, 6> hexahedron{
      {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}}};
  switch (n) {
  case 4:
    return tetrahedron;
  case 5:
    return pyramid;
  case 6:
    return wedge;
  case 8:
    return hexahedron;
  default:
    return {};
  }
}

/// Calls f(a, b, c, d) for each positively oriented tetrahedron of the decomposition of the
/// element with node coordinates x[0..n-1] (see the file comment).
template <class F>
void for_each_tetrahedron(const Vec3* x, std::size_t n, F&& f) {
  if (n == 4) {
    f(x[0], x[1], x[2], x[3]);
    return;
  }
  Vec3 c = Vec3::Zero();
  for (std::size_t k = 0; k < n; ++k)
    c += x[k];
  c /= static_cast<double>(n);
  for (const auto& face : element_faces(n)) {
    if (face[3] < 0) {
      // outward triangle (t0, t1, t2): (t2, t1, t0) has its normal towards c
      f(x[face[2]], x[face[1]], x[face[0]], c);
    } else {
      const Vec3 fc = 0.25 * (x[face[0]] + x[face[1]] + x[face[2]] + x[face[3]]);
      for (int k = 0; k < 4; ++k)
        f(fc, x[face[(k + 1) % 4]], x[face[k]], c);
    }
  }
}

/// Moments of one element about the point `origin`, validated: known node count, node indices
/// in range, a total volume above 1e-12 L^3 (L = the element's largest coordinate extent) and
/// every sub-tetrahedron with a positive volume.
inline Moments element_moments(const std::vector<Vec3>& nodes, const Element& e, std::size_t index,
                               const std::string& object, const Vec3& origin) {
  const std::size_t n = e.nodes.size();
  const std::string name = object + " element " + std::to_string(index);
  grain::detail::require(n == 4 || n == 5 || n == 6 || n == 8, name, "number of nodes", n,
                         "4 (tetrahedron), 5 (pyramid), 6 (wedge) or 8 (hexahedron)");
  const std::string kind = name + " (" + element_kind(n) + ")";
  grain::detail::require_positive(kind, "density", e.density);
  std::array<Vec3, 8> x;
  x.fill(Vec3::Zero());
  for (std::size_t k = 0; k < n; ++k) {
    grain::detail::require(e.nodes[k] < nodes.size(), kind, "node index", e.nodes[k],
                           "[0, " + std::to_string(nodes.size()) + ")");
    grain::detail::require(nodes[e.nodes[k]].allFinite(), kind, "node coordinates",
                           nodes[e.nodes[k]].transpose(), "finite [m]");
    x[k] = nodes[e.nodes[k]] - origin;
  }
  Vec3 lo = x[0], hi = x[0];
  for (std::size_t k = 1; k < n; ++k) {
    lo = lo.cwiseMin(x[k]);
    hi = hi.cwiseMax(x[k]);
  }
  const double ext = (hi - lo).maxCoeff();
  const double tol = 1e-12 * ext * ext * ext;
  Moments m;
  double min_tet = std::numeric_limits<double>::infinity();
  for_each_tetrahedron(x.data(), n,
                       [&](const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
                         const Moments t = tet_moments(a, b, c, d);
                         min_tet = std::min(min_tet, t.v);
                         m += t;
                       });
  grain::detail::require(m.v > tol, kind, "volume", m.v,
                         "(0, inf) m^3; a negative volume means an inverted element (node order "
                         "not as in VTK), a zero volume a degenerate one");
  grain::detail::require(min_tet > 0.0, kind, "smallest sub-tetrahedron volume", min_tet,
                         "(0, inf) m^3; the element is tangled (self-intersecting or "
                         "not star-shaped about its centre)");
  return m;
}

} // namespace detail

/// Mass properties of one element (validated as in `mass_properties`).
inline MassProperties element_mass_properties(const std::vector<Vec3>& nodes, const Element& e) {
  const Vec3 origin =
      e.nodes.empty() || e.nodes[0] >= nodes.size() ? Vec3::Zero() : nodes[e.nodes[0]];
  const detail::Moments m = detail::element_moments(nodes, e, 0, "mesh", origin);
  MassProperties p;
  p.volume = m.v;
  p.mass = e.density * m.v;
  p.centre = m.first / m.v;
  const Eigen::Matrix3d c = e.density * m.second - p.mass * p.centre * p.centre.transpose();
  p.inertia = c.trace() * Eigen::Matrix3d::Identity() - c;
  p.centre += origin;
  return p;
}

/// Mass properties of a meshed body (sum over its elements, each with its own density). Throws
/// InputError for an empty mesh, a wrong node count, a node index out of range, a density that
/// is not finite and > 0, non-finite coordinates, or a degenerate, inverted or tangled element
/// (the message names the element, its kind and the offending value).
inline MassProperties mass_properties(const Mesh& mesh, const std::string& object = "mesh") {
  grain::detail::require(!mesh.elements.empty(), object, "number of elements", mesh.elements.size(),
                         "at least 1");
  // Moments are taken about the mean node position to avoid cancellation in C - m c c^T for a
  // mesh far from the origin.
  Vec3 origin = Vec3::Zero();
  for (const Vec3& x : mesh.nodes)
    origin += x;
  if (!mesh.nodes.empty()) origin /= static_cast<double>(mesh.nodes.size());
  if (!origin.allFinite()) origin.setZero(); // non-finite nodes are reported per element
  double mass = 0.0, volume = 0.0;
  Vec3 first = Vec3::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < mesh.elements.size(); ++i) {
    const Element& e = mesh.elements[i];
    const detail::Moments m = detail::element_moments(mesh.nodes, e, i, object, origin);
    volume += m.v;
    mass += e.density * m.v;
    first += e.density * m.first;
    second += e.density * m.second;
  }
  MassProperties p;
  p.volume = volume;
  p.mass = mass;
  p.centre = first / mass;
  const Eigen::Matrix3d c = second - mass * p.centre * p.centre.transpose();
  p.inertia = c.trace() * Eigen::Matrix3d::Identity() - c;
  p.inertia = 0.5 * (p.inertia + p.inertia.transpose()).eval();
  p.centre += origin;
  return p;
}

/// The rigid body of a mesh in its given configuration: mass and inertia from the elements,
/// position = centre of mass, reference frame = world axes (rotation identity); local
/// coordinates of node k are then nodes[k] - centre.
inline RigidBody mesh_body(const Mesh& mesh, const Vec3& velocity = Vec3::Zero(),
                           const Vec3& omega = Vec3::Zero(), const std::string& object = "mesh") {
  const MassProperties p = mass_properties(mesh, object);
  RigidBody b;
  b.mass = p.mass;
  b.inertia = p.inertia;
  b.position = p.centre;
  b.velocity = velocity;
  b.omega = omega;
  b.name = object;
  return b;
}

/// Face colours of a meshed body (Parmec's MESH `colors`): `global` for every boundary face that
/// is not listed, and per-face overrides, each a face given by its nodes (3 or 4 mesh node
/// indices, in any order and from any starting node: a face is matched by its set of nodes) and
/// its colour. Colours are labels, integers >= 0 (the seed asks for positive ones; Parmec's
/// decks also colour faces 0); a face listed twice takes its last colour.
struct FaceColors {
  int global = 1;
  std::vector<std::pair<std::vector<std::size_t>, int>> faces{};
};

/// Face colours from Parmec's MESH flat list [gcolor, f1, n1 .. nf1, c1, f2, ...] (or [gcolor]
/// alone): gcolor the global colour, f the number of nodes of a listed face (3 or 4), n its
/// nodes, c its colour. Throws InputError for an empty list, a colour outside [0, INT_MAX], a
/// face of another size, a negative node or a list that ends inside a face.
inline FaceColors face_colors_from_list(std::span<const long> list,
                                        const std::string& object = "mesh") {
  const std::string obj = object + " colour list";
  constexpr long max_colour = std::numeric_limits<int>::max();
  const std::string colours = "[0, " + std::to_string(max_colour) + "] (an integer label)";
  grain::detail::require(!list.empty(), obj, "length", list.size(),
                         "at least 1 entry (the global colour)");
  grain::detail::require(list[0] >= 0 && list[0] <= max_colour, obj, "global colour", list[0],
                         colours);
  FaceColors out;
  out.global = static_cast<int>(list[0]);
  std::size_t k = 1;
  while (k < list.size()) {
    const std::string name = obj + " entry " + std::to_string(out.faces.size());
    const long n = list[k];
    grain::detail::require(n == 3 || n == 4, name, "number of nodes", n,
                           "3 or 4 (a triangle or a quadrilateral)");
    const auto m = static_cast<std::size_t>(n);
    grain::detail::require(k + m + 1 < list.size(), name, "list length", list.size(),
                           "at least " + std::to_string(k + m + 2) + " entries");
    std::vector<std::size_t> nodes;
    for (std::size_t j = 0; j < m; ++j) {
      const long node = list[k + 1 + j];
      grain::detail::require(node >= 0, name, "node", node, "[0, inf) (a mesh node index)");
      nodes.push_back(static_cast<std::size_t>(node));
    }
    const long c = list[k + m + 1];
    grain::detail::require(c >= 0 && c <= max_colour, name, "colour", c, colours);
    out.faces.emplace_back(std::move(nodes), static_cast<int>(c));
    k += m + 2;
  }
  return out;
}

/// The boundary surface of a meshed body: the faces of its elements that belong to exactly one
/// element, as triangles or quadrilaterals.
struct MeshSurface {
  /// The nodes used by boundary faces, in local coordinates: relative to the body's centre of
  /// mass in the mesh's axes, so that world = position + rotation * local [m].
  std::vector<Vec3> nodes{};
  /// 3 or 4 indices into `nodes` per face, ordered so that the right-hand normal points out of
  /// the body (the element's outward orientation).
  std::vector<std::vector<std::uint32_t>> faces{};
  std::vector<int> colors{};           ///< colour of each face
  std::vector<std::size_t> elements{}; ///< the element each face belongs to
};

namespace detail {

/// A face's sorted node list, padded with the largest size_t for a triangle.
inline std::array<std::size_t, 4> face_key(std::span<const std::size_t> nodes) {
  std::array<std::size_t, 4> key;
  key.fill(std::numeric_limits<std::size_t>::max());
  std::copy(nodes.begin(), nodes.end(), key.begin());
  std::sort(key.begin(), key.end());
  return key;
}

inline std::string node_list_text(std::span<const std::size_t> nodes) {
  std::string s = "(";
  for (std::size_t k = 0; k < nodes.size(); ++k)
    s += (k ? ", " : "") + std::to_string(nodes[k]);
  return s + ")";
}

} // namespace detail

/// The boundary surface of a mesh (see MeshSurface) with its face colours: faces in the order of
/// their elements and, within an element, of the face tables of `detail::element_faces`; nodes in
/// the order of first use, relative to the mesh's centre of mass (`mass_properties`). Validates
/// the mesh as `mass_properties` does, and throws InputError (naming the object, the value and
/// the valid range) for a colour < 0, a listed face with other than 3 or 4 nodes, with an
/// unknown node, or whose nodes are not those of a boundary face.
inline MeshSurface mesh_surface(const Mesh& mesh, const FaceColors& colors = {},
                                const std::string& object = "mesh") {
  const MassProperties props = mass_properties(mesh, object);
  grain::detail::require(colors.global >= 0, object, "global colour", colors.global,
                         "[0, inf) (an integer label)");
  // every face of every element, with its sorted nodes
  struct Face {
    std::array<std::size_t, 4> key;
    std::size_t element;
    std::array<int, 4> local;
  };
  std::vector<Face> all;
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    const std::vector<std::size_t>& en = mesh.elements[e].nodes;
    for (const auto& f : detail::element_faces(en.size())) {
      std::array<std::size_t, 4> nodes{};
      const std::size_t m = f[3] < 0 ? 3 : 4;
      for (std::size_t j = 0; j < m; ++j)
        nodes[j] = en[static_cast<std::size_t>(f[j])];
      all.push_back({detail::face_key(std::span<const std::size_t>(nodes.data(), m)), e, f});
    }
  }
  std::vector<std::size_t> order(all.size());
  for (std::size_t k = 0; k < order.size(); ++k)
    order[k] = k;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return all[a].key < all[b].key; });
  std::vector<bool> boundary(all.size(), false);
  for (std::size_t k = 0; k < order.size();) {
    std::size_t j = k + 1;
    while (j < order.size() && all[order[j]].key == all[order[k]].key)
      ++j;
    if (j == k + 1) boundary[order[k]] = true;
    k = j;
  }
  // boundary faces in element order, with the global colour
  MeshSurface s;
  std::vector<std::size_t> face_of(all.size(), 0);
  std::vector<std::uint32_t> number(mesh.nodes.size(), std::numeric_limits<std::uint32_t>::max());
  for (std::size_t k = 0; k < all.size(); ++k) {
    if (!boundary[k]) continue;
    const Face& f = all[k];
    const std::vector<std::size_t>& en = mesh.elements[f.element].nodes;
    std::vector<std::uint32_t> face;
    for (const int j : f.local) {
      if (j < 0) break;
      const std::size_t node = en[static_cast<std::size_t>(j)];
      if (number[node] == std::numeric_limits<std::uint32_t>::max()) {
        number[node] = static_cast<std::uint32_t>(s.nodes.size());
        s.nodes.push_back(mesh.nodes[node] - props.centre);
      }
      face.push_back(number[node]);
    }
    face_of[k] = s.faces.size();
    s.faces.push_back(std::move(face));
    s.colors.push_back(colors.global);
    s.elements.push_back(f.element);
  }
  // overrides, matched by their sets of nodes
  for (std::size_t c = 0; c < colors.faces.size(); ++c) {
    const auto& [nodes, colour] = colors.faces[c];
    const std::string name = object + " face colour " + std::to_string(c);
    grain::detail::require(colour >= 0, name, "colour", colour, "[0, inf) (an integer label)");
    grain::detail::require(nodes.size() == 3 || nodes.size() == 4, name, "number of nodes",
                           nodes.size(), "3 or 4 (a triangle or a quadrilateral)");
    for (const std::size_t n : nodes)
      grain::detail::require(n < mesh.nodes.size(), name, "node", n,
                             "[0, " + std::to_string(mesh.nodes.size()) + ") (the mesh's nodes)");
    const auto key = detail::face_key(nodes);
    const auto it = std::lower_bound(
        order.begin(), order.end(), key,
        [&](std::size_t a, const std::array<std::size_t, 4>& k) { return all[a].key < k; });
    const bool found = it != order.end() && all[*it].key == key;
    grain::detail::require(found && boundary[*it], name, "nodes", detail::node_list_text(nodes),
                           found ? "the nodes of a boundary face (this face is shared by two "
                                   "elements: it is inside the body)"
                                 : "the nodes of a boundary face (no element has a face with "
                                   "these nodes)");
    s.colors[face_of[*it]] = colour;
  }
  return s;
}

/// Elements from Parmec's MESH flat list [n, node_1 .. node_n, material, n, ...] with one density
/// per material number [kg/m^3].
inline std::vector<Element> elements_from_list(std::span<const std::size_t> list,
                                               std::span<const double> density_of_material) {
  std::vector<Element> out;
  std::size_t k = 0;
  while (k < list.size()) {
    const std::size_t n = list[k];
    const std::string name = "mesh element list entry " + std::to_string(out.size());
    grain::detail::require(n == 4 || n == 5 || n == 6 || n == 8, name, "number of nodes", n,
                           "4, 5, 6 or 8");
    grain::detail::require(k + n + 1 < list.size(), name, "list length", list.size(),
                           "at least " + std::to_string(k + n + 2) + " entries");
    Element e;
    e.nodes.assign(list.begin() + static_cast<std::ptrdiff_t>(k + 1),
                   list.begin() + static_cast<std::ptrdiff_t>(k + 1 + n));
    const std::size_t mat = list[k + n + 1];
    grain::detail::require(mat < density_of_material.size(), name, "material", mat,
                           "[0, " + std::to_string(density_of_material.size()) + ")");
    e.density = density_of_material[mat];
    out.push_back(std::move(e));
    k += n + 2;
  }
  return out;
}

} // namespace grain::bodies
