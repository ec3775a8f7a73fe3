#pragma once
/// \file clumps.hpp
/// Clumps: rigid aggregates of overlapping spheres (3D) or disks (2D), mixed with single
/// particles in one simulation, as a library stage (`grain::Clumps<D>`, see docs/clumps.md).
///
/// A clump is a *node* (the rigid body that carries mass and is integrated) and its *members*
/// (particles of the simulation that have a shape and collide). The members are ordinary
/// particles that forces do not move (`fixed`); the stage owns their motion:
///
/// - mass M = rho V and inertia J = rho int (|r|^2 I - r r^T) dV of the union of the members
///   (overlaps counted once; union_mass.hpp), rho the density of the clump's material; a plain
///   disk (2D) has area x thickness, a sphere-mass disk the moments of the sphere union;
/// - after the forces (`after_forces`): F = sum f_i, T = sum ((x_i - X) x f_i + t_i) over the
///   members, then the clump's second half kick (velocity Verlet; in 3D the rotation splitting of
///   Dullweber, Leimkuhler and McLachlan of bodies/rigid_body.hpp, gyroscopic term included; in
///   2D a scalar angle), and the members take the clump's velocities, v_i = V + w x (x_i - X),
///   w_i = w;
/// - before the neighbour search (`before_search`): half kick with the forces of the last
///   step, drift and free rotation of the clump; the members are placed rigidly, x_i = X + R s_i
///   (s_i the member's offset in the clump's reference frame), with the velocities the forces of
///   the step will see (the half-step velocities plus half a kick, as velocity Verlet predicts
///   them for single particles).
///
/// Each member's mass is its share of M in proportion to its own volume (they sum to M, so that
/// gravity adds up to the clump's weight, which acts at the centroid: the torque of the members'
/// weights about it is taken out); members have zero moment of
/// inertia, so `Simulation::kinetic_energy()` counts them as point masses; `Clumps::
/// kinetic_energy()` is the clump's exact value. Global damping acts on every member.
///
/// Units: SI (m, kg, s, rad).

#include <grain/bodies/rigid_body.hpp>
#include <grain/clumps/union_mass.hpp>
#include <grain/core/error.hpp>
#include <grain/core/stages.hpp>
#include <grain/core/vector.hpp>
#include <grain/simulation.hpp>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace grain {

/// Per-particle field of rigid aggregates (the clump stage): the clump and member index of a
/// particle, -1 for a single particle.
struct ClumpMember {
  std::int32_t clump = -1;
  std::int32_t member = -1;
};
/// Clump members have an inverse mass of 0 but move with their clump under their contact
/// forces; two members of the same clump never act on each other, so their pair is never in the
/// neighbour list.
template <>
struct field_traits<ClumpMember> {
  static bool driven(const ClumpMember& f) { return f.clump >= 0; }
  static bool excluded(const ClumpMember& a, const ClumpMember& b) {
    return a.clump >= 0 && a.clump == b.clump;
  }
};

/// The shape of a clump in its reference frame: member centres (relative to the centroid) and
/// radii, and the moments of their union per unit density. Make it once with `clump_shape` and
/// place it as many times as needed.
template <int D>
struct ClumpShape {
  std::vector<Vec<D>> offsets; ///< member centres relative to the centroid [m]
  std::vector<double> radii;   ///< [m]
  UnionMoments<D> moments;     ///< volume (area), centroid (zero), inertia per unit density
  std::vector<double> share;   ///< each member's volume over the sum of the members' volumes
};

/// The shape of a clump whose members have these centres and radii (any origin) [m]. `Shape` is
/// the simulation's particle shape (Sphere, or Disk: plain disks use the union's area times the
/// thickness, sphere-mass disks the union of spheres in the plane).
template <class Shape>
ClumpShape<Shape::dimension> clump_shape(const std::vector<Vec<Shape::dimension>>& centres,
                                         const std::vector<double>& radii, const Shape& shape,
                                         const std::string& name = "clump") {
  constexpr int D = Shape::dimension;
  ClumpShape<D> s;
  bool spheres = D == 3;
  if constexpr (D == 2) spheres = shape.sphere_mass;
  if constexpr (D == 3) {
    s.moments = union_moments(centres, radii, name);
  } else if (spheres) {
    std::vector<Vec3> c3;
    for (const auto& c : centres)
      c3.emplace_back(c.x(), c.y(), 0.0);
    const auto u = union_moments(c3, radii, name);
    s.moments.measure = u.measure;
    s.moments.centroid = Vec2(u.centroid.x(), u.centroid.y());
    s.moments.inertia = u.inertia(2, 2);
  } else {
    s.moments = union_moments(centres, radii, name);
    s.moments.measure *= shape.thickness;
    s.moments.inertia *= shape.thickness;
  }
  double total = 0.0;
  for (double r : radii)
    total += shape.volume(r);
  for (std::size_t k = 0; k < centres.size(); ++k) {
    s.offsets.push_back(centres[k] - s.moments.centroid);
    s.radii.push_back(radii[k]);
    s.share.push_back(shape.volume(radii[k]) / total);
  }
  s.moments.centroid.setZero();
  return s;
}

