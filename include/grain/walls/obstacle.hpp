#pragma once
/// \file obstacle.hpp
/// Obstacles: triangle sets that move rigidly with a prescribed linear velocity v(t) [m/s] of a
/// reference point and angular velocity w(t) [rad/s] about it (Parmec's OBSTACLE).
///
/// \code
/// walls::TriangleMesh box = ...;                      // vertices [m] + vertex-index triples
/// auto lid = grain::add_obstacle(sim, box, {.name = "lid", .material = steel,
///                                          .reference_point = Vec3(0, 0, 0.2),
///                                          .velocity = Vec3(0, 0, -0.1),
///                                          .omega = VectorTimeFunction<3>::along(
///                                              Vec3::UnitZ(), TimeFunction::linear(0, 2.0))});
/// sim.add_group("lid", {}, lid.walls());               // its walls, for group conditions
/// \endcode
///
/// An obstacle is one triangle wall per triangle (in the mesh's order, at consecutive wall
/// indices), all with the reference point as pivot and the same velocity functions, each with
/// the obstacle's material or, with `materials`, its own (Parmec's per-triangle colours), and the
/// mesh's features (walls/mesh_features.hpp), so that every contact of a sphere with the mesh is
/// counted once: a face contact where the sphere is over a face (one triangle where it is over a
/// shared edge or vertex of a flat patch), an edge contact only in the wedge of a convex edge, a
/// vertex contact only in the cone of a convex vertex.
///
/// Motion: over a step [t, t + dt] the reference point moves by v dt and the obstacle turns by the
/// rotation vector w dt about it (v and w at t + dt/2; exact for constant velocities, second-order
/// accurate for varying ones). w is spatial (world axes). The triangles' corners are always the
/// body-frame corners turned by the obstacle's orientation and shifted to the reference point,
/// so the mesh stays rigid over any number of steps. Without velocity functions the obstacle is
/// fixed; conditions on a group of its walls (`prescribe_motion`) may move it later, as long as
/// every wall of the obstacle gets the same motion.

#include <grain/core/error.hpp>
#include <grain/core/time_function.hpp>
#include <grain/core/vector.hpp>
#include <grain/walls/mesh_features.hpp>
#include <grain/walls/walls.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numeric>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace grain {

/// Options of an obstacle.
struct ObstacleOptions {
  std::string name = "obstacle"; ///< used in error messages; wall k is named "<name>[k]"
  std::uint32_t material = 0;    ///< index returned by add_material (every triangle)
  /// Per-triangle materials (Parmec's list of OBSTACLE colours): empty, every triangle uses
  /// `material`; otherwise one index returned by add_material per triangle, in the mesh's
  /// order (triangle k, wall first_wall + k, gets materials[k]).
  std::vector<std::uint32_t> materials{};
  /// Reference point [m]: the point that moves with `velocity` and about which the obstacle
  /// turns with `omega`.
  Vec3 reference_point = Vec3::Zero();
  /// Velocity of the reference point [m/s] as a function of time; empty: none.
  std::optional<VectorTimeFunction<3>> velocity{};
  /// Angular velocity about the reference point [rad/s] (world axes) as a function of time;
  /// empty: none.
  std::optional<VectorTimeFunction<3>> omega{};
  /// Temperature [K] of every triangle (constant or a time function); empty = insulated.
  std::optional<TimeFunction> temperature{};
  /// Faces whose planes differ by at most this angle [rad] count as one plane (a flat patch):
  /// where several of them contain a sphere's projection, the one of lowest index reports.
  double flat_angle = 1e-6;
};

/// A handle to an obstacle of a simulation: its walls are first_wall ... first_wall + count - 1,
/// wall first_wall + k being triangle k of the mesh.
struct Obstacle {
  std::string name;
  std::uint32_t first_wall = 0;
  std::uint32_t count = 0;
  std::shared_ptr<const walls::MeshFeatures> features;

  /// Wall index of triangle k.
  std::uint32_t wall(std::size_t k) const { return first_wall + static_cast<std::uint32_t>(k); }
  /// Wall indices of all triangles (for add_group).
  std::vector<std::uint32_t> walls() const {
    std::vector<std::uint32_t> w(count);
    for (std::uint32_t k = 0; k < count; ++k)
      w[k] = first_wall + k;
    return w;
  }
  /// Current position of the reference point [m].
  template <class Sim>
  Vec3 reference_point(const Sim& sim) const {
    return triangle(sim).origin;
  }
  /// Current orientation: the rotation from the body frame (the mesh as given, about the
  /// reference point) to the world.
  template <class Sim>
  Eigen::Quaterniond orientation(const Sim& sim) const {
    return triangle(sim).orientation;
  }
  /// Current world position of mesh vertex v [m].
  template <class Sim>
  Vec3 vertex(const Sim& sim, std::uint32_t v) const {
    const auto& t = triangle(sim);
    return t.origin + t.orientation.toRotationMatrix() * features->vertex(v);
  }

private:
  template <class Sim>
  const walls::Triangle& triangle(const Sim& sim) const {
    return std::get<walls::Triangle>(sim.walls().at(first_wall).geometry);
  }
};

