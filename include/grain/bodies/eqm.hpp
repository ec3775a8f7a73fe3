#pragma once
/// \file eqm.hpp
/// Equivalent point mass (EQM) of a point on a rigid body and critical time-step estimates for
/// springs attached to rigid bodies.
///
/// ## Equivalent point mass
/// A unit impulse P d applied at world point p of a free rigid body (mass m, world inertia J
/// about the centre c, arm r = p - c) changes its velocities by dv = P d / m and
/// domega = J^-1 (r x P d). The velocity of the material point at p changes by
/// du = dv + domega x r = P K d with the point's inverse-mass matrix
///
///     K = (1/m) 1 - [r]x J^-1 [r]x = (1/m) 1 + [r]x^T J^-1 [r]x,
///
/// ([r]x a = r x a, [r]x^T = -[r]x), symmetric and positive definite. The mass the point shows
/// along the unit direction d (du.d = P / m_eq) is
///
///     m_eq = 1 / (d^T K d) = 1 / (1/m + (r x d)^T J^-1 (r x d)).
///
/// At the centre (r = 0) m_eq = m; on a sphere (J = j 1) with r perpendicular to d,
/// m_eq = 1 / (1/m + |r|^2 / j). For the relative motion of points p1 on body 1 and p2 on body 2
/// under an equal and opposite impulse pair (a spring between them), the relative velocity
/// changes by P (K1 + K2) d, so m_eq = 1 / (d^T (K1 + K2) d), the series combination of the two
/// inverse masses. Without a direction the functions return the smallest equivalent mass over all
/// directions, 1 / lambda_max(K) (the stiffest case for a time-step estimate).
///
/// ## Critical time step
/// A linear spring k with dashpot c between a fixed point and a mass m (or between two bodies
/// with their relative EQM) has the natural frequency omega = sqrt(k/m) and the damping ratio
/// xi = c / (2 sqrt(k m)). The central-difference (velocity Verlet) scheme is stable for
///
///     h <= h_crit = (2 / omega) (sqrt(1 + xi^2) - xi),
///
/// which is 2/omega without damping and decreases with damping (Belytschko, Liu, Moran,
/// Nonlinear Finite Elements for Continua and Structures, Wiley 2000, ch. 6; the rule of the
/// Parmec's CRITICAL and EQM commands, where 2/sqrt(stiffness mass) is to be read as 2/omega).
///
/// Units (SI): mass kg, stiffness N/m, damping N s/m, omega rad/s, time s.

#include <grain/bodies/rigid_body.hpp>
#include <grain/core/error.hpp>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstddef>

namespace grain::bodies {

/// Inverse-mass matrix K = (1/m) 1 + [r]x^T J^-1 [r]x [1/kg] of a point at arm r [m] from the
/// centre of a body of mass m [kg] and inverse world inertia `inv_inertia` [1/(kg m^2)].
inline Eigen::Matrix3d point_inverse_mass(double mass, const Eigen::Matrix3d& inv_inertia,
                                          const Vec3& arm) {
  Eigen::Matrix3d rx;
  rx << 0.0, -arm.z(), arm.y(), arm.z(), 0.0, -arm.x(), -arm.y(), arm.x(), 0.0;
  return Eigen::Matrix3d::Identity() / mass + rx.transpose() * inv_inertia * rx;
}

/// K of the material point at world position `point` of body i [1/kg].
inline Eigen::Matrix3d point_inverse_mass(const RigidBodies& b, std::size_t i, const Vec3& point) {
  return point_inverse_mass(b.mass[i], inverse_world_inertia(b, i), point - b.position[i]);
}

namespace detail {
inline Vec3 unit_direction(const Vec3& d) {
  const double n = d.norm();
  grain::detail::require(std::isfinite(n) && n > 0.0, "equivalent mass", "direction", d.transpose(),
                         "a finite non-zero vector");
  return d / n;
}
inline double eqm_along(const Eigen::Matrix3d& k, const Vec3& d) {
  const Vec3 u = unit_direction(d);
  return 1.0 / u.dot(k * u);
}
inline double eqm_min(const Eigen::Matrix3d& k) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(k, Eigen::EigenvaluesOnly);
  return 1.0 / eig.eigenvalues().maxCoeff();
}
inline void require_body(const RigidBodies& b, std::size_t i) {
  grain::detail::require(i < b.size(), "equivalent mass", "body index", i,
                         "[0, " + std::to_string(b.size()) + ")");
}
/// Two bodies of a relative equivalent mass: valid, and not the same body (two points of one
/// rigid body do not move independently, so K1 + K2 would not describe them).
inline void require_pair(const RigidBodies& b, std::size_t i, std::size_t j) {
  require_body(b, i);
  require_body(b, j);
  grain::detail::require(i != j, "equivalent mass", "body j", j,
                         "a body other than body i = " + std::to_string(i));
}
} // namespace detail

