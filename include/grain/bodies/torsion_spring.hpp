#pragma once
/// \file torsion_spring.hpp
/// Torsion spring between two bodies (the TORSION_SPRING command of the Parmec user manual),
/// written as a stateless law on the two bodies' orientations and spatial angular velocities.
/// Body 2 may be the fixed world (identity orientation, zero angular velocity).
///
/// Units: SI (rad, rad/s, N m, N m s/rad, kg m^2).
///
/// ## Frames
///
/// At creation two orthogonal directions are given in the world, `zdir` (the yaw axis) and
/// `xdir` (the roll axis); y = z x x is the pitch axis. `torsion_frames` stores them in each
/// body's own frame, so that each body carries a co-rotated copy: F_i = R_i [x y z]_i (world
/// columns; R_i the body's rotation). At creation F_1 = F_2.
///
/// ## Angles
///
/// The relative rotation Q = F_2^T F_1 (body 1 relative to body 2, in frame coordinates) is split
/// into a twist about z followed by a swing about an axis in the x-y plane, Q = S(a, beta)
/// Rz(theta):
///
///   yaw theta = the twist angle,   (roll psi, pitch phi) = beta (a_x, a_y),
///
/// all in (-pi, pi]. So pure rotations about x, y or z give exactly that angle in roll, pitch or
/// yaw, the swing angle sqrt(psi^2 + phi^2) is exactly the angle between the two z axes (a true
/// cone about z), and for small rotations the angles agree to first order with the manual's
/// time integrals of the rates below. Unlike those integrals they depend only on the current
/// orientations (no drift, no history to store).
///
/// ## Rates and torque
///
/// With x, y, z the axes co-rotated with body 1 (the columns of F_1) and dw = w1 - w2:
///
///   psi' = x . dw,   phi' = y . dw,   theta' = z . dw
///
/// (the manual's formulas pair phi' with z and theta' with y, while its torque and its output
/// names pair pitch with y and yaw with z; the latter is used). Per angle a of axis n_a,
///
///   T_a = k_a(a) + d_a(a'),   torque on body 1 = -(T_roll x + T_pitch y + T_yaw z),
///
/// body 2 gets the opposite. k_a is the torque-angle table (default zero), d_a the dashpot
/// torque-rate table or c a' with c = 2 xi sqrt(k J), xi the critical damping ratio, k the
/// current tangent stiffness of k_a (zero outside its range) and J the effective moment of
/// inertia about that axis passed by the caller. Positive table slopes are restoring.
///
/// ## Cone
///
/// A cone couples two or three angles into the radial angle r = sqrt(sum of their squares):
/// T = k(r) + d(r') with r' = sum(a a') / r and the laws of the first coupled angle in (roll,
/// pitch, yaw) order; the torque on body 1 is -T sum (a / r) n_a over the coupled angles (none
/// at r = 0). The other angles keep their own laws. E.g. a ('roll', 'pitch') cone with a table
/// zero up to r0 and stiff beyond limits the angle between the two z axes to about r0.

#include <grain/bodies/spring.hpp>
#include <grain/core/error.hpp>
#include <grain/core/table.hpp>
#include <grain/core/vector.hpp>

#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>

namespace grain::bodies {

/// The law of one angle.
struct TorsionLaw {
  std::optional<Table> spring{};  ///< torque-angle table [rad -> N m]; absent: zero
  std::optional<Table> dashpot{}; ///< torque-rate table [rad/s -> N m]; excludes damping_ratio
  double damping_ratio = 0.0;     ///< critical damping ratio xi >= 0 [-]
};

/// Parameters of one torsion spring.
struct TorsionSpringParams {
  TorsionLaw roll{};  ///< about x
  TorsionLaw pitch{}; ///< about y = z x x
  TorsionLaw yaw{};   ///< about z
  /// The angles coupled into a cone (roll, pitch, yaw); none, or at least two.
  std::array<bool, 3> cone{false, false, false};
  std::string name = "TORSION_SPRING"; ///< name used in error messages
};

/// The reference directions in each body's frame (unit, x orthogonal to z).
struct TorsionFrames {
  Vec3 x1 = Vec3::UnitX(), z1 = Vec3::UnitZ(); ///< in body 1's frame
  Vec3 x2 = Vec3::UnitX(), z2 = Vec3::UnitZ(); ///< in body 2's frame
};

/// The two bodies' orientations (body -> world) and spatial angular velocities [rad/s].
struct TorsionKinematics {
  Eigen::Quaterniond q1 = Eigen::Quaterniond::Identity();
  Eigen::Quaterniond q2 = Eigen::Quaterniond::Identity();
  Vec3 w1 = Vec3::Zero();
  Vec3 w2 = Vec3::Zero();

