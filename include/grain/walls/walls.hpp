#pragma once
/// \file walls.hpp
/// Rigid walls: segments and circles (2D), infinite planes and triangles (3D).
///
/// A wall is a contact partner of infinite mass (and infinite radius where it is flat). It may
/// move with a prescribed translational velocity [m/s] and rotate with a prescribed angular
/// velocity [rad/s] about its pivot (default: segment midpoint, circle centre, plane point,
/// triangle centroid). A rotating circle does not change its geometry but drags particles with
/// its surface velocity (a rotating drum). Wall velocities are constant in time here; time
/// functions are added by the conditions layer.
///
/// A triangle may belong to an obstacle (see walls/obstacle.hpp): a triangle mesh that moves
/// rigidly. Such a triangle carries the obstacle's shared `MeshFeatures` and its pose (the
/// position of the reference point and the rotation from the body frame), moves with the pose
/// (its corners are the body-frame corners rotated and shifted, so the shape never drifts) and
/// reports only the contacts that are its own (see walls/mesh_features.hpp): each contact with
/// the mesh is counted once. `nearest` is the triangle's own nearest point, for the neighbour
/// search. A triangle without mesh (the default) is a lone triangle, touched at its face, edges
/// and corners.
///
/// Thermally a wall is insulated (the default: no heat crosses it) or held at a temperature [K]
/// given as a `TimeFunction` (a constant, a ramp, a table...). It has no thermal inertia: while
/// the function is inactive the wall keeps its last temperature. A conducting wall exchanges heat
/// through its material's conductivity.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <grain/core/error.hpp>
#include <grain/core/time_function.hpp>
#include <grain/core/vector.hpp>
#include <grain/walls/mesh_features.hpp>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <variant>

