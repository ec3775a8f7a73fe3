#pragma once
/// \file relative_rotation.hpp
/// Kinematics shared by the rolling-resistance models (namespace `grain::rolling::detail`).
///
/// The rolling of a contact is the part of the relative angular velocity w_rel = w_i - w_j
/// [rad/s] that is perpendicular to the contact normal n: w_r = w_rel - (w_rel . n) n in 3D (the
/// normal part is twisting, which these models do not resist), w_r = w_rel in 2D (the scalar z
/// component, always perpendicular to the in-plane normal). The rolling velocity is
/// v_r = R* |w_r| [m/s] (the objective rolling velocity -R* (w_i - w_j) x n of Luding, Granular
/// Matter 10 (2008) 235; it vanishes for a rigid rotation of the pair). For a wall the partner's
/// angular velocity is that of the wall (see `ContactGeometry::omega_rel`).
///
/// A rolling torque M acts on i and -M on j, so the pair's angular momentum is conserved.

#include <cmath>
#include <grain/models/concepts.hpp>

namespace grain::rolling::detail {

/// Rolling angular velocity w_r [rad/s] of a contact.
inline double rolling_omega(const ContactGeometry<2>& g) { return g.omega_rel; }
inline Vec3 rolling_omega(const ContactGeometry<3>& g) {
  return g.omega_rel - g.omega_rel.dot(g.normal) * g.normal;
}

/// Rolling angular velocity that turned the contact over the last step (springs integrate it).
inline double rolling_slip_omega(const ContactGeometry<2>& g) { return g.slip_omega_rel; }
inline Vec3 rolling_slip_omega(const ContactGeometry<3>& g) {
  return g.slip_omega_rel - g.slip_omega_rel.dot(g.normal) * g.normal;
}

/// Adds M to the torque on i and -M to the torque on j.
template <class A>
inline void apply(const A& m, A& ti, A& tj) {
  ti += m;
  tj -= m;
}

/// The rolling-resistance coefficient: `given` if >= 0, else the pair's.
inline double coefficient(double given, const PairProperties& pair) {
  return given >= 0.0 ? given : pair.rolling_friction;
}

inline void validate_coefficient(const char* model, double c) {
  grain::detail::require(std::isfinite(c), model, "coefficient", c,
                         "[0, inf), or < 0 for the pair's rolling_friction");
}

} // namespace grain::rolling::detail
