#pragma once
/// \file rigid_body.hpp
/// General 3D rigid bodies: mass, full inertia tensor, orientation, position, velocities, and a
/// rotation-correct explicit integrator with the gyroscopic term. A body has no shape and takes
/// part in no contact; forces and torques come from whatever is attached to it (springs, joints,
/// gravity, user loads).
///
/// Units (SI): mass kg, inertia kg m^2, length m, velocity m/s, angular velocity rad/s,
/// force N, torque N m, time s.
///
/// ## Frames
/// - *World frame*: positions, velocities, angular velocities (spatial omega), forces and torques
///   are world-frame vectors. Torques are about the centre of mass.
/// - *Reference frame* of a body: the frame in which its inertia tensor J_ref was given.
///   `rotation(b, i)` (Lambda) maps reference-frame vectors to world vectors; the world inertia
///   is Lambda J_ref Lambda^T. Local (material) coordinates X of a point are reference-frame
///   coordinates relative to the centre of mass: x = c + Lambda X (`to_world`, `to_local`). The
///   angular velocity in this frame (the body frame) is Omega = Lambda^T omega (`local_omega`).
/// - *Principal frame*: the eigenvectors of J_ref. The store integrates the principal frame's
///   orientation Q (`orientation`, a unit quaternion, principal -> world) and keeps the constant
///   principal -> reference rotation P (`axes`), so Lambda = Q P^T and J_world = Q diag(J) Q^T.
///
/// ## Integration
/// A splitting method, second-order accurate and time-reversible (symplectic for conservative
/// forces that depend on positions only): velocity Verlet for the translation and, for the
/// rotation, the splitting of Dullweber, Leimkuhler and McLachlan (1997):
///
///     kick(h/2):    v += h/2 F/m,            pi += h/2 Q^T T     (pi = body angular momentum)
///     drift(h):     x += h v,                free rotation of (Q, pi) over h
///     (forces and torques at the new configuration)
///     kick(h/2):    v += h/2 F/m,            pi += h/2 Q^T T
///
/// The free rotation (torque-free Euler equations dpi/dt = pi x Omega, Omega = J^-1 pi,
/// dQ/dt = Q [Omega]x, gyroscopic term included) is split by kinetic energy
/// T = sum_k pi_k^2 / (2 J_k) into the symmetric sequence of exact rotations about the principal
/// axes 1, 2, 3, 2, 1 with steps h/2, h/2, h, h/2, h/2. The rotation about axis k with step s
/// turns the body by theta = s pi_k / J_k (Q <- Q exp(theta [e_k]x)) and the body angular
/// momentum by -theta about e_k (pi <- exp(-theta [e_k]x) pi). Each sub-step keeps the spatial
/// angular momentum L = Q pi exactly, so a torque-free body conserves L to round-off and its
/// kinetic energy to O(h^2) without drift; a body spinning about a principal axis under a
/// constant torque about that axis gets omega = T t / J exactly, and a constant force gives
/// x = x0 + v0 t + F t^2 / (2 m) to round-off. The NO_SQUISH integrator of Miller et al. (2002)
/// is the same kind of splitting written with quaternion momenta.
///
/// ### Usage: forces between the stages
///
///     clear_forces(b); add_loads(b);          // forces at t = 0 (once)
///     for each step:
///       kick_drift(b, h);                     // v(t+h/2), x(t+h), Q(t+h)
///       clear_forces(b); add_loads(b);        // F(t+h), T(t+h) from positions/velocities
///       kick(b, h);                           // v(t+h), omega(t+h)
///
/// or `step(b, h, add_loads)`, which does the three lines of the loop body. Loads evaluated between
/// the stages see positions at t+h and velocities at t+h/2 (the usual velocity Verlet lag of a
/// dashpot).
///
/// ## References
/// - A. Dullweber, B. Leimkuhler, R. McLachlan, Symplectic splitting methods for rigid body
///   molecular dynamics, J. Chem. Phys. 107 (1997) 5840-5851.
/// - T. F. Miller III, M. Eleftheriou, P. Pattnaik, A. Ndirango, D. Newns, G. J. Martyna,
///   Symplectic quaternion scheme for biophysical molecular dynamics, J. Chem. Phys. 116 (2002)
///   8649-8659.
/// - H. Goldstein, C. Poole, J. Safko, Classical Mechanics, 3rd ed. (2002), ch. 4-5.

