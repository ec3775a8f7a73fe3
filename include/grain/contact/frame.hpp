#pragma once
/// \file frame.hpp
/// The local frame of a contact and a view of one contact for stages and output.
///
/// `ContactFrame<D>` is an orthonormal, right-handed frame built from the contact normal n
/// (unit, from particle i towards its partner): in 2D (n, t) with t = (-n_y, n_x); in 3D
/// (n, t1, t2) with t1 x t2 = n. No tangent field on the sphere is continuous everywhere; the 3D
/// frame is J. R. Frisvad's ("Building an orthonormal basis from a 3D unit vector without
/// normalization", J. Graphics Tools 16(3), 2012), whose only discontinuity (at n = -z) is turned
/// to n = -(1, 2, 3)/sqrt(14), a direction that the axis-aligned walls and lattices of typical
/// set-ups do not produce: the tangents change continuously with n everywhere else (horizontal and
/// vertical contacts included). They depend on n alone, so a contact keeps its frame while its
/// normal does not turn.
///
/// `ContactView` bundles, separately: the partners (i, j, wall or not), the geometry
/// (`ContactGeometry`: normal, overlap, point, relative velocities), the physics result (force
/// and torques on i in global components, and through the frame in local ones), the model data
/// (the per-contact history of the models in use: `data.normal`, `data.tangent`, `data.rolling`,
/// `data.conduction`, `data.area`) and the heat rate into i [W]. `Simulation::for_each_contact`
/// passes one to a callable that takes a single argument.

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <grain/contact/geometry.hpp>
#include <grain/core/vector.hpp>

namespace grain {

template <int D>
struct ContactFrame;

/// 2D contact frame: normal n and tangent t = (-n_y, n_x) (t is n turned by +90 degrees).
template <>
struct ContactFrame<2> {
  Vec2 normal = Vec2::UnitX();
  Vec2 tangent = Vec2::UnitY();

  static ContactFrame from_normal(const Vec2& n) { return {n, Vec2(-n.y(), n.x())}; }
  /// Components (normal, tangential) of a global vector.
  Vec2 to_local(const Vec2& v) const { return {v.dot(normal), v.dot(tangent)}; }
  /// Global vector of local components (normal, tangential).
  Vec2 to_global(const Vec2& l) const { return l[0] * normal + l[1] * tangent; }
  /// A 2D torque is a scalar about the out-of-plane axis: the same in both frames.
  static double to_local(double torque) { return torque; }
};

/// 3D contact frame: normal n and tangents t1, t2 with (n, t1, t2) right-handed.
template <>
struct ContactFrame<3> {
  Vec3 normal = Vec3::UnitX();
  Vec3 tangent1 = Vec3::UnitY();
  Vec3 tangent2 = Vec3::UnitZ();

  static ContactFrame from_normal(const Vec3& n) {
    // Frisvad's basis of m = S^T n, turned back by S: continuous in n except near n = -s, the
    // image of m = -z (s = S z = (1, 2, 3)/sqrt(14), a direction few contacts have)
    const Vec3 m = to_pole_frame(n);
    const double c = 1.0 + m.z();
    Vec3 b1;
    if (c > 1e-12) {
      const double a = 1.0 / c, b = -m.x() * m.y() * a;
      b1 = Vec3(1.0 - m.x() * m.x() * a, b, -m.x());
    } else {
      b1 = Vec3(0.0, -1.0, 0.0);
    }
    // Frisvad's vectors lose orthogonality as eps / (1 + m_z) towards the pole (1e-14 seen);
    // one Gram-Schmidt step keeps the basis orthonormal to rounding everywhere, and continuous
    b1 = (b1 - b1.dot(m) * m).normalized();
    return {n, from_pole_frame(b1), from_pole_frame(m.cross(b1))};
  }
  /// Components (normal, tangent 1, tangent 2) of a global vector.
  Vec3 to_local(const Vec3& v) const { return {v.dot(normal), v.dot(tangent1), v.dot(tangent2)}; }
  /// Global vector of local components (normal, tangent 1, tangent 2).
  Vec3 to_global(const Vec3& l) const { return l[0] * normal + l[1] * tangent1 + l[2] * tangent2; }

private:
  /// The fixed rotation S (an orthonormal basis with third axis s = (1, 2, 3)/sqrt(14)).
  static const Eigen::Matrix3d& pole() {
    static const Eigen::Matrix3d r = [] {
      const Vec3 z = Vec3(1.0, 2.0, 3.0).normalized();
      const Vec3 x = Vec3(2.0, -1.0, 0.0).normalized();
      Eigen::Matrix3d m;
      m.col(0) = x;
      m.col(1) = z.cross(x);
      m.col(2) = z;
      return m;
    }();
    return r;
  }
  static Vec3 to_pole_frame(const Vec3& v) { return pole().transpose() * v; }
  static Vec3 from_pole_frame(const Vec3& v) { return pole() * v; }
};

/// One touching contact, as `Simulation::for_each_contact` shows it. References are valid only
/// during the call.
template <int D, class Result, class History>
struct ContactView {
  std::size_t i = 0; ///< particle (current index)
  std::size_t j = 0; ///< partner particle (current index) or wall index
  bool wall = false; ///< true if the partner is wall j
  const ContactGeometry<D>& geometry;
  const Result& result;   ///< force on i (on j: minus it) [N], torques on i and j [N m], parts
  const History& data;    ///< per-contact model data after this evaluation
  double heat_rate = 0.0; ///< heat flow into i through the contact [W] (0 without conduction)
  ContactFrame<D> frame;

  /// Contact force on i [N], global components.
  const Vec<D>& force() const { return result.force; }
  /// Contact force on i [N] in the frame: normal (negative = repulsive, since n points from i
  /// to the partner) and tangential components.
  Vec<D> force_local() const { return frame.to_local(result.force); }
  /// Torque on i [N m] in the frame (3D: normal = twisting, tangential = bending/rolling; 2D: the
  /// scalar torque).
  Angular<D> torque_i_local() const { return frame.to_local(result.torque_i); }
  /// Torque on j [N m] in the frame.
  Angular<D> torque_j_local() const { return frame.to_local(result.torque_j); }
};

} // namespace grain