namespace grain {
namespace walls {

/// 2D line segment from `a` to `b`; particles touch it from either side and at its ends.
struct Segment {
  Vec2 a = Vec2::Zero(), b = Vec2::Zero();
};
/// 2D circle of centre `center` and radius `radius` [m]; a particle inside touches it from the
/// inside (a drum), a particle outside from the outside (a post).
struct Circle {
  Vec2 center = Vec2::Zero();
  double radius = 0.0;
};
/// 3D infinite plane through `point` whose unit `normal` points to the side where particles are.
struct Plane {
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();
};
/// 3D triangle with corners a, b, c; touched from either side, at edges and corners.
struct Triangle {
  Vec3 a = Vec3::Zero(), b = Vec3::UnitX(), c = Vec3::UnitY();
  /// Set for a triangle of an obstacle (by add_obstacle): the obstacle's mesh features, shared by
  /// its triangles, and this triangle's face index in them. Null: a lone triangle.
  std::shared_ptr<const MeshFeatures> mesh{};
  std::uint32_t face = 0;
  /// Pose of the obstacle (used with `mesh`): the current position of its reference point [m]
  /// and the rotation from the body frame to the world; a world point x is y = R^T (x - origin)
  /// in the body frame.
  Vec3 origin = Vec3::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
};

} // namespace walls

/// Options shared by all walls.
template <int D>
struct WallOptions {
  std::string name = "wall";
  std::uint32_t material = 0;            ///< index returned by add_material
  Vec<D> velocity = Vec<D>::Zero();      ///< translational velocity [m/s]
  Angular<D> omega = zero<Angular<D>>(); ///< angular velocity about the pivot [rad/s]
  bool has_pivot = false;                ///< if true, rotate about `pivot`
  Vec<D> pivot = Vec<D>::Zero();         ///< centre of rotation [m]
  /// Temperature [K] (constant or a time function); empty = thermally insulated.
  std::optional<TimeFunction> temperature{};
  /// Lifecycle (the first seed's wall activity): a wall takes part in contacts only while it is
  /// active and creation_time <= t < destruction_time [s]. Outside that interval it is absent:
  /// no contact, no heat exchange, no load; its contacts end (their histories are dropped) at the
  /// first step it is absent, and particles meet it afresh when it appears. It keeps its index
  /// (groups, conditions and output refer to it) and keeps moving with its velocities.
  bool active = true;
  double creation_time = -std::numeric_limits<double>::infinity();
  double destruction_time = std::numeric_limits<double>::infinity();
};

template <int D>
using WallGeometry = std::conditional_t<D == 2, std::variant<walls::Segment, walls::Circle>,
                                        std::variant<walls::Plane, walls::Triangle>>;

/// Where a particle centre x meets a wall: unit normal from the particle towards the wall,
/// distance from the centre to the wall surface, and the wall's radius of curvature at that point
/// (positive convex towards the particle, negative concave, infinite flat).
template <int D>
struct WallProximity {
  Vec<D> normal;
  double distance;
  double curvature_radius;
};

namespace detail {

inline Vec2 closest_on_segment(const Vec2& a, const Vec2& b, const Vec2& x) {
  const Vec2 ab = b - a;
  const double t = std::clamp((x - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return a + t * ab;
}

/// Closest point of triangle abc to x (Ericson, Real-Time Collision Detection, 5.1.5).
inline Vec3 closest_on_triangle(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + (d1 / (d1 - d3)) * ab;
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

/// Barycentric coordinates of the projection of p on the segment ab (clamped to it).
inline std::array<double, 2> barycentric(const std::array<Vec2, 2>& x, const Vec2& p) {
  const Vec2 e = x[1] - x[0];
  const double t = std::clamp((p - x[0]).dot(e) / e.squaredNorm(), 0.0, 1.0);
  return {1.0 - t, t};
}

/// Barycentric coordinates of the closest point of triangle abc to p.
inline std::array<double, 3> barycentric(const std::array<Vec3, 3>& x, const Vec3& p) {
  const Vec3 q = closest_on_triangle(x[0], x[1], x[2], p);
  const Vec3 e0 = x[1] - x[0], e1 = x[2] - x[0], d = q - x[0];
  const double d00 = e0.dot(e0), d01 = e0.dot(e1), d11 = e1.dot(e1);
  const double d20 = d.dot(e0), d21 = d.dot(e1);
  const double den = d00 * d11 - d01 * d01;
  double v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den;
  v = std::clamp(v, 0.0, 1.0);
  w = std::clamp(w, 0.0, 1.0 - v);
  return {1.0 - v - w, v, w};
}

} // namespace detail

/// A wall: its geometry, motion and material.
template <int D>
struct Wall {
  WallGeometry<D> geometry;
  WallOptions<D> options;
  Vec<D> pivot = Vec<D>::Zero();
  WallGeometry<D> snapshot; ///< geometry at the last neighbour-list rebuild
  /// Takes part in contacts now (kept by the simulation from `exists_at`).
  bool present = true;
  /// Removed for good (Simulation::remove_wall).
  bool removed = false;

  /// True if the wall takes part in contacts at time t [s] (see WallOptions::active).
  bool exists_at(double t) const noexcept {
    return !removed && options.active && t >= options.creation_time && t < options.destruction_time;
  }
  double temperature = std::numeric_limits<double>::quiet_NaN(); ///< current temperature [K]

  /// Velocity [m/s] and angular velocity [rad/s] as functions of time (fixed / prescribed by a
  /// condition); while set, they replace options.velocity / options.omega (0 while inactive).
  std::optional<VectorTimeFunction<D>> velocity_function{};
  std::optional<AngularTimeFunction<D>> omega_function{};

  /// Velocities of the corners (2D: a, b of a segment; 3D: a, b, c of a triangle) of a wall whose
  /// corners move independently (a multi-node facet, walls/facets.hpp) [m/s]: when set, the
  /// surface velocity at a point is their barycentric interpolation, and `options.velocity` and
  /// `options.omega` are not used.
  std::optional<std::array<Vec<D>, D>> node_velocity{};

  /// Sets the current velocities at time t [s] from the velocity functions, if any.
  void update_motion(double t) {
    if (velocity_function) options.velocity = (*velocity_function)(t);
    if (omega_function) options.omega = (*omega_function)(t);
  }

  /// True if heat crosses the wall (it has a temperature).
  bool conducts() const { return options.temperature.has_value(); }

  /// Sets the current temperature at time t [s] (kept while the function is inactive); throws
  /// InputError if the function gives a value below 0 K or not finite.
  void update_temperature(double t) {
    if (!options.temperature) return;
    const TimeFunction& f = *options.temperature;
    if (f.active(t) || std::isnan(temperature)) {
      const double T = f.value(t);
      if (!(std::isfinite(T) && T >= 0.0))
        detail::require(false, "Wall '" + options.name + "'",
                        ("temperature at t = " + detail::to_text(t) + " s").c_str(), T,
                        "[0, inf) K");
      temperature = T;
    }
  }

  static constexpr double inf = std::numeric_limits<double>::infinity();

  /// Normal, distance and curvature seen from a particle centre x. A triangle of an obstacle
  /// that does not report the contact (another triangle of the mesh does, or the nearest
  /// feature is one the mesh covers otherwise) gives an infinite distance.
  WallProximity<D> proximity(const Vec<D>& x) const {
    // the usual flat walls without the variant's dispatch
    if constexpr (D == 3) {
      if (const auto* plane = std::get_if<walls::Plane>(&geometry)) [[likely]]
        return proximity_of(*plane, x);
    } else {
      if (const auto* segment = std::get_if<walls::Segment>(&geometry)) [[likely]]
        return proximity_of(*segment, x);
    }
    return std::visit([&](const auto& g) { return proximity_of(g, x); }, geometry);
  }

  /// The nearest point of the wall's own geometry (for a triangle of an obstacle: of this
  /// triangle alone, whichever triangle reports the contact); the neighbour search and the cell
  /// diagrams use it. The same as proximity for every other wall.
  WallProximity<D> nearest(const Vec<D>& x) const {
    if constexpr (D == 3)
      if (const auto* t = std::get_if<walls::Triangle>(&geometry)) return nearest_on(*t, x);
    return proximity(x);
  }

  /// Velocity of the wall surface at point p [m/s].
  Vec<D> velocity_at(const Vec<D>& p) const {
    if (node_velocity) [[unlikely]]
      return interpolated_velocity(p);
    return options.velocity + cross(options.omega, Vec<D>(p - pivot));
  }

  bool moves() const {
    return options.velocity.squaredNorm() > 0 || squared_norm(options.omega) > 0;
  }

  /// Advances the geometry by dt with the prescribed velocities.
  void move(double dt) {
    if (!moves()) return;
    const Vec<D> shift = options.velocity * dt;
    const auto w = options.omega;
    auto tr = [&](const Vec<D>& p) -> Vec<D> {
      return Vec<D>(pivot + rotated(Vec<D>(p - pivot), w, dt) + shift);
    };
    std::visit(
        [&](auto& g) {
          using G = std::decay_t<decltype(g)>;
          if constexpr (std::is_same_v<G, walls::Segment>) {
            g.a = tr(g.a);
            g.b = tr(g.b);
          } else if constexpr (std::is_same_v<G, walls::Circle>) {
            g.center = tr(g.center);
          } else if constexpr (std::is_same_v<G, walls::Plane>) {
            g.point = tr(g.point);
            g.normal = rotated(g.normal, w, dt).normalized();
          } else if (g.mesh) {
            // the pose moves; the corners follow from it, so the mesh stays rigid
            g.origin = tr(g.origin);
            rotate(g.orientation, w, dt);
            const Eigen::Matrix3d R = g.orientation.toRotationMatrix();
            const auto& v = g.mesh->face_vertices(g.face);
            g.a = g.origin + R * g.mesh->vertex(v[0]);
            g.b = g.origin + R * g.mesh->vertex(v[1]);
            g.c = g.origin + R * g.mesh->vertex(v[2]);
          } else {
            g.a = tr(g.a);
            g.b = tr(g.b);
            g.c = tr(g.c);
          }
        },
        geometry);
    pivot += shift;
  }

  /// Upper bound of how far any point of the wall surface that lies within `reach` [m] of the
  /// pivot has moved since the last snapshot. For a plane, the distance from a point x changes
  /// by (x - p0).(n - n0) - (p - p0).n under a rigid motion (p0, n0 the point and normal at the
  /// snapshot), and |x - p0| <= reach + |p - pivot| (the pivot moves with the plane).
  double displacement_since_snapshot(double reach) const {
    return std::visit(
        [&](const auto& g) -> double {
          using G = std::decay_t<decltype(g)>;
          const auto& s = std::get<G>(snapshot);
          if constexpr (std::is_same_v<G, walls::Segment>)
            return std::max((g.a - s.a).norm(), (g.b - s.b).norm());
          else if constexpr (std::is_same_v<G, walls::Circle>)
            return (g.center - s.center).norm();
          else if constexpr (std::is_same_v<G, walls::Plane>)
            return (g.point - s.point).norm() +
                   (g.normal - s.normal).norm() * (reach + (g.point - pivot).norm());
          else
            return std::max({(g.a - s.a).norm(), (g.b - s.b).norm(), (g.c - s.c).norm()});
        },
        geometry);
  }

  void take_snapshot() { snapshot = geometry; }

  /// Checks the geometry; throws InputError naming the wall.
  void validate() const {
    const std::string obj = "Wall '" + options.name + "'";
    std::visit(
        [&](const auto& g) {
          using G = std::decay_t<decltype(g)>;
          if constexpr (std::is_same_v<G, walls::Segment>) {
            detail::require(all_finite(g.a) && all_finite(g.b), obj, "segment end points",
                            "(non-finite)", "finite coordinates");
            detail::require_positive(obj, "segment length", (g.b - g.a).norm());
          } else if constexpr (std::is_same_v<G, walls::Circle>) {
            detail::require(all_finite(g.center), obj, "circle centre", "(non-finite)",
                            "finite coordinates");
            detail::require_positive(obj, "circle radius", g.radius);
          } else if constexpr (std::is_same_v<G, walls::Plane>) {
            detail::require(all_finite(g.point), obj, "plane point", "(non-finite)",
                            "finite coordinates");
            detail::require(all_finite(g.normal) && std::abs(g.normal.norm() - 1.0) < 1e-9, obj,
                            "plane normal length", g.normal.norm(), "1 (a unit vector)");
          } else {
            detail::require(all_finite(g.a) && all_finite(g.b) && all_finite(g.c), obj,
                            "triangle corners", "(non-finite)", "finite coordinates");
            detail::require_positive(obj, "triangle area",
                                     0.5 * (g.b - g.a).cross(g.c - g.a).norm());
            if (g.mesh) {
              detail::require(g.face < g.mesh->face_count(), obj, "mesh face", g.face,
                              "[0, " + std::to_string(g.mesh->face_count()) + ")");
              detail::require(all_finite(g.origin), obj, "mesh origin", "(non-finite)",
                              "finite coordinates");
              detail::require(std::abs(g.orientation.norm() - 1.0) < 1e-9, obj,
                              "mesh orientation norm", g.orientation.norm(),
                              "1 (a unit quaternion)");
            }
          }
        },
        geometry);
    detail::require(all_finite(options.velocity), obj, "velocity", "(non-finite)", "finite");
    detail::require(all_finite(options.omega), obj, "omega", "(non-finite)", "finite");
    if (options.has_pivot)
      detail::require(all_finite(options.pivot), obj, "pivot", "(non-finite)",
                      "finite coordinates [m]");
    if (options.temperature)
      detail::require_non_negative(obj, "temperature", *options.temperature, 0.0, "[0, inf) K");
    detail::require(!std::isnan(options.creation_time) &&
                        options.creation_time < std::numeric_limits<double>::infinity(),
                    obj, "creation_time", options.creation_time, "[-inf, inf) s");
    if (!(options.destruction_time > options.creation_time))
      detail::require(false, obj, "destruction_time", options.destruction_time,
                      "(creation_time, inf] = (" + detail::to_text(options.creation_time) +
                          ", inf] s");
  }

  /// Default pivot of a geometry.
  static Vec<D> default_pivot(const WallGeometry<D>& geometry) {
    return std::visit(
        [](const auto& g) -> Vec<D> {
          using G = std::decay_t<decltype(g)>;
          if constexpr (std::is_same_v<G, walls::Segment>)
            return 0.5 * (g.a + g.b);
          else if constexpr (std::is_same_v<G, walls::Circle>)
            return g.center;
          else if constexpr (std::is_same_v<G, walls::Plane>)
            return g.point;
          else
            return (g.a + g.b + g.c) / 3.0;
        },
        geometry);
  }

private:
  /// Barycentric interpolation of node_velocity at the point of the segment / triangle closest
  /// to p.
  Vec<D> interpolated_velocity(const Vec<D>& p) const {
    const auto& u = *node_velocity;
    if constexpr (D == 2) {
      const auto* s = std::get_if<walls::Segment>(&geometry);
      if (!s) return options.velocity;
      const auto l = detail::barycentric(std::array<Vec2, 2>{s->a, s->b}, p);
      return l[0] * u[0] + l[1] * u[1];
    } else {
      const auto* t = std::get_if<walls::Triangle>(&geometry);
      if (!t) return options.velocity;
      const auto l = detail::barycentric(std::array<Vec3, 3>{t->a, t->b, t->c}, p);
      return l[0] * u[0] + l[1] * u[1] + l[2] * u[2];
    }
  }

  static WallProximity<2> proximity_of(const walls::Segment& s, const Vec2& x) {
    const Vec2 q = detail::closest_on_segment(s.a, s.b, x);
    Vec2 d = q - x;
    double dist = d.norm();
    if (dist > 0) return {d / dist, dist, inf};
    const Vec2 t = (s.b - s.a).normalized();
    return {Vec2(-t.y(), t.x()), 0.0, inf};
  }
  static WallProximity<2> proximity_of(const walls::Circle& c, const Vec2& x) {
    const Vec2 d = x - c.center;
    const double r = d.norm();
    const Vec2 u = r > 0 ? Vec2(d / r) : Vec2(Vec2::UnitX());
    if (r <= c.radius) return {u, c.radius - r, -c.radius}; // inside: concave wall
    return {-u, r - c.radius, c.radius};                    // outside: convex wall
  }
  static WallProximity<3> proximity_of(const walls::Plane& p, const Vec3& x) {
    return {-p.normal, (x - p.point).dot(p.normal), inf};
  }
  static WallProximity<3> proximity_of(const walls::Triangle& t, const Vec3& x) {
    if (!t.mesh) return nearest_on(t, x);
    // the mesh's tests run in the body frame, where all triangles of the obstacle share the data
    const Vec3 y = t.orientation.conjugate() * Vec3(x - t.origin);
    const walls::MeshContact c = t.mesh->contact(t.face, y);
    return {t.orientation * c.normal, c.distance, inf};
  }
  static WallProximity<3> nearest_on(const walls::Triangle& t, const Vec3& x) {
    const Vec3 q = detail::closest_on_triangle(t.a, t.b, t.c, x);
    const Vec3 d = q - x;
    const double dist = d.norm();
    if (dist > 0) return {d / dist, dist, inf};
    return {(t.b - t.a).cross(t.c - t.a).normalized(), 0.0, inf};
  }
};

} // namespace grain