#include <grain/core/error.hpp>
#include <grain/core/vector.hpp>
#include <grain/particles/storage.hpp>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace grain::bodies {

/// Description of one rigid body, passed to `RigidBodies::add`. `radius` is the radius of the
/// sphere drawn at the centre in output (a body converted from a sphere keeps its radius); 0 = no
/// shape. It is finite and >= 0, and never used in the dynamics.
struct RigidBody {
  double mass = 1.0;                                      ///< [kg], finite, > 0
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Identity();  ///< J_ref about the centre [kg m^2]
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity(); ///< Lambda: reference -> world
  Vec3 position = Vec3::Zero();                           ///< centre of mass [m]
  Vec3 velocity = Vec3::Zero();                           ///< [m/s]
  Vec3 omega = Vec3::Zero();                              ///< spatial angular velocity [rad/s]
  double radius = 0.0;                                    ///< display radius [m], output only
  std::string name = "rigid body";                        ///< used in error messages
};

/// Inertia tensor from the six components (Ixx, Iyy, Izz, Ixy, Ixz, Iyz) [kg m^2], in the order
/// of Parmec's ANALYTICAL command. Ixy, Ixz, Iyz are the off-diagonal entries of the tensor
/// (J_xy = -int rho x y dV about the centre), not the product integrals themselves.
inline Eigen::Matrix3d inertia_tensor(double ixx, double iyy, double izz, double ixy, double ixz,
                                      double iyz) {
  Eigen::Matrix3d j;
  j << ixx, ixy, ixz, ixy, iyy, iyz, ixz, iyz, izz;
  return j;
}

/// A solid sphere of radius r [m] and density rho [kg/m^3] as a rigid body:
/// m = 4/3 pi r^3 rho, J = 2/5 m r^2 (isotropic), reference frame = world frame, display
/// radius r.
inline RigidBody sphere_body(double radius, double density, const Vec3& position,
                             const Vec3& velocity = Vec3::Zero(),
                             const Vec3& omega = Vec3::Zero()) {
  grain::detail::require_positive("sphere body", "radius", radius);
  grain::detail::require_positive("sphere body", "density", density);
  const double m = 4.0 / 3.0 * std::numbers::pi * radius * radius * radius * density;
  RigidBody b;
  b.mass = m;
  b.inertia = Eigen::Matrix3d::Identity() * (0.4 * m * radius * radius);
  b.position = position;
  b.velocity = velocity;
  b.omega = omega;
  b.radius = radius;
  b.name = "sphere body";
  return b;
}

/// Particle `i` of a 3D particle store (mass, isotropic inertia, orientation, position,
/// velocity, angular velocity) as a rigid body; the reference frame is the particle's frame and
/// the display radius the particle's radius.
inline RigidBody sphere_body(const ParticleArrays<3>& p, std::size_t i) {
  grain::detail::require(i < p.size(), "sphere body", "particle index", i,
                         "[0, " + std::to_string(p.size()) + ")");
  RigidBody b;
  b.mass = p.mass[i];
  b.inertia = Eigen::Matrix3d::Identity() * p.inertia[i];
  b.rotation = p.orientation[i].normalized().toRotationMatrix();
  b.position = p.position[i];
  b.velocity = p.velocity[i];
  b.omega = p.omega[i];
  b.radius = p.radius[i];
  b.name = "sphere body (particle " + std::to_string(i) + ")";
  return b;
}

