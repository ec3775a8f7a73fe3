#pragma once
/// \file geometry.hpp
/// Contact geometry and kinematics of a particle i and its partner j (a particle or a wall).
///
/// Conventions (SI units):
/// - `normal` n is the unit vector from the centre of i towards the partner.
/// - `overlap` delta = R_i + R_j - |x_j - x_i| for two particles, R_i - (distance of the centre
///   to the wall surface) for a wall; the pair touches while delta > 0.
/// - The contact point lies in the middle of the overlap: x_c = x_i + (R_i - delta/2) n.
///   `arm_i` = x_c - x_i and `arm_j` = x_c - x_j (zero for walls, which receive no torque).
/// - `velocity` is the velocity of i relative to j at the contact point, rotation included:
///   (v_i + w_i x arm_i) - (v_j + w_j x arm_j) (wall: its surface velocity at x_c).
///   `normal_velocity` = velocity . n is positive while the pair approaches.
/// - `omega_rel` is w_i - w_j (for a wall, w_i minus the wall's angular velocity).
/// - `slip_velocity` is the tangential relative velocity at the contact point that moved the
///   contact over the last step; tangential springs integrate it (xi += slip_velocity dt). It
///   equals `tangential_velocity` except with velocity Verlet, where forces see the velocity
///   predicted at the end of the step (so that dashpots are second-order accurate) while positions
///   advanced with the half-step velocity. `slip_omega_rel` is the rotational counterpart (used by
///   rolling springs).
/// - A wall is a partner of infinite radius and mass: r_eff = R_i (flat), R_i R_w/(R_w -+ R_i)
///   for the inside/outside of a circle; m_eff = m_i.
/// - `lens_contact_radius(g)` is the geometric radius of the intersection of the two undeformed
///   bodies (the half chord of the lens), a = sqrt(R_i^2 - ((R_i^2 - R_j^2 + d^2)/(2 d))^2), or
///   sqrt(R_i^2 - d^2) for a flat wall. For small overlaps it is sqrt(2) times the Hertz radius
///   sqrt(r_eff delta); models that need the Hertz radius compute it from r_eff and overlap.

#include <algorithm>
#include <cmath>
#include <grain/core/config.hpp>
#include <grain/core/vector.hpp>
#include <grain/walls/walls.hpp>