  /// The same from rotation matrices (body -> world).
  static TorsionKinematics from_matrices(const Eigen::Matrix3d& R1, const Eigen::Matrix3d& R2,
                                         const Vec3& w1, const Vec3& w2) {
    return TorsionKinematics{Eigen::Quaterniond(R1), Eigen::Quaterniond(R2), w1, w2};
  }
};

/// What one evaluation gives; per-angle arrays are in (roll, pitch, yaw) order.
struct TorsionResult {
  Vec3 torque = Vec3::Zero(); ///< on body 1 [N m]; body 2 gets -torque
  Vec3 x = Vec3::UnitX(), y = Vec3::UnitY(), z = Vec3::UnitZ(); ///< body 1's axes (world)
  Vec3 angles = Vec3::Zero();                                   ///< (psi, phi, theta) [rad]
  Vec3 rates = Vec3::Zero();                                    ///< their rates [rad/s]
  Vec3 spring_torque = Vec3::Zero();                            ///< elastic parts of T_a [N m]
  Vec3 total_torque = Vec3::Zero();                             ///< T_a (elastic + damping) [N m]

  template <class Archive>
  void serialize(Archive& ar) {
    ar(torque, x, y, z, angles, rates, spring_torque, total_torque);
  }
};

namespace detail {

/// (roll, pitch, yaw) of a relative rotation by the swing-twist split about z.
inline Vec3 swing_twist_angles(Eigen::Quaterniond q) {
  q.normalize();
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();
  const double yaw = (q.z() == 0.0 && q.w() == 0.0) ? 0.0 : 2.0 * std::atan2(q.z(), q.w());
  const Eigen::Quaterniond twist(std::cos(0.5 * yaw), 0.0, 0.0, std::sin(0.5 * yaw));
  const Eigen::Quaterniond swing = q * twist.conjugate();
  const Vec3 v(swing.x(), swing.y(), 0.0);
  const double n = v.norm();
  if (n == 0.0) return Vec3(0.0, 0.0, yaw);
  const double beta = 2.0 * std::atan2(n, std::abs(swing.w()));
  const double sgn = swing.w() < 0.0 ? -1.0 : 1.0;
  return Vec3(sgn * beta * v.x() / n, sgn * beta * v.y() / n, yaw);
}

/// T = k(a) + d(a') of one law.
inline double torsion_torque(const TorsionLaw& law, double a, double rate, double inertia,
                             double& elastic) {
  elastic = law.spring ? (*law.spring)(a) : 0.0;
  double damping = 0.0;
  if (law.dashpot) {
    damping = (*law.dashpot)(rate);
  } else if (law.damping_ratio > 0.0 && law.spring) {
    const double k = std::max(table_slope(*law.spring, a), 0.0);
    damping = 2.0 * law.damping_ratio * std::sqrt(k * inertia) * rate;
  }
  return elastic + damping;
}

inline void validate_law(const std::string& obj, const char* which, const TorsionLaw& law) {
  if (law.spring)
    grain::detail::require_given(*law.spring, obj, std::string(which) + ".spring",
                                 "a given torque-angle table (or leave it absent)");
  if (law.dashpot)
    grain::detail::require_given(*law.dashpot, obj, std::string(which) + ".dashpot",
                                 "a given torque-rate table (or leave it absent)");
  const std::string name = std::string(which) + ".damping_ratio";
  grain::detail::require(std::isfinite(law.damping_ratio) && law.damping_ratio >= 0.0, obj,
                         name.c_str(), law.damping_ratio, "[0, inf) (a critical damping ratio)");
  if (law.dashpot && law.damping_ratio > 0.0)
    throw InputError(obj + ": " + name + " = " + grain::detail::to_text(law.damping_ratio) +
                     " is invalid; valid range: 0 when a dashpot table is given (give one of "
                     "the two)");
}

} // namespace detail

/// Checks the parameters; throws `InputError` naming the spring, the value and the valid range.
inline void validate(const TorsionSpringParams& p) {
  detail::validate_law(p.name, "roll", p.roll);
  detail::validate_law(p.name, "pitch", p.pitch);
  detail::validate_law(p.name, "yaw", p.yaw);
  const int n = int(p.cone[0]) + int(p.cone[1]) + int(p.cone[2]);
  grain::detail::require(n != 1, p.name, "number of cone angles", n,
                         "0, 2 or 3 (a cone couples at least two angles)");
}

/// The frames of a torsion spring created with the bodies at orientations q1, q2 and the world
/// directions zdir, xdir (non-zero, orthogonal within 1e-6 after normalisation).
inline TorsionFrames torsion_frames(const Eigen::Quaterniond& q1, const Eigen::Quaterniond& q2,
                                    const Vec3& zdir, const Vec3& xdir,
                                    const std::string& name = "TORSION_SPRING") {
  detail::require_finite_vec(name, "zdir", zdir);
  detail::require_finite_vec(name, "xdir", xdir);
  grain::detail::require(zdir.norm() > 0.0, name, "|zdir|", zdir.norm(), "(0, inf)");
  grain::detail::require(xdir.norm() > 0.0, name, "|xdir|", xdir.norm(), "(0, inf)");
  const Vec3 z = zdir.normalized(), x = xdir.normalized();
  grain::detail::require(std::abs(z.dot(x)) <= 1e-6, name, "zdir . xdir (unit)", z.dot(x),
                         "[-1e-6, 1e-6] (orthogonal directions)");
  const Vec3 xo = (x - z.dot(x) * z).normalized();
  const Eigen::Matrix3d R1t = q1.normalized().toRotationMatrix().transpose();
  const Eigen::Matrix3d R2t = q2.normalized().toRotationMatrix().transpose();
  return TorsionFrames{R1t * xo, R1t * z, R2t * xo, R2t * z};
}

/// Evaluates the torsion spring; `effective_inertia` holds the moments of inertia [kg m^2] about
/// (x, y, z) used by damping ratios. The parameters must have passed `validate`.
inline TorsionResult evaluate(const TorsionSpringParams& p, const TorsionFrames& f,
                              const TorsionKinematics& k, const Vec3& effective_inertia) {
  TorsionResult r;
  const Eigen::Matrix3d R1 = k.q1.normalized().toRotationMatrix();
  const Eigen::Matrix3d R2 = k.q2.normalized().toRotationMatrix();
  Eigen::Matrix3d F1, F2;
  F1.col(0) = R1 * f.x1;
  F1.col(2) = R1 * f.z1;
  F1.col(1) = F1.col(2).cross(F1.col(0));
  F2.col(0) = R2 * f.x2;
  F2.col(2) = R2 * f.z2;
  F2.col(1) = F2.col(2).cross(F2.col(0));
  const Eigen::Matrix3d Q = F2.transpose() * F1;
  r.angles = detail::swing_twist_angles(Eigen::Quaterniond(Q));
  const Vec3 dw = k.w1 - k.w2;
  r.x = F1.col(0);
  r.y = F1.col(1);
  r.z = F1.col(2);
  r.rates = Vec3(r.x.dot(dw), r.y.dot(dw), r.z.dot(dw));

  const std::array<const TorsionLaw*, 3> laws{&p.roll, &p.pitch, &p.yaw};
  const bool cone = p.cone[0] || p.cone[1] || p.cone[2];
  for (int i = 0; i < 3; ++i) {
    if (cone && p.cone[static_cast<std::size_t>(i)]) continue;
    double el = 0.0;
    r.total_torque[i] = detail::torsion_torque(*laws[static_cast<std::size_t>(i)], r.angles[i],
                                               r.rates[i], effective_inertia[i], el);
    r.spring_torque[i] = el;
  }
  if (cone) {
    int first = -1;
    double r2 = 0.0, rr = 0.0;
    for (int i = 0; i < 3; ++i) {
      if (!p.cone[static_cast<std::size_t>(i)]) continue;
      if (first < 0) first = i;
      r2 += r.angles[i] * r.angles[i];
      rr += r.angles[i] * r.rates[i];
    }
    const double radial = std::sqrt(r2);
    if (radial > 0.0) {
      double el = 0.0;
      const double T = detail::torsion_torque(*laws[static_cast<std::size_t>(first)], radial,
                                              rr / radial, effective_inertia[first], el);
      for (int i = 0; i < 3; ++i) {
        if (!p.cone[static_cast<std::size_t>(i)]) continue;
        r.total_torque[i] = T * r.angles[i] / radial;
        r.spring_torque[i] = el * r.angles[i] / radial;
      }
    }
  }
  r.torque = -(r.total_torque[0] * r.x + r.total_torque[1] * r.y + r.total_torque[2] * r.z);
  return r;
}

/// The radial (cone) angle of the coupled angles [rad].
inline double cone_angle(const TorsionSpringParams& p, const Vec3& angles) {
  double r2 = 0.0;
  for (int i = 0; i < 3; ++i)
    if (p.cone[static_cast<std::size_t>(i)]) r2 += angles[i] * angles[i];
  return std::sqrt(r2);
}

} // namespace grain::bodies