/// Where and how a clump starts.
template <int D>
struct ClumpPlacement {
  Vec<D> position = Vec<D>::Zero(); ///< centroid [m]
  /// Rotation of the reference frame (3D: a rotation matrix, reference -> world; 2D: an angle
  /// [rad]).
  std::conditional_t<D == 3, Eigen::Matrix3d, double> rotation = [] {
    if constexpr (D == 3)
      return Eigen::Matrix3d(Eigen::Matrix3d::Identity());
    else
      return 0.0;
  }();
  Vec<D> velocity = Vec<D>::Zero();      ///< [m/s]
  Angular<D> omega = zero<Angular<D>>(); ///< [rad/s]
  std::uint32_t material = 0;            ///< index returned by add_material
  std::string name = "clump";
};

/// The clump stage: add it as `grain::stages<grain::Clumps<D>>` and create clumps with `add`.
template <int D>
class Clumps {
public:
  using fields = grain::fields<ClumpMember>;
  using V = Vec<D>;
  using A = Angular<D>;

  /// Adds a clump of this shape (its members become particles of `sim`); returns its index.
  /// Call before the run starts or between runs.
  template <class Sim>
  std::size_t add(Sim& sim, const ClumpShape<D>& shape, const ClumpPlacement<D>& at) {
    const std::string obj = "Clump '" + at.name + "'";
    detail::require(at.material < sim.materials().size(), obj, "material", at.material,
                    "[0, " + std::to_string(sim.materials().size()) +
                        ") (indices of add_material)");
    detail::require(shape.offsets.size() > 0 && shape.offsets.size() == shape.radii.size(), obj,
                    "members", shape.offsets.size(),
                    "at least one (make the shape with clump_shape)");
    detail::require(shape.share.size() == shape.offsets.size(), obj, "shares", shape.share.size(),
                    std::to_string(shape.offsets.size()) +
                        " (one per member; make the shape with clump_shape)");
    double shares = 0.0;
    bool valid = true;
    for (const double w : shape.share) {
      valid = valid && std::isfinite(w) && w >= 0.0;
      shares += w;
    }
    detail::require(valid && std::abs(shares - 1.0) <= 1e-9, obj, "sum of the shares", shares,
                    "1 within 1e-9, each share finite and >= 0 (make the shape with clump_shape)");
    const double rho = sim.materials()[at.material].density;
    const double mass = rho * shape.moments.measure;
    detail::require_positive(obj, "mass", mass);
    if constexpr (D == 2)
      detail::require_positive(obj, "moment of inertia", rho * shape.moments.inertia);
    const std::size_t c = size();
    if constexpr (D == 3) {
      bodies::RigidBody b;
      b.mass = mass;
      b.inertia = rho * shape.moments.inertia;
      b.rotation = at.rotation;
      b.position = at.position;
      b.velocity = at.velocity;
      b.omega = at.omega;
      b.name = obj;
      body_.add(b);
    } else {
      detail::require(std::isfinite(at.rotation), obj, "rotation", at.rotation, "finite [rad]");
      detail::require(at.position.allFinite() && at.velocity.allFinite() && std::isfinite(at.omega),
                      obj, "position, velocity and omega", "(non-finite)", "finite values");
      plane_.mass.push_back(mass);
      plane_.inertia.push_back(rho * shape.moments.inertia);
      plane_.angle.push_back(at.rotation);
      plane_.position.push_back(at.position);
      plane_.velocity.push_back(at.velocity);
      plane_.omega.push_back(at.omega);
      plane_.force.push_back(V::Zero());
      plane_.torque.push_back(0.0);
    }
    shapes_.push_back(shape);
    names_.push_back(at.name);
    std::vector<std::int64_t> ids;
    for (std::size_t k = 0; k < shape.offsets.size(); ++k) {
      const V x = world(c, shape.offsets[k]);
      ParticleSpec<D> spec;
      spec.position = x;
      spec.radius = shape.radii[k];
      spec.material = at.material;
      spec.velocity = point_velocity(c, x);
      spec.omega = omega(c);
      spec.fixed = true;
      const auto id = sim.add_particle(spec);
      ids.push_back(id);
      auto& p = sim.particles();
      // a member is appended at the end (no search over the particles: adding n clumps is O(n))
      const std::size_t i = !p.id.empty() && p.id.back() == id ? p.id.size() - 1 : sim.index_of(id);
      p.mass[i] = mass * shape.share[k];
      p.inertia[i] = 0.0;
      auto& f = sim.template field<ClumpMember>();
      f[i].clump = static_cast<std::int32_t>(c);
      f[i].member = static_cast<std::int32_t>(k);
    }
    ids_.push_back(std::move(ids));
    return c;
  }