namespace detail {

inline std::string matrix_text(const Eigen::Matrix3d& m) {
  std::ostringstream s;
  s.precision(10);
  s << "[" << m(0, 0) << ", " << m(0, 1) << ", " << m(0, 2) << "; " << m(1, 0) << ", " << m(1, 1)
    << ", " << m(1, 2) << "; " << m(2, 0) << ", " << m(2, 1) << ", " << m(2, 2) << "]";
  return s.str();
}

/// Principal moments (ascending) and a proper rotation P (det +1) whose columns are the
/// principal axes: J = P diag(moments) P^T. Validates J: finite, symmetric to 1e-12 relative,
/// positive definite.
struct Principal {
  Vec3 moments;
  Eigen::Matrix3d axes;
};
inline Principal principal(const Eigen::Matrix3d& j, const std::string& object) {
  grain::detail::require(j.allFinite(), object, "inertia", matrix_text(j),
                         "finite entries [kg m^2]");
  const double scale = j.cwiseAbs().maxCoeff();
  grain::detail::require((j - j.transpose()).cwiseAbs().maxCoeff() <= 1e-12 * scale, object,
                         "inertia", matrix_text(j),
                         "a symmetric matrix (|J - J^T| <= 1e-12 max|J|) [kg m^2]");
  const Eigen::Matrix3d s = 0.5 * (j + j.transpose());
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(s);
  const Vec3 ev = eig.eigenvalues();
  grain::detail::require(ev.minCoeff() > 1e-14 * ev.maxCoeff() && ev.minCoeff() > 0.0, object,
                         "inertia eigenvalues", ev.transpose(),
                         "all > 0 (a positive definite tensor) [kg m^2]");
  // A physical inertia tensor satisfies the triangle inequalities J_a + J_b >= J_c.
  grain::detail::require(ev(0) + ev(1) >= ev(2) * (1.0 - 1e-12), object, "inertia eigenvalues",
                         ev.transpose(), "J1 + J2 >= J3 (a physical mass distribution) [kg m^2]");
  Eigen::Matrix3d p = eig.eigenvectors();
  if (p.determinant() < 0.0) p.col(2) = -p.col(2);
  return {ev, p};
}

/// Orthonormal check of a user rotation matrix (|R^T R - 1| <= 1e-9, det R > 0).
inline void require_rotation(const Eigen::Matrix3d& r, const std::string& object) {
  const bool ok = r.allFinite() &&
                  (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() <= 1e-9 &&
                  r.determinant() > 0.0;
  grain::detail::require(ok, object, "rotation", matrix_text(r),
                         "a proper rotation matrix (orthonormal to 1e-9, det = +1)");
}

/// Exact torque-free rotation about principal axis k over a sub-step s.
inline void rotate_about_axis(Eigen::Quaterniond& q, Vec3& pi, const Vec3& inv_j, int k, double s) {
  const double theta = s * pi(k) * inv_j(k);
  if (theta == 0.0) return;
  const double c = std::cos(theta), sn = std::sin(theta);
  const int a = (k + 1) % 3, b = (k + 2) % 3;
  // pi <- exp(-theta [e_k]x) pi: rotate the (a, b) components by -theta.
  const double pa = pi(a), pb = pi(b);
  pi(a) = c * pa + sn * pb;
  pi(b) = -sn * pa + c * pb;
  // Q <- Q exp(theta [e_k]x)
  const double ch = std::cos(0.5 * theta), sh = std::sin(0.5 * theta);
  Eigen::Quaterniond r(ch, 0.0, 0.0, 0.0);
  r.vec()(k) = sh;
  q = q * r;
}

} // namespace detail

/// Rigid bodies as a structure of arrays; a body is addressed by the index `add` returns.
struct RigidBodies {
  std::vector<double> mass;                    ///< [kg]
  std::vector<double> inv_mass;                ///< [1/kg]
  std::vector<Vec3> inertia;                   ///< principal moments J1 <= J2 <= J3 [kg m^2]
  std::vector<Vec3> inv_inertia;               ///< 1/J_k [1/(kg m^2)]
  std::vector<Eigen::Quaterniond> orientation; ///< Q: principal frame -> world
  std::vector<Eigen::Quaterniond> axes;        ///< P: principal -> reference frame (constant)
  std::vector<Vec3> position;                  ///< centre of mass [m]
  std::vector<Vec3> velocity;                  ///< [m/s]
  std::vector<Vec3> omega;                     ///< spatial angular velocity [rad/s]
  std::vector<Vec3> force;                     ///< world-frame force accumulator [N]
  std::vector<Vec3> torque;                    ///< world torque about the centre [N m]
  std::vector<double> radius;                  ///< display radius (output only; 0: none) [m]