/// Equivalent mass [kg] of the point `point` [m, world] of body i along `direction` (any
/// non-zero length; it is normalised): 1 / (d^T K d).
inline double equivalent_mass(const RigidBodies& b, std::size_t i, const Vec3& point,
                              const Vec3& direction) {
  detail::require_body(b, i);
  return detail::eqm_along(point_inverse_mass(b, i, point), direction);
}

/// Smallest equivalent mass over all directions at `point` of body i [kg]: 1 / lambda_max(K).
inline double equivalent_mass(const RigidBodies& b, std::size_t i, const Vec3& point) {
  detail::require_body(b, i);
  return detail::eqm_min(point_inverse_mass(b, i, point));
}

/// Relative equivalent mass [kg] of point p1 on body i and point p2 on body j along
/// `direction`: 1 / (d^T (K1 + K2) d).
inline double equivalent_mass(const RigidBodies& b, std::size_t i, const Vec3& p1, std::size_t j,
                              const Vec3& p2, const Vec3& direction) {
  detail::require_pair(b, i, j);
  return detail::eqm_along(point_inverse_mass(b, i, p1) + point_inverse_mass(b, j, p2), direction);
}

/// Smallest relative equivalent mass of p1 on body i and p2 on body j over all directions [kg].
inline double equivalent_mass(const RigidBodies& b, std::size_t i, const Vec3& p1, std::size_t j,
                              const Vec3& p2) {
  detail::require_pair(b, i, j);
  return detail::eqm_min(point_inverse_mass(b, i, p1) + point_inverse_mass(b, j, p2));
}

/// Natural circular frequency sqrt(k/m) [rad/s] of a stiffness k [N/m] on a mass m [kg].
inline double natural_frequency(double stiffness, double mass) {
  grain::detail::require_positive("natural frequency", "stiffness", stiffness);
  grain::detail::require_positive("natural frequency", "mass", mass);
  return std::sqrt(stiffness / mass);
}

/// Critical damping coefficient 2 sqrt(k m) [N s/m]; a dashpot c has the damping ratio
/// xi = c / critical_damping(k, m).
inline double critical_damping(double stiffness, double mass) {
  grain::detail::require_positive("critical damping", "stiffness", stiffness);
  grain::detail::require_positive("critical damping", "mass", mass);
  return 2.0 * std::sqrt(stiffness * mass);
}

/// Critical time step (2/omega)(sqrt(1 + xi^2) - xi) [s] of the central-difference scheme for
/// an oscillator of circular frequency omega [rad/s] and damping ratio xi >= 0 [-]. Written as
/// 2 / (omega (sqrt(1 + xi^2) + xi)) to avoid cancellation for large xi.
inline double critical_step(double omega, double damping_ratio) {
  grain::detail::require_positive("critical step", "omega", omega);
  grain::detail::require_non_negative("critical step", "damping ratio", damping_ratio);
  return 2.0 / (omega * (std::sqrt(1.0 + damping_ratio * damping_ratio) + damping_ratio));
}

/// Critical time step [s] of a spring of stiffness k [N/m] and damping ratio xi on the
/// equivalent mass m_eq [kg] (see `equivalent_mass`): critical_step(sqrt(k/m_eq), xi).
inline double spring_critical_step(double stiffness, double mass, double damping_ratio) {
  return critical_step(natural_frequency(stiffness, mass), damping_ratio);
}

} // namespace grain::bodies