  std::size_t size() const { return shapes_.size(); }
  const ClumpShape<D>& shape(std::size_t c) const { return shapes_[c]; }
  /// Ids of the clump's member particles (in member order).
  const std::vector<std::int64_t>& member_ids(std::size_t c) const { return ids_[c]; }
  double mass(std::size_t c) const {
    if constexpr (D == 3)
      return body_.mass[c];
    else
      return plane_.mass[c];
  }
  /// 3D: the world inertia tensor about the centroid; 2D: the moment of inertia [kg m^2].
  auto inertia(std::size_t c) const {
    if constexpr (D == 3)
      return Eigen::Matrix3d(bodies::world_inertia(body_, c));
    else
      return plane_.inertia[c];
  }
  const V& position(std::size_t c) const {
    if constexpr (D == 3)
      return body_.position[c];
    else
      return plane_.position[c];
  }
  const V& velocity(std::size_t c) const {
    if constexpr (D == 3)
      return body_.velocity[c];
    else
      return plane_.velocity[c];
  }
  const A& omega(std::size_t c) const {
    if constexpr (D == 3)
      return body_.omega[c];
    else
      return plane_.omega[c];
  }
  /// World position of a point given in the clump's reference frame (relative to the centroid).
  V world(std::size_t c, const V& offset) const {
    if constexpr (D == 3) {
      return bodies::to_world(body_, c, offset);
    } else {
      const double a = plane_.angle[c];
      return plane_.position[c] + Vec2(std::cos(a) * offset.x() - std::sin(a) * offset.y(),
                                       std::sin(a) * offset.x() + std::cos(a) * offset.y());
    }
  }
  /// Velocity of the clump's material point at world position x [m/s].
  V point_velocity(std::size_t c, const V& x) const {
    return velocity(c) + cross(omega(c), V(x - position(c)));
  }
  /// Linear momentum M V [kg m/s].
  V momentum(std::size_t c) const { return mass(c) * velocity(c); }
  /// Angular momentum about the centroid [kg m^2/s].
  A spin(std::size_t c) const {
    if constexpr (D == 3)
      return bodies::angular_momentum(body_, c);
    else
      return plane_.inertia[c] * plane_.omega[c];
  }
  /// Kinetic energy of all clumps [J].
  double kinetic_energy() const {
    double e = 0.0;
    for (std::size_t c = 0; c < size(); ++c) {
      if constexpr (D == 3)
        e += bodies::kinetic_energy(body_, c);
      else
        e += 0.5 * plane_.mass[c] * plane_.velocity[c].squaredNorm() +
             0.5 * plane_.inertia[c] * plane_.omega[c] * plane_.omega[c];
    }
    return e;
  }
  /// Force and torque (about the centroid) of the last force evaluation [N], [N m].
  const V& force(std::size_t c) const {
    if constexpr (D == 3)
      return body_.force[c];
    else
      return plane_.force[c];
  }
  const A& torque(std::size_t c) const {
    if constexpr (D == 3)
      return body_.torque[c];
    else
      return plane_.torque[c];
  }