  std::size_t size() const { return mass.size(); }

  /// Validates and appends a body; returns its index. Throws InputError for a mass that is not
  /// finite and > 0, an inertia tensor that is not finite, symmetric and positive definite (or
  /// violates J1 + J2 >= J3), a rotation that is not proper orthonormal, a non-finite
  /// position, velocity or angular velocity, or a display radius that is not finite and >= 0.
  std::size_t add(const RigidBody& b) {
    grain::detail::require_positive(b.name, "mass", b.mass);
    const detail::Principal pr = detail::principal(b.inertia, b.name);
    detail::require_rotation(b.rotation, b.name);
    grain::detail::require(b.position.allFinite(), b.name, "position", b.position.transpose(),
                           "finite [m]");
    grain::detail::require(b.velocity.allFinite(), b.name, "velocity", b.velocity.transpose(),
                           "finite [m/s]");
    grain::detail::require(b.omega.allFinite(), b.name, "omega", b.omega.transpose(),
                           "finite [rad/s]");
    grain::detail::require(std::isfinite(b.radius) && b.radius >= 0.0, b.name, "radius", b.radius,
                           "[0, inf) m (display radius; 0 = no shape)");
    mass.push_back(b.mass);
    inv_mass.push_back(1.0 / b.mass);
    inertia.push_back(pr.moments);
    inv_inertia.push_back(pr.moments.cwiseInverse());
    orientation.push_back(Eigen::Quaterniond(b.rotation * pr.axes).normalized());
    axes.push_back(Eigen::Quaterniond(pr.axes).normalized());
    position.push_back(b.position);
    velocity.push_back(b.velocity);
    omega.push_back(b.omega);
    force.push_back(Vec3::Zero());
    torque.push_back(Vec3::Zero());
    radius.push_back(b.radius);
    return size() - 1;
  }
};

/// Lambda: the body's reference frame -> world rotation, Q P^T.
inline Eigen::Matrix3d rotation(const RigidBodies& b, std::size_t i) {
  return (b.orientation[i] * b.axes[i].conjugate()).toRotationMatrix();
}

/// World inertia tensor about the centre, Q diag(J) Q^T [kg m^2].
inline Eigen::Matrix3d world_inertia(const RigidBodies& b, std::size_t i) {
  const Eigen::Matrix3d q = b.orientation[i].toRotationMatrix();
  return q * b.inertia[i].asDiagonal() * q.transpose();
}

/// Inverse world inertia tensor, Q diag(1/J) Q^T [1/(kg m^2)].
inline Eigen::Matrix3d inverse_world_inertia(const RigidBodies& b, std::size_t i) {
  const Eigen::Matrix3d q = b.orientation[i].toRotationMatrix();
  return q * b.inv_inertia[i].asDiagonal() * q.transpose();
}

/// Spatial angular momentum about the centre, L = J_world omega [kg m^2/s].
inline Vec3 angular_momentum(const RigidBodies& b, std::size_t i) {
  return b.orientation[i] *
         b.inertia[i].cwiseProduct(b.orientation[i].conjugate() * b.omega[i]).eval();
}

/// Kinetic energy 1/2 m v.v + 1/2 omega.J_world omega [J].
inline double kinetic_energy(const RigidBodies& b, std::size_t i) {
  const Vec3 w = b.orientation[i].conjugate() * b.omega[i];
  return 0.5 * b.mass[i] * b.velocity[i].squaredNorm() + 0.5 * w.dot(b.inertia[i].cwiseProduct(w));
}

/// World position of local (reference-frame, centre-relative) coordinates X: c + Lambda X [m].
inline Vec3 to_world(const RigidBodies& b, std::size_t i, const Vec3& local) {
  return b.position[i] + b.orientation[i] * (b.axes[i].conjugate() * local);
}

/// Local coordinates of a world point: Lambda^T (x - c) [m].
inline Vec3 to_local(const RigidBodies& b, std::size_t i, const Vec3& world) {
  return b.axes[i] * (b.orientation[i].conjugate() * (world - b.position[i]));
}

/// Angular velocity in the body's own frame [rad/s]: Omega = Lambda^T omega, the components of
/// the spatial angular velocity omega along the axes of the body's reference frame (the frame of
/// its inertia tensor J_ref and of its local coordinates; Parmec's referential angular velocity).
/// omega = Lambda Omega; the time derivative of the orientation is dLambda/dt = Lambda [Omega]x.
/// For the principal axes use Q^T omega = P^T Omega (`orientation`, `axes`).
inline Vec3 local_omega(const RigidBodies& b, std::size_t i) {
  return b.axes[i] * (b.orientation[i].conjugate() * b.omega[i]);
}

/// The same for particle `i` of a 3D particle store [rad/s]: R^T omega, R the particle's
/// orientation (`ParticleArrays<3>::orientation`, body axes -> world; for a clump member, the
/// clump's reference frame).
inline Vec3 local_omega(const ParticleArrays<3>& p, std::size_t i) {
  return p.orientation[i].normalized().conjugate() * p.omega[i];
}

/// Velocity of the material point now at world position x: v + omega x (x - c) [m/s].
inline Vec3 point_velocity(const RigidBodies& b, std::size_t i, const Vec3& world) {
  return b.velocity[i] + b.omega[i].cross(world - b.position[i]);
}

/// Adds a world force f [N] acting at world point x: F += f, T += (x - c) x f.
inline void apply_force(RigidBodies& b, std::size_t i, const Vec3& f, const Vec3& world) {
  b.force[i] += f;
  b.torque[i] += (world - b.position[i]).cross(f);
}

/// Sets every force and torque accumulator to zero.
inline void clear_forces(RigidBodies& b) {
  for (std::size_t i = 0; i < b.size(); ++i) {
    b.force[i].setZero();
    b.torque[i].setZero();
  }
}

/// First stage of a step of length h [s]: half kick of the velocities with the current forces
/// and torques, then drift of the positions over h and exact free rotation (1-2-3-2-1 splitting)
/// of the orientations over h. After it, positions and orientations are at t + h, velocities
/// and angular velocities at t + h/2.
inline void kick_drift(RigidBodies& b, double h) {
  const double hh = 0.5 * h;
  for (std::size_t i = 0; i < b.size(); ++i) {
    b.velocity[i] += hh * b.inv_mass[i] * b.force[i];
    b.position[i] += h * b.velocity[i];
    Eigen::Quaterniond q = b.orientation[i];
    const Vec3& j = b.inertia[i];
    const Vec3& ij = b.inv_inertia[i];
    // body angular momentum after the half kick
    Vec3 pi = j.cwiseProduct(q.conjugate() * b.omega[i]) + hh * (q.conjugate() * b.torque[i]);
    detail::rotate_about_axis(q, pi, ij, 0, hh);
    detail::rotate_about_axis(q, pi, ij, 1, hh);
    detail::rotate_about_axis(q, pi, ij, 2, h);
    detail::rotate_about_axis(q, pi, ij, 1, hh);
    detail::rotate_about_axis(q, pi, ij, 0, hh);
    q.normalize();
    b.orientation[i] = q;
    b.omega[i] = q * ij.cwiseProduct(pi).eval();
  }
}

/// Second stage of a step of length h [s]: half kick with the forces and torques evaluated at
/// the new configuration, v += h/2 F/m, omega += h/2 J_world^-1 T.
inline void kick(RigidBodies& b, double h) {
  const double hh = 0.5 * h;
  for (std::size_t i = 0; i < b.size(); ++i) {
    b.velocity[i] += hh * b.inv_mass[i] * b.force[i];
    const Eigen::Quaterniond& q = b.orientation[i];
    b.omega[i] += q * (hh * b.inv_inertia[i].cwiseProduct(q.conjugate() * b.torque[i])).eval();
  }
}

/// One full step: `kick_drift(b, h)`, `clear_forces(b)`, `loads(b)` (adds forces and torques
/// of the new configuration), `kick(b, h)`. The accumulators must hold the forces of the current
/// configuration on entry (call `clear_forces` and `loads` once before the first step).
template <class Loads>
void step(RigidBodies& b, double h, Loads&& loads) {
  kick_drift(b, h);
  clear_forces(b);
  loads(b);
  kick(b, h);
}

} // namespace grain::bodies