namespace grain {

template <int D>
struct ContactGeometry {
  Vec<D> normal;
  double overlap = 0.0;
  double distance = 0.0; ///< centre distance (pair) or centre-to-surface distance (wall) [m]
  Vec<D> point;          ///< contact point [m]
  Vec<D> arm_i, arm_j;
  Vec<D> velocity;                       ///< relative velocity at the contact point [m/s]
  double normal_velocity = 0.0;          ///< velocity . normal [m/s], > 0 approaching
  Vec<D> tangential_velocity;            ///< velocity - normal_velocity * normal [m/s]
  Vec<D> slip_velocity;                  ///< tangential velocity that moved the contact [m/s]
  Angular<D> omega_rel;                  ///< w_i - w_j (wall: w_i - w_wall) [rad/s]
  Angular<D> slip_omega_rel;             ///< w_i - w_j that turned the contact over the last step
  double radius_i = 0.0, radius_j = 0.0; ///< radius_j is infinite for a flat wall [m]
  double r_eff = 0.0;                    ///< effective radius R* [m]
  double m_eff = 0.0;                    ///< effective mass m* [kg]
  bool wall = false;
};

namespace detail {

/// Lens half-chord of two circles of radii r1, r2 at centre distance d.
GRAIN_INLINE double lens_radius(double r1, double r2, double d) {
  const double x = (r1 * r1 - r2 * r2 + d * d) / (2.0 * d);
  return std::sqrt(std::abs(r1 * r1 - x * x));
}

} // namespace detail

/// Geometry of two touching particles. `n` and `dist` come from the caller's distance test.
template <int D>
GRAIN_INLINE void pair_geometry(ContactGeometry<D>& g, const Vec<D>& xi, const Vec<D>& n,
                                double dist, double ri, double rj, double mi, double mj,
                                const Vec<D>& vi, const Vec<D>& vj, const Angular<D>& wi,
                                const Angular<D>& wj) {
  g.normal = n;
  g.distance = dist;
  g.overlap = ri + rj - dist;
  const double ci = ri - 0.5 * g.overlap, cj = rj - 0.5 * g.overlap;
  g.arm_i = ci * n;
  g.arm_j = -cj * n;
  g.point = xi + g.arm_i;
  g.velocity = (vi + cross(wi, g.arm_i)) - (vj + cross(wj, g.arm_j));
  g.normal_velocity = g.velocity.dot(n);
  g.tangential_velocity = g.velocity - g.normal_velocity * n;
  g.slip_velocity = g.tangential_velocity;
  g.omega_rel = wi - wj;
  g.slip_omega_rel = g.omega_rel;
  g.radius_i = ri;
  g.radius_j = rj;
  g.r_eff = ri * rj / (ri + rj);
  g.m_eff = mi * mj / (mi + mj);
  g.wall = false;
}

/// Geometry of a particle (centre x, radius r, mass m) touching a wall.
template <int D>
GRAIN_INLINE void wall_geometry(ContactGeometry<D>& g, const Wall<D>& wall,
                                const WallProximity<D>& w, const Vec<D>& x, double r, double m,
                                const Vec<D>& v, const Angular<D>& omega) {
  g.normal = w.normal;
  g.distance = w.distance;
  g.overlap = r - w.distance;
  g.arm_i = (r - 0.5 * g.overlap) * w.normal;
  g.point = x + g.arm_i;
  g.arm_j = Vec<D>::Zero();
  g.velocity = (v + cross(omega, g.arm_i)) - wall.velocity_at(g.point);
  g.normal_velocity = g.velocity.dot(w.normal);
  g.tangential_velocity = g.velocity - g.normal_velocity * w.normal;
  g.slip_velocity = g.tangential_velocity;
  g.omega_rel = omega - wall.options.omega;
  g.slip_omega_rel = g.omega_rel;
  g.radius_i = r;
  g.m_eff = m;
  if (std::isinf(w.curvature_radius)) {
    g.radius_j = w.curvature_radius;
    g.r_eff = r;
  } else {
    // circle wall: convex (> 0, particle outside) or concave (< 0, particle inside)
    const double rw = w.curvature_radius;
    g.radius_j = rw;
    g.r_eff = r * rw / (rw + r);
  }
  g.wall = true;
}

/// The half chord of the lens in which the undeformed bodies of a touching contact intersect [m]
/// (flat wall: sqrt(R_i^2 - d^2); circle wall: the lens of the two circles).
template <int D>
GRAIN_INLINE double lens_contact_radius(const ContactGeometry<D>& g) {
  const double r = g.radius_i;
  if (!g.wall) return detail::lens_radius(r, g.radius_j, g.distance);
  if (std::isinf(g.radius_j)) {
    const double d = std::max(g.distance, 0.0);
    return std::sqrt(std::max(r * r - d * d, 0.0));
  }
  const double rc = std::abs(g.radius_j);
  const double centre_distance = g.radius_j > 0 ? g.distance + rc : rc - g.distance;
  return centre_distance > 0 ? detail::lens_radius(r, rc, centre_distance) : r;
}

/// Geometry of two particles separated by a gap (for conduction across the gap): normal,
/// distance, radii, r_eff, m_eff and overlap = -gap; no velocities.
template <int D>
inline void gap_pair_geometry(ContactGeometry<D>& g, const Vec<D>& n, double dist, double ri,
                              double rj, double mi, double mj) {
  g.normal = n;
  g.distance = dist;
  g.overlap = ri + rj - dist;
  g.radius_i = ri;
  g.radius_j = rj;
  g.r_eff = ri * rj / (ri + rj);
  g.m_eff = mi * mj / (mi + mj);
  g.normal_velocity = 0.0;
  g.wall = false;
}

/// Geometry of a particle separated from a wall by a gap (see gap_pair_geometry).
template <int D>
inline void gap_wall_geometry(ContactGeometry<D>& g, const WallProximity<D>& w, double r,
                              double m) {
  g.normal = w.normal;
  g.distance = w.distance;
  g.overlap = r - w.distance;
  g.radius_i = r;
  g.radius_j = w.curvature_radius;
  g.r_eff = std::isinf(w.curvature_radius) ? r : r * w.curvature_radius / (w.curvature_radius + r);
  g.m_eff = m;
  g.normal_velocity = 0.0;
  g.wall = true;
}

/// Sets `slip_velocity` from the velocities that moved the particles over the last step.
template <int D>
inline void set_slip_velocity(ContactGeometry<D>& g, const Vec<D>& vi, const Vec<D>& vj,
                              const Angular<D>& wi, const Angular<D>& wj) {
  const Vec<D> u = (vi + cross(wi, g.arm_i)) - (vj + cross(wj, g.arm_j));
  g.slip_velocity = u - u.dot(g.normal) * g.normal;
  g.slip_omega_rel = wi - wj;
}
template <int D>
inline void set_slip_velocity(ContactGeometry<D>& g, const Wall<D>& wall, const Vec<D>& v,
                              const Angular<D>& w) {
  const Vec<D> u = (v + cross(w, g.arm_i)) - wall.velocity_at(g.point);
  g.slip_velocity = u - u.dot(g.normal) * g.normal;
  g.slip_omega_rel = w - wall.options.omega;
}

} // namespace grain