namespace walls {

/// A mesh from a list of triangles: corners with equal coordinates become one vertex (exact
/// comparison), in the order of first appearance.
inline TriangleMesh triangle_mesh(std::span<const Triangle> triangles) {
  TriangleMesh m;
  std::vector<std::pair<std::array<double, 3>, std::uint32_t>> seen;
  std::vector<std::array<double, 3>> corners;
  corners.reserve(3 * triangles.size());
  for (const auto& t : triangles)
    for (const Vec3* p : {&t.a, &t.b, &t.c})
      corners.push_back({p->x(), p->y(), p->z()});
  seen.reserve(corners.size());
  // a corner that is not finite stays a vertex of its own (not sorted: NaN does not order), and
  // the mesh's check rejects it with its coordinates
  for (std::uint32_t k = 0; k < corners.size(); ++k)
    if (std::isfinite(corners[k][0]) && std::isfinite(corners[k][1]) &&
        std::isfinite(corners[k][2]))
      seen.push_back({corners[k], k});
  std::stable_sort(seen.begin(), seen.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  // first appearance of each distinct point, then vertex numbers in that order
  std::vector<std::uint32_t> first(corners.size());
  std::iota(first.begin(), first.end(), std::uint32_t{0});
  for (std::size_t k = 0; k < seen.size(); ++k)
    first[seen[k].second] =
        (k > 0 && seen[k].first == seen[k - 1].first) ? first[seen[k - 1].second] : seen[k].second;
  std::vector<std::uint32_t> number(corners.size(), 0);
  for (std::uint32_t k = 0; k < corners.size(); ++k) {
    if (first[k] == k) {
      number[k] = static_cast<std::uint32_t>(m.vertices.size());
      m.vertices.push_back(Vec3(corners[k][0], corners[k][1], corners[k][2]));
    } else {
      number[k] = number[first[k]];
    }
  }
  for (std::uint32_t t = 0; t < triangles.size(); ++t)
    m.triangles.push_back({number[3 * t], number[3 * t + 1], number[3 * t + 2]});
  return m;
}

} // namespace walls

/// Adds an obstacle made of the triangles of `mesh` to a 3D simulation: one triangle wall per
/// triangle, moving rigidly with `options.velocity` and `options.omega` about
/// `options.reference_point`. Throws InputError (naming the obstacle, the value and the valid
/// range) for an empty mesh, a non-finite vertex, a vertex index out of range, a degenerate
/// triangle, a non-finite reference point, an unknown material, a `materials` list whose size is
/// neither 0 nor the number of triangles or that holds an unknown material, or a negative
/// temperature.
template <class Sim>
Obstacle add_obstacle(Sim& sim, const walls::TriangleMesh& mesh,
                      const ObstacleOptions& options = {}) {
  static_assert(Sim::dimension == 3,
                "grain::add_obstacle: obstacles are triangle meshes, for 3D simulations only");
  const std::string obj = "Obstacle '" + options.name + "'";
  // check everything before the first wall is added
  auto features =
      walls::MeshFeatures::build(mesh, options.reference_point, obj, options.flat_angle);
  const auto materials = sim.materials().size();
  detail::require(options.material < materials, obj, "material", options.material,
                  "[0, " + std::to_string(materials) + ") (indices returned by add_material)");
  const std::size_t nt = mesh.triangles.size();
  detail::require(options.materials.empty() || options.materials.size() == nt, obj,
                  "number of materials", options.materials.size(),
                  "0 (every triangle uses material) or " + std::to_string(nt) +
                      " (one per triangle)");
  for (std::size_t f = 0; f < options.materials.size(); ++f)
    detail::require(options.materials[f] < materials, obj,
                    ("triangle " + std::to_string(f) + " material").c_str(), options.materials[f],
                    "[0, " + std::to_string(materials) + ") (indices returned by add_material)");
  const double t = sim.time();
  if (options.temperature)
    detail::require_non_negative(obj, "temperature", *options.temperature, 0.0, "[0, inf) K");

  Obstacle ob;
  ob.name = options.name;
  ob.first_wall = static_cast<std::uint32_t>(sim.walls().size());
  ob.count = static_cast<std::uint32_t>(mesh.triangles.size());
  ob.features = features;
  for (std::uint32_t f = 0; f < ob.count; ++f) {
    const auto& v = mesh.triangles[f];
    walls::Triangle tri{mesh.vertices[v[0]], mesh.vertices[v[1]], mesh.vertices[v[2]]};
    tri.mesh = features;
    tri.face = f;
    tri.origin = options.reference_point;
    WallOptions<3> w;
    w.name = options.name + "[" + std::to_string(f) + "]";
    w.material = options.materials.empty() ? options.material : options.materials[f];
    w.has_pivot = true;
    w.pivot = options.reference_point;
    w.temperature = options.temperature;
    const auto index = sim.add_wall(tri, w);
    auto& wall = sim.walls()[index];
    if (options.velocity) wall.velocity_function = *options.velocity;
    if (options.omega) wall.omega_function = *options.omega;
    wall.update_motion(t);
  }
  return ob;
}

/// The same with the triangles given one by one (corners with equal coordinates are one vertex).
template <class Sim>
Obstacle add_obstacle(Sim& sim, std::span<const walls::Triangle> triangles,
                      const ObstacleOptions& options = {}) {
  return add_obstacle(sim, walls::triangle_mesh(triangles), options);
}
template <class Sim>
Obstacle add_obstacle(Sim& sim, const std::vector<walls::Triangle>& triangles,
                      const ObstacleOptions& options = {}) {
  return add_obstacle(sim, std::span<const walls::Triangle>(triangles), options);
}

} // namespace grain