  // ------------------------------------------------------------------ hooks
  /// Half kick, drift and rotation of the clumps; members placed rigidly.
  template <class Sim>
  void before_search(Sim& sim) {
    static_assert(Sim::integrator_type::drift_before_forces,
                  "grain::Clumps: clumps are integrated with velocity Verlet; use "
                  "integrate::VelocityVerlet (the default) as the simulation's integrator");
    in_step_ = true; // a step that moves (not the initial evaluation, not a thermal analysis)
    const double h = sim.time_step();
    if constexpr (D == 3) {
      bodies::kick_drift(body_, h);
    } else {
      for (std::size_t c = 0; c < size(); ++c) {
        plane_.velocity[c] += (0.5 * h / plane_.mass[c]) * plane_.force[c];
        plane_.omega[c] += 0.5 * h / plane_.inertia[c] * plane_.torque[c];
        plane_.position[c] += h * plane_.velocity[c];
        plane_.angle[c] += h * plane_.omega[c];
      }
    }
    // velocities the forces will see: half-step velocities plus half a kick
    auto& v = predicted_v_;
    auto& w = predicted_w_;
    v.resize(size());
    w.resize(size());
    for (std::size_t c = 0; c < size(); ++c) {
      v[c] = velocity(c) + (0.5 * h / mass(c)) * force(c);
      if constexpr (D == 3)
        w[c] = omega(c) + 0.5 * h * (bodies::inverse_world_inertia(body_, c) * torque(c));
      else
        w[c] = omega(c) + 0.5 * h / plane_.inertia[c] * torque(c);
    }
    auto& p = sim.particles();
    const auto& f = sim.template field<ClumpMember>();
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (f[i].clump < 0) continue;
      const auto c = static_cast<std::size_t>(f[i].clump);
      const auto k = static_cast<std::size_t>(f[i].member);
      p.position[i] = world(c, shapes_[c].offsets[k]);
      p.velocity[i] = v[c] + cross(w[c], V(p.position[i] - position(c)));
      p.omega[i] = w[c];
      set_orientation(p, i, c);
    }
  }

  /// Sums the members' forces onto the clumps, second half kick, member velocities.
  template <class Sim>
  void after_forces(Sim& sim) {
    auto& p = sim.particles();
    const auto& f = sim.template field<ClumpMember>();
    for (std::size_t c = 0; c < size(); ++c) {
      force_ref(c) = V::Zero();
      torque_ref(c) = zero<A>();
    }
    // gravity acts at the centroid: the members' weights (at their own centres) make no torque
    const V g = sim.gravity();
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (f[i].clump < 0) continue;
      const auto c = static_cast<std::size_t>(f[i].clump);
      force_ref(c) += p.force[i];
      torque_ref(c) +=
          cross(V(p.position[i] - position(c)), V(p.force[i] - p.mass[i] * g)) + p.torque[i];
    }
    if (in_step_) {
      const double h = sim.time_step();
      if constexpr (D == 3) {
        bodies::kick(body_, h);
      } else {
        for (std::size_t c = 0; c < size(); ++c) {
          plane_.velocity[c] += (0.5 * h / plane_.mass[c]) * plane_.force[c];
          plane_.omega[c] += 0.5 * h / plane_.inertia[c] * plane_.torque[c];
        }
      }
    }
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (f[i].clump < 0) continue;
      const auto c = static_cast<std::size_t>(f[i].clump);
      p.velocity[i] = point_velocity(c, p.position[i]);
      p.omega[i] = omega(c);
    }
  }

  template <class Sim>
  void end_of_step(Sim&) {
    in_step_ = false;
  }

  /// The clumps' state in a checkpoint (the program makes the same clumps again before loading).
  template <class Archive>
  void serialize(Archive& ar) {
    std::uint64_t n = size();
    ar(n);
    if (n != size())
      throw InputError("checkpoint: clumps = " + std::to_string(n) +
                       " is invalid; valid: " + std::to_string(size()) +
                       " (the clumps this program adds, in the same order)");
    if constexpr (D == 3)
      ar(body_.position, body_.velocity, body_.omega, body_.orientation, body_.force, body_.torque);
    else
      ar(plane_.position, plane_.velocity, plane_.omega, plane_.angle, plane_.force, plane_.torque);
  }

private:
  V& force_ref(std::size_t c) {
    if constexpr (D == 3)
      return body_.force[c];
    else
      return plane_.force[c];
  }
  A& torque_ref(std::size_t c) {
    if constexpr (D == 3)
      return body_.torque[c];
    else
      return plane_.torque[c];
  }
  template <class P>
  void set_orientation(P& p, std::size_t i, std::size_t c) const {
    if constexpr (D == 3)
      p.orientation[i] = body_.orientation[c] * body_.axes[c].conjugate();
    else
      p.orientation[i] = plane_.angle[c];
  }

  /// 2D clumps: centroid, angle and their rates.
  struct Planar {
    std::vector<double> mass, inertia, angle, omega, torque;
    std::vector<Vec2> position, velocity, force;
  };
  bodies::RigidBodies body_;
  Planar plane_;
  std::vector<ClumpShape<D>> shapes_;
  std::vector<std::string> names_;
  std::vector<std::vector<std::int64_t>> ids_;
  std::vector<V> predicted_v_; ///< clump velocities the forces of the step see (work space)
  std::vector<A> predicted_w_;
  bool in_step_ = false;
};

} // namespace grain
