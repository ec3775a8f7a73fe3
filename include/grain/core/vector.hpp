#pragma once
/// \file vector.hpp
/// Small fixed-size vectors and the 2D/3D rotation helpers used everywhere in grain.
///
/// Positions, velocities and forces are Eigen column vectors of dimension D (2 or 3), in SI units.
/// Angular quantities (angular velocity, torque) are a scalar in 2D (the z component) and a
/// 3-vector in 3D; `Angular<D>` names that type, and `cross` covers every combination.

#include <grain/core/config.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <type_traits>

namespace grain {

/// A D-dimensional column vector of doubles [SI units of whatever it holds].
template <int D>
using Vec = Eigen::Matrix<double, D, 1>;
using Vec2 = Vec<2>;
using Vec3 = Vec<3>;

/// A trivially copyable D-vector for per-contact history (Eigen types are not trivially
/// copyable); convert with `load` / `store`.
template <int D>
using PlainVec = std::array<double, D>;

template <int D>
inline Vec<D> load(const PlainVec<D>& a) {
  return Eigen::Map<const Vec<D>>(a.data());
}
template <int D>
inline void store(PlainVec<D>& a, const Vec<D>& v) {
  Eigen::Map<Vec<D>>(a.data()) = v;
}

/// Angular velocity / torque type: `double` (z component) in 2D, `Vec3` in 3D.
template <int D>
using Angular = std::conditional_t<D == 2, double, Vec3>;

/// Orientation type: an angle [rad] in 2D, a unit quaternion in 3D.
template <int D>
using Orientation = std::conditional_t<D == 2, double, Eigen::Quaterniond>;

/// Zero value of a vector or angular quantity.
template <class T>
inline T zero() {
  if constexpr (std::is_arithmetic_v<T>)
    return T(0);
  else
    return T::Zero();
}

/// Identity orientation.
template <int D>
inline Orientation<D> identity_orientation() {
  if constexpr (D == 2)
    return 0.0;
  else
    return Eigen::Quaterniond::Identity();
}

/// omega x r for a 2D angular velocity (z) and an in-plane arm.
GRAIN_INLINE Vec2 cross(double w, const Vec2& r) { return Vec2(-w * r.y(), w * r.x()); }
/// omega x r in 3D.
GRAIN_INLINE Vec3 cross(const Vec3& w, const Vec3& r) { return w.cross(r); }
/// r x F (z component) in 2D.
GRAIN_INLINE double cross(const Vec2& r, const Vec2& f) { return r.x() * f.y() - r.y() * f.x(); }

/// Euclidean norm of an angular quantity.
inline double norm(double w) { return std::abs(w); }
inline double norm(const Vec3& w) { return w.norm(); }
/// Dot product of two angular quantities (scalars in 2D, 3-vectors in 3D).
inline double dot(double a, double b) { return a * b; }
inline double dot(const Vec3& a, const Vec3& b) { return a.dot(b); }
/// Squared norm of an angular quantity.
inline double squared_norm(double w) { return w * w; }
inline double squared_norm(const Vec3& w) { return w.squaredNorm(); }

/// Advance an orientation by the rotation `w * dt` (exact for constant w).
inline void rotate(double& angle, double w, double dt) { angle += w * dt; }
inline void rotate(Eigen::Quaterniond& q, const Vec3& w, double dt) {
  const double angle = w.norm() * dt;
  if (angle > 0.0) {
    q = Eigen::Quaterniond(Eigen::AngleAxisd(angle, w / w.norm())) * q;
    q.normalize();
  }
}

/// Rotate a vector `r` by the angle `w*dt` (2D) or the rotation vector `w*dt` (3D).
inline Vec2 rotated(const Vec2& r, double w, double dt) {
  const double c = std::cos(w * dt), s = std::sin(w * dt);
  return Vec2(c * r.x() - s * r.y(), s * r.x() + c * r.y());
}
inline Vec3 rotated(const Vec3& r, const Vec3& w, double dt) {
  const double angle = w.norm() * dt;
  if (angle == 0.0) return r;
  return Eigen::AngleAxisd(angle, w / w.norm()) * r;
}

/// True if every component is finite.
template <class T>
inline bool all_finite(const T& v) {
  if constexpr (std::is_arithmetic_v<T>)
    return std::isfinite(v);
  else
    return v.allFinite();
}

} // namespace grain
