#pragma once
/// \file system.hpp
/// A system of rigid bodies connected by translational springs, torsion springs and ball joints,
/// under gravity and global damping, with rule-based spring failure, critical time-step
/// estimates and an adaptive step: the body part of Parmec (its SPRING, TORSION_SPRING,
/// UNSPRING, BALL_JOINT, GRAVITY, DAMPING, CRITICAL commands and the `adaptive` option of DEM)
/// assembled on `RigidBodies` (rigid_body.hpp).
///
/// Units (SI): m, s, kg, N, N m, rad, rad/s.
///
/// ## Attachments
/// Bodies are addressed by the index `add_body` returns; `world` (-1) stands for the fixed
/// world. Attachment points and directions are given in world coordinates when an object is
/// created and stored in each body's local frame (`to_local`), so they move with the body; a
/// point on `world` stays where it was given. For the point-to-plane geometry the plane normal is
/// carried by body 2 and turns with it.
///
/// ## Step
/// One step of length h from t to t + h (velocity Verlet with the rotation splitting of
/// rigid_body.hpp; F(t) are the forces of the configuration at t):
///
///     1. kick:   v += h/2 F(t)/m,  omega += h/2 J_world^-1 T(t)
///     2. joints: impulses that give every joint point the relative velocity -C/h (C the joint's
///                gap p1 - p2 at t), so that the drift closes the gap
///     3. drift:  x += h v, free rotation over h (stages 2 and 3 repeated with further impulses
///                until the gaps after the drift are closed, see below);  t += h
///     4. forces at t + h: gravity m g(t), external loads (set_external_load), global damping,
///        springs, torsion springs
///     5. kick:   v += h/2 F(t+h)/m,  omega += h/2 J_world^-1 T(t+h)
///     6. joints: impulses that set every joint point's relative velocity to zero
///     7. unspring rules (one `Unspring::update` each, on the springs' results of stage 4)
///
/// The forces of stage 4 see the positions at t + h and the velocities at t + h/2 (the usual
/// velocity Verlet lag of a dashpot: it shortens the period of a damped oscillator by the
/// relative xi omega h / 2, and a global damping d decays a velocity as (1 - d h) a step).
///
/// ## Ball joints
/// A ball joint keeps point p1 of body 1 and point p2 of body 2 (or a fixed point) coincident:
/// C = p1 - p2 = 0, three rows per joint. With the generalized velocities (v_i, omega_i) of the
/// bodies, the relative velocity of the joint points is u = J V with the blocks
/// J_(j, body1) = [1, -[r1]x], J_(j, body2) = -[1, -[r2]x] (r the arms from the centres,
/// [r]x a = r x a). Impulses lambda (on body 1 at p1, -lambda on body 2 at p2) change the
/// velocities by M^-1 J^T lambda, M^-1 = diag(1/m 1, J_world^-1); the impulses that give the
/// target relative velocities u_t solve
///
///     (J M^-1 J^T) lambda = u_t - J V*,
///
/// a sparse symmetric positive (semi-)definite system whose 3x3 blocks are the points'
/// inverse-mass matrices K = (1/m) 1 + [r]x^T J^-1 [r]x of eqm.hpp on the diagonal and
/// s_j s_k ((1/m) 1 - [r_j]x J^-1 [r_k]x) for two joints j, k on one body (s = +1 for body 1,
/// -1 for body 2). It is assembled for all joints and factorised with Eigen's SimplicialLDLT
/// twice a step, at the configurations of t (stage 2) and t + h (stage 6). The two stages are
/// the two halves of the RATTLE scheme (Andersen, 1983):
/// - stage 2 solves for u_t = -C/h: with a linear drift this would close the gap exactly, but the
///   rotation over the step is not linear, which leaves a gap of order h^2 |omega|^2 |r|; the
///   drift is then made again from the configuration at t after a further impulse with
///   u_t = J V - C(t+h)/h (the same matrix, i.e. the joint directions at t, as in SHAKE), until
///   the largest gap is below `joint_tolerance` (1e-12) times the largest joint arm, or stops
///   decreasing, or after `joint_iterations` (10) repetitions. Each repetition reduces the gap by
///   a factor of order h |omega|; two or three suffice;
/// - stage 6 solves for u_t = 0: the relative velocity at the joint points is zero at the end
///   of every step (as the Parmec user manual describes its ball joint).
/// So the joint length does not drift (a pendulum keeps it to 1e-12 over 100 periods) and the
/// energy of an undamped pendulum fluctuates at O(h^2) without drift. Initial velocities should
/// satisfy the joints (zero relative velocity at the joint points); otherwise the first step
/// removes the relative velocity by an inelastic impulse. A tiny diagonal regularisation (1e-12
/// of each row's diagonal entry) lets redundant joint sets be solved (two ball joints on one
/// axis make a hinge); the reactions of a redundant set are split by the regularised solution.
/// The joint reaction reported is the force on body 1, (lambda_2 + lambda_6) / h with lambda_2
/// all the impulses of stages 2-3: the mean joint force over the step (exactly m g for a body
/// hanging at rest). Joints are constraints, not springs: they do not enter the critical step,
/// and their solve does not restrict the step.
///
/// ## Critical steps
/// Estimates from the springs' tangent stiffness and damping at their last evaluation:
/// - a translational spring: omega = sqrt(k / m_eq), k = `SpringResult::stiffness`, m_eq the
///   relative equivalent mass of its two points along its direction (eqm.hpp); xi the damping
///   ratio, or c / (2 sqrt(k m_eq)) with c the slope of the dashpot table at the current stroke
///   rate; with friction and kskn > 0 also the tangential mode sqrt(kskn k / m_min), m_min the
///   smallest equivalent mass over all directions; h = critical_step(omega, xi) (eqm.hpp) of the
///   limiting mode;
/// - a torsion spring: per angle omega = sqrt(k_a / J_a), k_a the slope of its torque table at
///   the current angle (a cone: of the first coupled law at the radial angle), J_a the relative
///   effective inertia about the axis, 1 / (n^T (J1^-1 + J2^-1) n); the limiting angle;
/// - a body: omega = sqrt(sum of omega^2 over the springs and torsion-spring angles acting on
///   it), xi = the largest of their damping ratios. For point masses on springs omega_b^2 is the
///   column sum of M^-1 K at the body, so the largest omega_b bounds the largest frequency
///   (Gershgorin); it is exact for springs in parallel to fixed points and for two equal masses
///   on one spring, and conservative when translational and rotational springs share a body;
/// - the global estimate is the minimum over springs, torsion springs and bodies.
/// A spring that is off (inactive, undone, being unloaded by a rule, or with zero tangent
/// stiffness: outside its table, or an open contact element) gives no limit. With
/// `set_adaptive(factor)` each step of `run` is min(h, factor x the global estimate), h the
/// step given to `run`; the estimate is that of the previous step's state, so a spring that
/// switches on (a contact element closing) limits the step from the next step on.
///
/// `critical_bound` (Parmec's CRITICAL) estimates each spring at the stiffest state it can
/// reach instead: k the largest slope of its force table (and of its unloading curve), c the
/// largest slope of its dashpot table, k_a the largest slope of each torsion table, every spring
/// and torsion spring counted (on or off, dormant included); along the spring's current
/// direction, and, while that is undefined (the two points of a zero-length spring coincide),
/// along the stiffest one (m_min). A step below it stays stable wherever the strokes go.
///
/// ## References
/// - H. C. Andersen, Rattle: a "velocity" version of the Shake algorithm for molecular dynamics
///   calculations, J. Comput. Phys. 52 (1983) 24-34.
/// - J.-P. Ryckaert, G. Ciccotti, H. J. C. Berendsen, Numerical integration of the cartesian
///   equations of motion of a system with constraints: molecular dynamics of n-alkanes,
///   J. Comput. Phys. 23 (1977) 327-341 (SHAKE).
/// - T. Belytschko, W. K. Liu, B. Moran, Nonlinear Finite Elements for Continua and Structures,
///   Wiley 2000, ch. 6 (critical step, Gershgorin bound).

#include <grain/bodies/eqm.hpp>
#include <grain/bodies/mesh.hpp>
#include <grain/bodies/rigid_body.hpp>
#include <grain/bodies/spring.hpp>
#include <grain/bodies/torsion_spring.hpp>
#include <grain/bodies/unspring.hpp>
#include <grain/conditions/conditions.hpp>
#include <grain/core/error.hpp>
#include <grain/core/observer.hpp>
#include <grain/core/time_function.hpp>
#include <grain/core/vector.hpp>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace grain::bodies {

/// The fixed world as a body index: a point on it does not move.
inline constexpr long world = -1;

/// Where a translational spring is attached.
struct SpringLink {
  long body1 = 0;               ///< body of point 1
  long body2 = world;           ///< body of point 2 (or of the plane), or `world`
  Vec3 local1 = Vec3::Zero();   ///< point 1 in body 1's local frame [m]
  Vec3 local2 = Vec3::Zero();   ///< point 2 in body 2's local frame (world: world point) [m]
  Vec3 normal2 = Vec3::UnitZ(); ///< plane normal in body 2's reference frame (world: world)
};

/// Where a torsion spring is attached.
struct TorsionLink {
  long body1 = 0;
  long body2 = world;
  TorsionFrames frames{};
  bool has_reference = false;    ///< a reference point was given
  Vec3 reference = Vec3::Zero(); ///< the reference point in body 1's local frame [m]
};

/// A ball joint: point local1 of body 1 coincides with point local2 of body 2 (or a fixed point).
struct BallJoint {
  long body1 = 0;
  long body2 = world;
  Vec3 local1 = Vec3::Zero(); ///< in body 1's local frame [m]
  Vec3 local2 = Vec3::Zero(); ///< in body 2's local frame (world: the fixed point) [m]
};

/// What the joint solve gave in the last step.
struct JointResult {
  Vec3 point = Vec3::Zero();    ///< joint point on body 1 (world) [m]
  Vec3 reaction = Vec3::Zero(); ///< mean joint force on body 1 over the step [N]
  double gap = 0.0;             ///< abs(p1 - p2) [m]

  template <class Archive>
  void serialize(Archive& ar) {
    ar(point, reaction, gap);
  }
};

/// One critical-step estimate, as a record of Parmec's CRITICAL list.
struct CriticalStep {
  double step = std::numeric_limits<double>::infinity(); ///< h [s]
  std::size_t index = 0;                                 ///< spring, torsion spring or body index
  double omega = 0.0;                                    ///< circular frequency [rad/s]
  double damping_ratio = 0.0;                            ///< xi [-]
};

/// The n lowest per-spring and per-body estimates, each in ascending order of the step.
struct CriticalSteps {
  std::vector<CriticalStep> springs;
  std::vector<CriticalStep> bodies;
};

namespace detail {

/// The unit direction of a spring for the positions p1, p2 and plane normal n (zero if
/// undefined); the same as `evaluate` of spring.hpp computes.
inline Vec3 spring_direction(const SpringParams& p, const SpringKinematics& k) {
  const Vec3 d = k.p2 - k.p1;
  switch (p.geometry) {
  case SpringGeometry::point_to_point: {
    const double n = d.norm();
    return n > 0.0 ? Vec3(d / n) : Vec3(Vec3::Zero());
  }
  case SpringGeometry::constant_direction:
    return p.direction.normalized();
  case SpringGeometry::planar: {
    const Vec3 c = p.direction.normalized();
    const Vec3 w = d - c.dot(d) * c;
    const double n = w.norm();
    return n > 0.0 ? Vec3(w / n) : Vec3(Vec3::Zero());
  }
  case SpringGeometry::point_to_plane:
    return -k.normal.normalized();
  }
  return Vec3::Zero();
}

/// The n smallest records by step, ascending (ties by index).
inline std::vector<CriticalStep> lowest(std::vector<CriticalStep> all, std::size_t n) {
  const auto less = [](const CriticalStep& a, const CriticalStep& b) {
    return a.step < b.step || (a.step == b.step && a.index < b.index);
  };
  n = std::min(n, all.size());
  std::partial_sort(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(n), all.end(), less);
  all.resize(n);
  return all;
}

/// [r]x, the matrix of r x.
inline Eigen::Matrix3d skew(const Vec3& r) {
  Eigen::Matrix3d m;
  m << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
  return m;
}

} // namespace detail

/// Rigid bodies with springs, torsion springs, ball joints and unspring rules. No virtual
/// functions; objects are addressed by the indices their `add_*` returns.
class BodySystem {
public:
  BodySystem() = default;
  /// A system under the gravitational acceleration g(t) [m/s^2].
  explicit BodySystem(VectorTimeFunction<3> gravity) : gravity_(std::move(gravity)) {}

  // ---------------------------------------------------------------- set-up
  /// Adds a body (validated by `RigidBodies::add`); returns its index.
  std::size_t add_body(const RigidBody& b) {
    initialized_ = false;
    const std::size_t i = bodies_.add(b);
    external_force_.resize(bodies_.size(), Vec3::Zero());
    external_torque_.resize(bodies_.size(), Vec3::Zero());
    return i;
  }

  /// Adds the body of a meshed particle (mesh_body) and keeps its boundary surface with the face
  /// colours for output (mesh_surface); returns the body index. Validates the mesh and the
  /// colours before anything is added.
  std::size_t add_mesh_body(const Mesh& mesh, const FaceColors& colors = {},
                            const Vec3& velocity = Vec3::Zero(), const Vec3& omega = Vec3::Zero(),
                            const std::string& name = "mesh") {
    MeshSurface surface = bodies::mesh_surface(mesh, colors, name);
    const std::size_t b = add_body(mesh_body(mesh, velocity, omega, name));
    meshes_.emplace_back(b, std::move(surface));
    return b;
  }
  /// Number of bodies added by add_mesh_body.
  std::size_t mesh_count() const noexcept { return meshes_.size(); }
  /// Body index of mesh k (k-th call of add_mesh_body).
  std::size_t mesh_body_index(std::size_t k) const { return meshes_.at(k).first; }
  /// Boundary surface of mesh k, in its body's local coordinates.
  const MeshSurface& mesh_surface(std::size_t k) const { return meshes_.at(k).second; }

  /// Adds a translational spring between point1 of body1 and point2 of body2 (`world`: a fixed
  /// point), both in world coordinates now [m]; for `SpringGeometry::point_to_plane`, point2 is
  /// a point of the plane and `normal` its normal (world, non-zero; carried by body 2), which
  /// must not be given for the other geometries. Validates the parameters (spring.hpp) and
  /// returns the spring's index. Throws InputError for an unknown body, body1 = world or
  /// body1 = body2, non-finite points, or a missing or zero plane normal. Coincident points of a
  /// point-to-point or planar spring (a zero-length spring, as Parmec allows) leave its
  /// direction undefined: it acts once they separate.
  std::size_t add_spring(SpringParams p, long body1, const Vec3& point1, long body2,
                         const Vec3& point2, const Vec3& normal = Vec3::Zero()) {
    if (p.name == "SPRING") p.name += " " + std::to_string(spring_links_.size());
    const std::string& obj = p.name;
    require_pair(obj, body1, body2);
    detail::require_finite_vec(obj, "point1", point1);
    detail::require_finite_vec(obj, "point2", point2);
    const bool plane = p.geometry == SpringGeometry::point_to_plane;
    detail::require_finite_vec(obj, "normal", normal);
    if (plane)
      grain::detail::require(normal.norm() > 0.0, obj, "|normal|", normal.norm(),
                             "(0, inf) (the plane normal of a point-to-plane spring)");
    else
      grain::detail::require(normal.norm() == 0.0, obj, "|normal|", normal.norm(),
                             "0 (a normal is given for the point-to-plane geometry only)");
    SpringKinematics k;
    k.p1 = point1;
    k.p2 = point2;
    k.normal = plane ? Vec3(normal.normalized()) : Vec3(Vec3::UnitZ());
    validate(p);
    SpringLink l;
    l.body1 = body1;
    l.body2 = body2;
    const auto b1 = static_cast<std::size_t>(body1);
    l.local1 = to_local(bodies_, b1, point1);
    if (body2 == world) {
      l.local2 = point2;
      l.normal2 = k.normal;
    } else {
      const auto b2 = static_cast<std::size_t>(body2);
      l.local2 = to_local(bodies_, b2, point2);
      l.normal2 = rotation(bodies_, b2).transpose() * k.normal;
    }
    SpringState st = init_spring(p, k, time_);
    spring_params_.push_back(std::move(p));
    spring_states_.push_back(st);
    spring_links_.push_back(l);
    spring_results_.emplace_back();
    spring_masses_.push_back(0.0);
    initialized_ = false;
    return spring_links_.size() - 1;
  }

  /// Adds a torsion spring between body1 and body2 (`world`: a fixed frame) with the world
  /// directions zdir (yaw) and xdir (roll) now (torsion_spring.hpp); returns its index. Throws
  /// InputError for an unknown body, body1 = world, body1 = body2 or bad parameters.
  std::size_t add_torsion_spring(TorsionSpringParams p, long body1, long body2, const Vec3& zdir,
                                 const Vec3& xdir,
                                 const std::optional<Vec3>& reference = std::nullopt) {
    if (p.name == "TORSION_SPRING") p.name += " " + std::to_string(torsion_links_.size());
    const std::string& obj = p.name;
    require_pair(obj, body1, body2);
    validate(p);
    TorsionLink l;
    l.body1 = body1;
    l.body2 = body2;
    l.frames = torsion_frames(orientation_of(body1), orientation_of(body2), zdir, xdir, obj);
    if (reference) {
      detail::require_finite_vec(obj, "reference point", *reference);
      l.has_reference = true;
      l.reference = to_local(bodies_, static_cast<std::size_t>(body1), *reference);
    }
    torsion_params_.push_back(std::move(p));
    torsion_links_.push_back(l);
    torsion_results_.emplace_back();
    initialized_ = false;
    return torsion_links_.size() - 1;
  }

  /// Adds a ball joint at the world point `point` [m] between body1 and body2 (default `world`:
  /// body1 is pinned at `point`); returns its index. Throws InputError for an unknown body,
  /// body1 = world, body1 = body2 or a non-finite point.
  std::size_t add_ball_joint(long body1, const Vec3& point, long body2 = world) {
    const std::string obj = "BALL_JOINT " + std::to_string(joints_.size());
    require_body(obj, "body1", body1, false);
    require_body(obj, "body2", body2, true);
    grain::detail::require(body1 != body2, obj, "body2", body2,
                           "a body other than body1 = " + std::to_string(body1) +
                               ", or world (-1) (a joint references two different bodies)");
    detail::require_finite_vec(obj, "point", point);
    BallJoint j;
    j.body1 = body1;
    j.body2 = body2;
    j.local1 = to_local(bodies_, static_cast<std::size_t>(body1), point);
    j.local2 = body2 == world ? point : to_local(bodies_, static_cast<std::size_t>(body2), point);
    joints_.push_back(j);
    JointResult r;
    r.point = point;
    joint_results_.push_back(r);
    return joints_.size() - 1;
  }

  /// Adds an unspring rule over the springs added so far (validated by `Unspring`); returns its
  /// index. It is checked once a step, after the springs are evaluated.
  std::size_t add_unspring(UnspringRule rule) {
    if (rule.name == "UNSPRING") rule.name += " " + std::to_string(unsprings_.size());
    // the springs a rule activates are dormant ones, other than those it undoes (numbers out
    // of range are reported by Unspring)
    for (std::size_t j = 0; j < rule.activate.size(); ++j) {
      const std::size_t s = rule.activate[j];
      if (s >= spring_params_.size()) continue;
      const std::string what = "activate[" + std::to_string(j) + "]";
      grain::detail::require(spring_params_[s].inactive, rule.name, what.c_str(), s,
                             "a dormant spring (SpringParams::inactive)");
      grain::detail::require(
          std::find(rule.msprings.begin(), rule.msprings.end(), s) == rule.msprings.end(),
          rule.name, what.c_str(), s, "a spring not in msprings (the rule undoes those)");
    }
    unsprings_.emplace_back(std::move(rule), spring_links_.size());
    return unsprings_.size() - 1;
  }

  /// The gravitational acceleration g(t) [m/s^2].
  void set_gravity(VectorTimeFunction<3> g) {
    gravity_ = std::move(g);
    initialized_ = false;
  }
  /// Replaces g(t) without re-evaluating the loads of the current configuration: the next
  /// first kick uses the loads of the last evaluation, the next evaluation the new gravity (what a
  /// simulation does when its gravity changes between runs; coupling.hpp).
  void replace_gravity(VectorTimeFunction<3> g) { gravity_ = std::move(g); }

  /// Global damping as Parmec's DAMPING command, with coefficients d_v(t), d_w(t) [1/s] >= 0 per
  /// world axis: F -= m (d_v . v) and T -= J_world (d_w . omega) (component-wise products),
  /// opposing the motion. A negative coefficient is an InputError, raised here for the current
  /// time and by a step that meets one.
  void set_damping(VectorTimeFunction<3> linear, VectorTimeFunction<3> angular) {
    require_damping(linear, angular);
    damping_linear_ = std::move(linear);
    damping_angular_ = std::move(angular);
    damped_ = true;
    initialized_ = false;
  }

  /// Restrains body b (Parmec's RESTRAIN): its velocity has no component along the `linear`
  /// directions and its spatial angular velocity none about the `angular` axes (world
  /// coordinates; up to 3 independent directions each, any length). The reaction is the
  /// constraint's: a linear direction removes that velocity component, an angular axis applies
  /// the torque about it that keeps the rotation about it zero (for a body whose inertia is not
  /// isotropic this changes the free components too, as a real bearing does). Replaces an
  /// earlier restraint of b; empty lists remove it. Joints, springs and critical steps see the
  /// restrained body through its constrained inverse mass. Throws InputError for an unknown
  /// body, more than 3, non-finite, zero or dependent directions.
  void restrain(std::size_t b, const std::vector<Vec3>& linear,
                const std::vector<Vec3>& angular = {}) {
    const std::string obj = "BodySystem::restrain (body " + std::to_string(b) + ")";
    require_body(obj, "body", static_cast<long>(b), false);
    const auto lin = grain::detail::orthonormal<3>(linear, obj, "linear");
    const auto ang = grain::detail::orthonormal<3>(angular, obj, "angular");
    BodyControl& c = control(b);
    c.linear = lin;
    c.angular = ang;
    enforce_now(b);
    initialized_ = false;
  }

  /// Prescribes the motion of body b (Parmec's PRESCRIBE): a linear history [m/s or m/s^2] of
  /// its centre and an angular history [rad/s or rad/s^2] of its spatial angular velocity, each
  /// optional, read as velocities or accelerations by `kind` ("vv", "va", "av", "aa"; linear
  /// first). Each world component is prescribed while its function is active and follows the
  /// dynamics otherwise; prescribed components override the restraints (a restrained direction
  /// then restrains what the prescribed axes leave free). Velocity histories set the velocity
  /// now. Replaces an earlier history of the same part; `std::nullopt` keeps it. Throws
  /// InputError for an unknown body, no history, or a bad kind.
  void prescribe_motion(std::size_t b, std::optional<VectorTimeFunction<3>> linear,
                        std::optional<VectorTimeFunction<3>> angular,
                        std::string_view kind = "vv") {
    const std::string obj = "BodySystem::prescribe_motion (body " + std::to_string(b) + ")";
    require_body(obj, "body", static_cast<long>(b), false);
    const auto [lk, ak] = motion_kinds(kind, obj);
    if (!linear && !angular)
      throw InputError(obj + ": linear = angular = none is invalid; valid: at least one history");
    BodyControl& c = control(b);
    if (linear) {
      c.lin_motion = std::move(linear);
      c.lin_kind = lk;
    }
    if (angular) {
      c.ang_motion = std::move(angular);
      c.ang_kind = ak;
    }
    enforce_now(b);
    initialized_ = false;
  }

  /// The restrained directions (linear, angular; orthonormal) of body b; empty if none.
  std::pair<std::vector<Vec3>, std::vector<Vec3>> restraints(std::size_t b) const {
    const long k = control_index(b);
    if (k < 0) return {};
    return {controls_[static_cast<std::size_t>(k)].linear,
            controls_[static_cast<std::size_t>(k)].angular};
  }

  /// Adaptive stepping in `run` and `steps`: each step is min(h, factor x critical()), h the step
  /// given to them. factor in (0, 1]; 0 switches it off (the default).
  void set_adaptive(double factor) {
    grain::detail::require(std::isfinite(factor) && factor >= 0.0 && factor <= 1.0, "BodySystem",
                           "adaptive factor", factor,
                           "[0, 1] (0: off; else the fraction of the critical step)");
    adaptive_ = factor;
  }
  double adaptive() const noexcept { return adaptive_; }

  /// The joint gap accepted after the drift, relative to the largest joint arm [-], and the
  /// largest number of extra drifts made to reach it (see the file comment).
  double joint_tolerance = 1e-12;
  int joint_iterations = 10;

  // ---------------------------------------------------------------- running
  /// Evaluates the forces of the current configuration (done by the first step; call it to get
  /// spring results or critical steps before running).
  void initialize() {
    compute_forces(0.0);
    initialized_ = true;
  }

  /// A load [N], [N m] (torque about the centre) on body i, world components, added to its
  /// forces in every evaluation until it is set again (the contact forces of a body that is
  /// also a particle of a simulation arrive this way, see coupling.hpp). Throws InputError for an
  /// unknown body or non-finite components.
  void set_external_load(std::size_t i, const Vec3& force, const Vec3& torque = Vec3::Zero()) {
    require_body("BodySystem::set_external_load", "body", static_cast<long>(i), false);
    if (!force.allFinite() || !torque.allFinite())
      grain::detail::require(false, "BodySystem::set_external_load", "load", "(non-finite)",
                             "finite components [N], [N m]");
    external_force_.resize(bodies_.size(), Vec3::Zero()); // bodies added through bodies()
    external_torque_.resize(bodies_.size(), Vec3::Zero());
    external_force_[i] = force;
    external_torque_[i] = torque;
  }
  /// The external load of body i (set_external_load) [N], [N m]; zero if none was set.
  std::pair<Vec3, Vec3> external_load(std::size_t i) const {
    require_body("BodySystem::external_load", "body", static_cast<long>(i), false);
    if (i >= external_force_.size()) return {Vec3::Zero(), Vec3::Zero()};
    return {external_force_[i], external_torque_[i]};
  }

  /// Sets the time [s] (the start of a run, or the clock of a simulation the system is coupled
  /// to). Throws InputError for a non-finite time.
  void set_time(double t) {
    grain::detail::require(std::isfinite(t), "BodySystem::set_time", "t", t, "finite [s]");
    time_ = t;
  }

  /// One step of length h [s] (see the file comment). Throws InputError for h not finite and > 0.
  void step(double h) {
    begin_step(h);
    finish_step(h);
  }

  /// Stages 1-3 of a step of length h [s]: first kick, joint impulses and drift, t += h. A
  /// coupled simulation evaluates its contact forces between `begin_step` and `finish_step`
  /// (coupling.hpp); `step` calls both.
  void begin_step(double h) {
    grain::detail::require_positive("BodySystem::step", "h", h);
    grain::detail::require(std::isfinite(joint_tolerance) && joint_tolerance > 0.0, "BodySystem",
                           "joint_tolerance", joint_tolerance, "(0, inf) (relative gap)");
    grain::detail::require(joint_iterations >= 0, "BodySystem", "joint_iterations",
                           joint_iterations, "[0, inf)");
    if (!initialized_) initialize();
    save_controls(h);
    kick(bodies_, h);
    enforce_controls(h, Stage::mid);
    if (joints_.empty())
      drift(h);
    else
      drift_with_joints(h);
    time_ += h;
  }

  /// Stages 4-7 of the step of length h begun by `begin_step`: forces at t + h (with the
  /// external loads), second kick, joint impulses, unspring rules.
  void finish_step(double h) {
    compute_forces(h);
    kick(bodies_, h);
    enforce_controls(h, Stage::end);
    if (!joints_.empty()) {
      factor_joints();
      impulse_end_.assign(joints_.size(), Vec3::Zero());
      apply_joint_impulses(-joint_velocities(), impulse_end_);
      for (std::size_t j = 0; j < joints_.size(); ++j) {
        const auto [p1, p2] = joint_points(j);
        joint_results_[j].point = p1;
        joint_results_[j].gap = (p1 - p2).norm();
        joint_results_[j].reaction = (impulse_half_[j] + impulse_end_[j]) / h;
      }
    }
    bool fired = false;
    for (auto& u : unsprings_)
      fired |= u.update(std::span<const SpringResult>(spring_results_),
                        std::span<SpringState>(spring_states_))
                   .fired;
    if (fired) {
      // the undone springs act no more from the next kick on: the loads of the new spring
      // states (the springs' own state advanced once this step, so it is kept, and so are the
      // results of the step, which the rule judged)
      // and were reported (results)
      const auto states = spring_states_;
      const auto results = spring_results_;
      const auto torsion = torsion_results_;
      compute_forces(h);
      spring_states_ = states;
      spring_results_ = results;
      torsion_results_ = torsion;
    }
    h_ = h;
    ++steps_;
  }

  /// Runs n steps of h [s] (with adaptive stepping: of at most h), calling each observer after
  /// every step (`start(sys)` before and `finish(sys)` after the run, if it has them; see
  /// io::every).
  template <class... Observers>
  void steps(long n, double h, Observers&&... obs) {
    grain::detail::require_positive("BodySystem::steps", "h", h);
    grain::detail::require(n >= 0, "BodySystem::steps", "n", n, "[0, inf) steps");
    if (!initialized_) initialize();
    h_ = h;
    (grain::detail::start_observer(obs, *this), ...);
    for (long k = 0; k < n; ++k) {
      step(next_step(h));
      (obs(*this), ...);
    }
    (grain::detail::finish_observer(obs, *this), ...);
  }

  /// Runs for `duration` [s] with steps of h [s]: without adaptive stepping, ceil(duration / h)
  /// steps of h (the end rounded up to a whole step, as Simulation::run); with it, steps of
  /// min(h, factor x critical()), the last one shortened to end at t + duration.
  template <class... Observers>
  void run(double duration, double h, Observers&&... obs) {
    grain::detail::require_non_negative("BodySystem::run", "duration", duration);
    grain::detail::require_positive("BodySystem::run", "h", h);
    if (!initialized_) initialize();
    if (adaptive_ == 0.0) {
      const double n = std::ceil(duration / h - 1e-9);
      grain::detail::require(n < 1e15, "BodySystem::run", "duration / h", duration / h,
                             "[0, 1e15) steps");
      steps(static_cast<long>(n), h, std::forward<Observers>(obs)...);
      return;
    }
    const double end = time_ + duration;
    h_ = h;
    (grain::detail::start_observer(obs, *this), ...);
    while (time_ < end - 1e-12 * h) {
      const double hk = std::min(next_step(h), end - time_);
      step(hk);
      (obs(*this), ...);
    }
    (grain::detail::finish_observer(obs, *this), ...);
  }

  // ---------------------------------------------------------------- state
  double time() const noexcept { return time_; }
  /// The last step length [s] (the nominal h of the run before its first step).
  double time_step() const noexcept { return h_; }
  long step_count() const noexcept { return steps_; }

  RigidBodies& bodies() noexcept { return bodies_; }
  const RigidBodies& bodies() const noexcept { return bodies_; }

  std::size_t spring_count() const noexcept { return spring_links_.size(); }
  std::size_t torsion_spring_count() const noexcept { return torsion_links_.size(); }
  std::size_t joint_count() const noexcept { return joints_.size(); }
  std::size_t unspring_count() const noexcept { return unsprings_.size(); }

  const SpringParams& spring_params(std::size_t i) const { return spring_params_.at(i); }
  const SpringState& spring_state(std::size_t i) const { return spring_states_.at(i); }
  const SpringLink& spring_link(std::size_t i) const { return spring_links_.at(i); }
  /// The spring's result of its last evaluation (forces at the end of the last step).
  const SpringResult& spring_result(std::size_t i) const { return spring_results_.at(i); }
  std::span<const SpringResult> spring_results() const noexcept { return spring_results_; }
  /// The equivalent mass used for the spring's damping ratio in its last evaluation [kg].
  double spring_mass(std::size_t i) const { return spring_masses_.at(i); }
  /// World positions of the spring's points 1 and 2 now (the plane: point 1 and the plane's
  /// point) [m].
  std::pair<Vec3, Vec3> spring_points(std::size_t i) const {
    const SpringLink& l = spring_links_.at(i);
    return {to_world(bodies_, static_cast<std::size_t>(l.body1), l.local1), point2_of(l)};
  }

  const TorsionSpringParams& torsion_params(std::size_t i) const { return torsion_params_.at(i); }
  const TorsionLink& torsion_link(std::size_t i) const { return torsion_links_.at(i); }
  const TorsionResult& torsion_result(std::size_t i) const { return torsion_results_.at(i); }
  /// Where torsion spring i is shown (output only) [m]: its reference point, which moves with
  /// body 1, if one was given, else the midpoint of the two bodies' centres (body 1's centre
  /// for a spring to the world).
  Vec3 torsion_point(std::size_t i) const {
    const TorsionLink& l = torsion_links_.at(i);
    const auto b1 = static_cast<std::size_t>(l.body1);
    if (l.has_reference) return to_world(bodies_, b1, l.reference);
    if (l.body2 == world) return bodies_.position[b1];
    return 0.5 * (bodies_.position[b1] + bodies_.position[static_cast<std::size_t>(l.body2)]);
  }

  const BallJoint& joint(std::size_t i) const { return joints_.at(i); }
  const JointResult& joint_result(std::size_t i) const { return joint_results_.at(i); }
  /// World positions of the joint's point on body 1 and on body 2 (or the fixed point) now [m].
  std::pair<Vec3, Vec3> joint_points(std::size_t i) const {
    const BallJoint& j = joints_.at(i);
    const Vec3 p1 = to_world(bodies_, static_cast<std::size_t>(j.body1), j.local1);
    const Vec3 p2 = j.body2 == world
                        ? j.local2
                        : to_world(bodies_, static_cast<std::size_t>(j.body2), j.local2);
    return {p1, p2};
  }

  const Unspring& unspring(std::size_t i) const { return unsprings_.at(i); }

  /// Visits the run state (bodies' motion and loads, spring states and results, unspring rules,
  /// clock) with a checkpoint archive (io/checkpoint.hpp); the set-up (bodies, springs, torsion
  /// springs, joints, rules, gravity, damping) is made again by the program before reading.
  /// Throws InputError when reading a state of a system with other counts.
  template <class Archive>
  void serialize(Archive& ar) {
    const std::array<std::uint64_t, 5> have{bodies_.size(), spring_links_.size(),
                                            torsion_links_.size(), joints_.size(),
                                            unsprings_.size()};
    std::array<std::uint64_t, 5> n = have;
    ar(n);
    if (n != have) {
      const auto text = [](const std::array<std::uint64_t, 5>& c) {
        return std::to_string(c[0]) + " bodies, " + std::to_string(c[1]) + " springs, " +
               std::to_string(c[2]) + " torsion springs, " + std::to_string(c[3]) + " joints, " +
               std::to_string(c[4]) + " unspring rules";
      };
      throw InputError("checkpoint: body system with " + text(n) + " is invalid; valid: " +
                       text(have) + " (the system this program makes, in the same order)");
    }
    external_force_.resize(bodies_.size(), Vec3::Zero());
    external_torque_.resize(bodies_.size(), Vec3::Zero());
    ar(bodies_.position, bodies_.velocity, bodies_.omega, bodies_.orientation, bodies_.force,
       bodies_.torque, external_force_, external_torque_);
    // a spring being unloaded by a rule points to the rule's curve: saved as (rule, curve)
    std::vector<SpringState> states = spring_states_;
    std::vector<std::pair<std::int64_t, std::int64_t>> curve(states.size(), {-1, -1});
    if constexpr (!Archive::reading) {
      for (std::size_t s = 0; s < states.size(); ++s) {
        for (std::size_t u = 0; u < unsprings_.size() && states[s].rule_unload; ++u) {
          const auto& unload = unsprings_[u].rule().unload;
          for (std::size_t k = 0; k < unload.size(); ++k)
            if (&unload[k].second == states[s].rule_unload)
              curve[s] = {static_cast<std::int64_t>(u), static_cast<std::int64_t>(k)};
        }
        states[s].rule_unload = nullptr;
      }
    }
    ar(states, curve);
    if constexpr (Archive::reading) {
      for (std::size_t s = 0; s < states.size(); ++s) {
        const auto [u, k] = curve[s];
        if (u < 0) continue;
        if (static_cast<std::size_t>(u) >= unsprings_.size() ||
            k >= static_cast<std::int64_t>(
                     unsprings_[static_cast<std::size_t>(u)].rule().unload.size()))
          throw InputError("checkpoint: unloading curve of spring " + std::to_string(s) +
                           " is invalid; valid: a curve of an unspring rule of this system");
        states[s].rule_unload = &unsprings_[static_cast<std::size_t>(u)]
                                     .rule()
                                     .unload[static_cast<std::size_t>(k)]
                                     .second;
      }
      spring_states_ = std::move(states);
    }
    ar(spring_results_, spring_masses_, torsion_results_, joint_results_);
    for (auto& u : unsprings_)
      ar(u);
    ar(time_, h_, steps_, initialized_, joint_drifts_);
  }

  /// The number of drifts made in the last step to close the joint gaps (1 without joints).
  int joint_drifts() const noexcept { return joints_.empty() ? 1 : joint_drifts_; }

  /// Gravity g(t) at the current time [m/s^2].
  Vec3 gravity() const { return gravity_(time_); }

  /// Sum of the bodies' kinetic energies [J].
  double kinetic_energy() const {
    double e = 0.0;
    for (std::size_t i = 0; i < bodies_.size(); ++i)
      e += grain::bodies::kinetic_energy(bodies_, i);
    return e;
  }
  /// Gravitational potential energy -sum m g(t) . x [J] (zero at the origin).
  double potential_energy() const {
    const Vec3 g = gravity_(time_);
    double e = 0.0;
    for (std::size_t i = 0; i < bodies_.size(); ++i)
      e -= bodies_.mass[i] * g.dot(bodies_.position[i]);
    return e;
  }

  // ---------------------------------------------------------------- critical steps
  /// Per-spring estimates of every spring that is on, in index order (see the file comment);
  /// `bound`: at the stiffest state of every spring (critical_bound).
  std::vector<CriticalStep> spring_critical_steps(bool bound = false) {
    if (!initialized_) initialize();
    std::vector<CriticalStep> out;
    for (std::size_t i = 0; i < spring_links_.size(); ++i) {
      const CriticalStep c = spring_estimate(i, bound);
      if (std::isfinite(c.step)) out.push_back(c);
    }
    return out;
  }
  /// Per-torsion-spring estimates of every torsion spring with a stiff angle, in index order;
  /// `bound`: at the largest slopes of their tables.
  std::vector<CriticalStep> torsion_critical_steps(bool bound = false) {
    if (!initialized_) initialize();
    std::vector<CriticalStep> out;
    for (std::size_t i = 0; i < torsion_links_.size(); ++i) {
      CriticalStep c = torsion_estimate(i, nullptr, bound);
      if (std::isfinite(c.step)) out.push_back(c);
    }
    return out;
  }
  /// Per-body estimates of every body with a spring that is on, in index order; `bound`: from
  /// the bounds of the springs.
  std::vector<CriticalStep> body_critical_steps(bool bound = false) {
    if (!initialized_) initialize();
    const std::size_t n = bodies_.size();
    std::vector<double> w2(n, 0.0), xi(n, 0.0);
    const auto add = [&](long b, double omega, double ratio) {
      if (b == world) return;
      const auto i = static_cast<std::size_t>(b);
      w2[i] += omega * omega;
      xi[i] = std::max(xi[i], ratio);
    };
    for (std::size_t s = 0; s < spring_links_.size(); ++s) {
      const CriticalStep c = spring_estimate(s, bound);
      if (!std::isfinite(c.step)) continue;
      add(spring_links_[s].body1, c.omega, c.damping_ratio);
      add(spring_links_[s].body2, c.omega, c.damping_ratio);
    }
    for (std::size_t s = 0; s < torsion_links_.size(); ++s) {
      std::array<CriticalStep, 3> angles;
      torsion_estimate(s, &angles, bound);
      for (const CriticalStep& c : angles) {
        if (!std::isfinite(c.step)) continue;
        add(torsion_links_[s].body1, c.omega, c.damping_ratio);
        add(torsion_links_[s].body2, c.omega, c.damping_ratio);
      }
    }
    std::vector<CriticalStep> out;
    for (std::size_t i = 0; i < n; ++i) {
      if (w2[i] <= 0.0) continue;
      const double omega = std::sqrt(w2[i]);
      out.push_back({critical_step(omega, xi[i]), i, omega, xi[i]});
    }
    return out;
  }

  /// The n_springs lowest per-spring and n_bodies lowest per-body estimates, ascending: the
  /// lists of Parmec's CRITICAL(perspring, perparticle).
  CriticalSteps critical(std::size_t n_springs, std::size_t n_bodies) {
    return {detail::lowest(spring_critical_steps(), n_springs),
            detail::lowest(body_critical_steps(), n_bodies)};
  }
  /// The n lowest per-torsion-spring estimates, ascending.
  std::vector<CriticalStep> critical_torsion(std::size_t n) {
    return detail::lowest(torsion_critical_steps(), n);
  }
  /// The n_springs lowest per-spring and n_bodies lowest per-body bounds (critical_bound()),
  /// ascending.
  CriticalSteps critical_bound(std::size_t n_springs, std::size_t n_bodies) {
    return {detail::lowest(spring_critical_steps(true), n_springs),
            detail::lowest(body_critical_steps(true), n_bodies)};
  }
  /// The global estimate at the stiffest state of every spring and torsion spring [s] (see the
  /// file comment): Parmec's CRITICAL. Infinity if no spring can limit the step.
  double critical_bound() { return critical(true); }

  /// The global estimate [s]: the minimum over springs, torsion springs and bodies (infinity if
  /// no spring is on); `bound`: critical_bound().
  double critical(bool bound = false) {
    double h = std::numeric_limits<double>::infinity();
    if (damped_) {
      // v <- (1 - d h) v per step under global damping d: stable for h < 2 / d
      const double d =
          std::max(damping_linear_(time_).maxCoeff(), damping_angular_(time_).maxCoeff());
      if (d > 0.0) h = 2.0 / d;
    }
    for (const auto& c : spring_critical_steps(bound))
      h = std::min(h, c.step);
    for (const auto& c : torsion_critical_steps(bound))
      h = std::min(h, c.step);
    for (const auto& c : body_critical_steps(bound))
      h = std::min(h, c.step);
    return h;
  }

private:
  void require_body(const std::string& obj, const char* what, long b, bool world_ok) const {
    const bool ok =
        (world_ok && b == world) || (b >= 0 && static_cast<std::size_t>(b) < bodies_.size());
    grain::detail::require(ok, obj, what, b,
                           "[0, " + std::to_string(bodies_.size()) + ")" +
                               (world_ok ? " or world (-1)" : " (a body)"));
  }

  /// Throws InputError unless body1 is a body and body2 another body or the world.
  void require_pair(const std::string& obj, long body1, long body2) const {
    require_body(obj, "body1", body1, false);
    require_body(obj, "body2", body2, true);
    grain::detail::require(body1 != body2, obj, "body2", body2,
                           "a body other than body1 = " + std::to_string(body1) +
                               ", or world (-1)");
  }

  /// Throws InputError if a damping coefficient is negative now.
  void require_damping(const VectorTimeFunction<3>& linear,
                       const VectorTimeFunction<3>& angular) const {
    const double d = std::min(linear(time_).minCoeff(), angular(time_).minCoeff());
    if (!(d >= 0.0))
      throw InputError("BodySystem damping: coefficient = " + grain::detail::to_text(d) +
                       " at t = " + grain::detail::to_text(time_) +
                       " s is invalid; valid range: [0, inf) 1/s");
  }

  Eigen::Quaterniond orientation_of(long b) const {
    return b == world ? Eigen::Quaterniond::Identity()
                      : bodies_.orientation[static_cast<std::size_t>(b)];
  }
  Vec3 omega_of(long b) const {
    return b == world ? Vec3(Vec3::Zero()) : bodies_.omega[static_cast<std::size_t>(b)];
  }
  /// The inverse world inertia of body b as its restraints and prescribed rotation leave it
  /// (zero for world): J^-1 - J^-1 B (B^T J^-1 B)^-1 B^T J^-1, B the constrained axes.
  Eigen::Matrix3d inverse_inertia_of(long b) const {
    if (b == world) return Eigen::Matrix3d::Zero();
    const auto i = static_cast<std::size_t>(b);
    const Eigen::Matrix3d inv = inverse_world_inertia(bodies_, i);
    const long k = control_index(i);
    if (k < 0) return inv;
    const auto basis =
        constrained_axes(controls_[static_cast<std::size_t>(k)], true, time_, nullptr);
    return constrained_inverse(inv, basis);
  }
  /// The inverse mass matrix of body b's centre as its restraints and prescribed motion leave
  /// it (zero for world): (1/m) (1 - B B^T).
  Eigen::Matrix3d inverse_mass_of(long b) const {
    if (b == world) return Eigen::Matrix3d::Zero();
    const auto i = static_cast<std::size_t>(b);
    Eigen::Matrix3d im = bodies_.inv_mass[i] * Eigen::Matrix3d::Identity();
    const long k = control_index(i);
    if (k < 0) return im;
    for (const Vec3& d :
         constrained_axes(controls_[static_cast<std::size_t>(k)], false, time_, nullptr))
      im -= bodies_.inv_mass[i] * d * d.transpose();
    return im;
  }
  /// The inverse-mass matrix of the material point of body b at world point x (zero for world;
  /// restraints and prescribed motion taken into account).
  Eigen::Matrix3d point_k(long b, const Vec3& x) const {
    if (b == world) return Eigen::Matrix3d::Zero();
    const auto i = static_cast<std::size_t>(b);
    if (control_index(i) < 0) return point_inverse_mass(bodies_, i, x);
    const Eigen::Matrix3d rx = detail::skew(x - bodies_.position[i]);
    return inverse_mass_of(b) + rx.transpose() * inverse_inertia_of(b) * rx;
  }

  // ---------------------------------------------------------------- restraints, prescribed motion
  /// The restraints and prescribed motion of one body, and its state at the start of the step.
  struct BodyControl {
    std::size_t body = 0;
    std::vector<Vec3> linear{}, angular{}; ///< restrained directions (orthonormal)
    std::optional<VectorTimeFunction<3>> lin_motion{}, ang_motion{};
    MotionKind lin_kind = MotionKind::velocity, ang_kind = MotionKind::velocity;
    Vec3 v0 = Vec3::Zero(), w0 = Vec3::Zero();   ///< velocities at the start of the step
    Vec3 a = Vec3::Zero(), alpha = Vec3::Zero(); ///< accelerations at mid-step
    std::array<bool, 3> lin_on{}, ang_on{};      ///< prescribed components this step
  };
  enum class Stage { now, mid, end };

  long control_index(std::size_t b) const { return b < control_of_.size() ? control_of_[b] : -1; }
  BodyControl& control(std::size_t b) {
    if (control_of_.size() < bodies_.size()) control_of_.resize(bodies_.size(), -1);
    if (control_of_[b] < 0) {
      control_of_[b] = static_cast<long>(controls_.size());
      controls_.push_back(BodyControl{});
      controls_.back().body = b;
    }
    return controls_[static_cast<std::size_t>(control_of_[b])];
  }

  /// Which world components of a history are prescribed at t.
  static std::array<bool, 3> prescribed(const std::optional<VectorTimeFunction<3>>& f, double t) {
    std::array<bool, 3> on{};
    if (f)
      for (int k = 0; k < 3; ++k)
        on[static_cast<std::size_t>(k)] = f->component_active(k, t);
    return on;
  }

  /// The orthonormal constrained axes of a body's translation (angular = false) or rotation at t:
  /// the prescribed world axes first, then the restrained directions with their parts along the
  /// prescribed axes removed (those that are left). With `targets`, also the target velocity
  /// component along each axis (the prescribed value `values`, 0 for a restrained one).
  static std::vector<Vec3> constrained_axes(const BodyControl& c, bool angular, double t,
                                            std::vector<double>* targets,
                                            const Vec3* values = nullptr,
                                            const std::array<bool, 3>* on_given = nullptr) {
    std::vector<Vec3> basis;
    const std::array<bool, 3> on =
        on_given ? *on_given : prescribed(angular ? c.ang_motion : c.lin_motion, t);
    for (int k = 0; k < 3; ++k)
      if (on[static_cast<std::size_t>(k)]) {
        basis.push_back(Vec3::Unit(k));
        if (targets) targets->push_back(values ? (*values)[k] : 0.0);
      }
    for (const Vec3& d : angular ? c.angular : c.linear) {
      Vec3 u = d;
      for (const Vec3& b : basis)
        u -= u.dot(b) * b;
      const double n = u.norm();
      if (n <= 1e-9) continue;
      basis.push_back(u / n);
      if (targets) targets->push_back(0.0);
    }
    return basis;
  }

  /// inv - inv B (B^T inv B)^-1 B^T inv.
  static Eigen::Matrix3d constrained_inverse(const Eigen::Matrix3d& inv,
                                             const std::vector<Vec3>& basis) {
    if (basis.empty()) return inv;
    if (basis.size() == 3) return Eigen::Matrix3d::Zero();
    Eigen::Matrix<double, 3, Eigen::Dynamic> B(3, static_cast<Eigen::Index>(basis.size()));
    for (std::size_t k = 0; k < basis.size(); ++k)
      B.col(static_cast<Eigen::Index>(k)) = basis[k];
    const Eigen::MatrixXd S = B.transpose() * inv * B;
    const Eigen::Matrix<double, 3, Eigen::Dynamic> IB = inv * B;
    return inv - IB * S.ldlt().solve(IB.transpose());
  }

  /// Sets the constrained components of v (linear: the axes' components to their targets) and
  /// of omega (with the constraint's reaction torque: omega -= J^-1 B (B^T J^-1 B)^-1
  /// (B^T omega - targets)).
  void enforce(std::size_t i, const BodyControl& c, const Vec3& vt, const Vec3& wt,
               const std::array<bool, 3>& lin_on, const std::array<bool, 3>& ang_on) {
    std::vector<double> tl, ta;
    const auto bl = constrained_axes(c, false, 0.0, &tl, &vt, &lin_on);
    for (std::size_t k = 0; k < bl.size(); ++k)
      bodies_.velocity[i] -= (bodies_.velocity[i].dot(bl[k]) - tl[k]) * bl[k];
    const auto ba = constrained_axes(c, true, 0.0, &ta, &wt, &ang_on);
    if (ba.empty()) return;
    Vec3& w = bodies_.omega[i];
    if (ba.size() == 3) {
      Eigen::Matrix3d B;
      for (int k = 0; k < 3; ++k)
        B.col(k) = ba[static_cast<std::size_t>(k)];
      w = B * Vec3(ta[0], ta[1], ta[2]); // B orthonormal: omega = B targets
      return;
    }
    const Eigen::Matrix3d inv = inverse_world_inertia(bodies_, i);
    Eigen::Matrix<double, 3, Eigen::Dynamic> B(3, static_cast<Eigen::Index>(ba.size()));
    Eigen::VectorXd r(static_cast<Eigen::Index>(ba.size()));
    for (std::size_t k = 0; k < ba.size(); ++k) {
      B.col(static_cast<Eigen::Index>(k)) = ba[k];
      r(static_cast<Eigen::Index>(k)) = ba[k].dot(w) - ta[k];
    }
    const Eigen::MatrixXd S = B.transpose() * inv * B;
    w -= inv * B * S.ldlt().solve(r);
  }

  /// The prescribed velocities at a stage of the step from t (mid: t + h/2, end: t + h; now: at
  /// the current time, between runs).
  std::pair<Vec3, Vec3> targets(const BodyControl& c, double h, Stage stage) const {
    Vec3 v = Vec3::Zero(), w = Vec3::Zero();
    const double s = stage == Stage::mid ? 0.5 * h : h;
    const double t = stage == Stage::now ? time_ : time_ + s;
    // an acceleration history keeps the current velocity between runs
    const bool now = stage == Stage::now;
    if (c.lin_motion)
      v = c.lin_kind == MotionKind::velocity ? c.lin_motion->value(t)
          : now                              ? bodies_.velocity[c.body]
                                             : Vec3(c.v0 + s * c.a);
    if (c.ang_motion)
      w = c.ang_kind == MotionKind::velocity ? c.ang_motion->value(t)
          : now                              ? bodies_.omega[c.body]
                                             : Vec3(c.w0 + s * c.alpha);
    return {v, w};
  }

  /// At the start of a step of h: the velocities, which components are prescribed over the
  /// step (those active at mid-step) and the mid-step accelerations.
  void save_controls(double h) {
    const double tm = time_ + 0.5 * h;
    for (BodyControl& c : controls_) {
      c.v0 = bodies_.velocity[c.body];
      c.w0 = bodies_.omega[c.body];
      c.lin_on = prescribed(c.lin_motion, tm);
      c.ang_on = prescribed(c.ang_motion, tm);
      if (c.lin_motion && c.lin_kind == MotionKind::acceleration) c.a = c.lin_motion->value(tm);
      if (c.ang_motion && c.ang_kind == MotionKind::acceleration) c.alpha = c.ang_motion->value(tm);
    }
  }

  /// After a kick of the step begun at time_ (stage mid or end): the prescribed components and
  /// the restraints.
  void enforce_controls(double h, Stage stage) {
    for (const BodyControl& c : controls_) {
      if (stage == Stage::end) {
        // time_ is t + h now: the targets of the step's end
        const auto [v, w] = targets_end(c, h);
        enforce(c.body, c, v, w, c.lin_on, c.ang_on);
      } else {
        const auto [v, w] = targets(c, h, stage);
        enforce(c.body, c, v, w, c.lin_on, c.ang_on);
      }
    }
  }
  std::pair<Vec3, Vec3> targets_end(const BodyControl& c, double h) const {
    Vec3 v = Vec3::Zero(), w = Vec3::Zero();
    if (c.lin_motion)
      v = c.lin_kind == MotionKind::velocity ? c.lin_motion->value(time_) : Vec3(c.v0 + h * c.a);
    if (c.ang_motion)
      w = c.ang_kind == MotionKind::velocity ? c.ang_motion->value(time_)
                                             : Vec3(c.w0 + h * c.alpha);
    return {v, w};
  }

  /// Between runs (restrain, prescribe_motion): the constraints at the current time.
  void enforce_now(std::size_t b) {
    const BodyControl& c = controls_[static_cast<std::size_t>(control_of_[b])];
    const auto [v, w] = targets(c, 0.0, Stage::now);
    enforce(b, c, v, w, prescribed(c.lin_motion, time_), prescribed(c.ang_motion, time_));
  }

  /// Stage 3 without joints' impulses: the drift over h (pure: the forces are cleared). A body
  /// with two or three constrained rotation axes turns at its constant mid-step angular velocity
  /// (exact for rotation about one free axis); one with a single constrained axis makes the free
  /// drift and its angular velocity is constrained again after it.
  void drift(double h) {
    c_drift_q_.resize(controls_.size());
    c_drift_w_.resize(controls_.size());
    for (std::size_t k = 0; k < controls_.size(); ++k) {
      c_drift_q_[k] = bodies_.orientation[controls_[k].body];
      c_drift_w_[k] = bodies_.omega[controls_[k].body];
    }
    clear_forces(bodies_);
    kick_drift(bodies_, h);
    for (std::size_t k = 0; k < controls_.size(); ++k) {
      const BodyControl& c = controls_[k];
      const std::size_t i = c.body;
      const auto n = constrained_axes(c, true, 0.0, nullptr, nullptr, &c.ang_on).size();
      if (n == 0) continue;
      if (n >= 2) {
        const Vec3 w = c_drift_w_[k];
        const double a = w.norm() * h;
        bodies_.orientation[i] =
            a > 0.0 ? Eigen::Quaterniond(Eigen::AngleAxisd(a, w.normalized()) * c_drift_q_[k])
                          .normalized()
                    : c_drift_q_[k];
        bodies_.omega[i] = w;
      } else {
        const auto [v, w] = targets(c, h, Stage::mid);
        enforce(i, c, v, w, c.lin_on, c.ang_on);
      }
    }
  }

  Vec3 point2_of(const SpringLink& l) const {
    return l.body2 == world ? l.local2
                            : to_world(bodies_, static_cast<std::size_t>(l.body2), l.local2);
  }

  SpringKinematics spring_kinematics(const SpringLink& l, bool plane) const {
    SpringKinematics k;
    const auto b1 = static_cast<std::size_t>(l.body1);
    k.p1 = to_world(bodies_, b1, l.local1);
    k.v1 = point_velocity(bodies_, b1, k.p1);
    if (l.body2 == world) {
      k.p2 = l.local2;
      k.normal = l.normal2;
    } else {
      const auto b2 = static_cast<std::size_t>(l.body2);
      k.p2 = to_world(bodies_, b2, l.local2);
      k.normal = rotation(bodies_, b2) * l.normal2;
      k.v2 = point_velocity(bodies_, b2, plane ? k.p1 : k.p2);
    }
    return k;
  }

  /// Forces and torques of the current configuration at time_; h is the step just made (0 at
  /// initialisation).
  void compute_forces(double h) {
    clear_forces(bodies_);
    external_force_.resize(bodies_.size(), Vec3::Zero()); // bodies added through bodies()
    external_torque_.resize(bodies_.size(), Vec3::Zero());
    const Vec3 g = gravity_(time_);
    if (!g.allFinite())
      grain::detail::require(false, "BodySystem", "gravity",
                             "(non-finite) at t = " + grain::detail::to_text(time_),
                             "finite components [m/s^2]");
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      bodies_.force[i] += bodies_.mass[i] * g + external_force_[i];
      bodies_.torque[i] += external_torque_[i];
    }
    if (damped_) {
      const Vec3 dv = damping_linear_(time_), dw = damping_angular_(time_);
      require_damping(damping_linear_, damping_angular_);
      for (std::size_t i = 0; i < bodies_.size(); ++i) {
        bodies_.force[i] -= bodies_.mass[i] * dv.cwiseProduct(bodies_.velocity[i]);
        // -S J S w with S = diag(sqrt(dw)): dissipative for any J (J diag(dw) w is not when dw
        // differs per axis and J is not diagonal); equal to -J (dw w) for isotropic dw
        const Vec3 sw = dw.cwiseSqrt();
        bodies_.torque[i] -=
            sw.cwiseProduct(world_inertia(bodies_, i) * sw.cwiseProduct(bodies_.omega[i]));
      }
    }
    for (std::size_t s = 0; s < spring_links_.size(); ++s) {
      const SpringLink& l = spring_links_[s];
      const SpringParams& p = spring_params_[s];
      const bool plane = p.geometry == SpringGeometry::point_to_plane;
      const SpringKinematics k = spring_kinematics(l, plane);
      const Eigen::Matrix3d K = point_k(l.body1, k.p1) + point_k(l.body2, plane ? k.p1 : k.p2);
      const Vec3 e = detail::spring_direction(p, k);
      double im = 0.0;
      if (e.squaredNorm() > 0.0) {
        im = e.dot(K * e);
      } else {
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(K, Eigen::EigenvaluesOnly);
        im = eig.eigenvalues().maxCoeff();
      }
      // neither end can move along the spring (restrained or prescribed): no damping mass
      const double m = im > 0.0 ? 1.0 / im : 0.0;
      spring_masses_[s] = m;
      const SpringResult r = evaluate(p, spring_states_[s], k, time_, h, m);
      spring_results_[s] = r;
      apply_force(bodies_, static_cast<std::size_t>(l.body1), r.force, k.p1);
      if (l.body2 != world)
        apply_force(bodies_, static_cast<std::size_t>(l.body2), -r.force, plane ? k.p1 : k.p2);
    }
    for (std::size_t s = 0; s < torsion_links_.size(); ++s) {
      const TorsionLink& l = torsion_links_[s];
      const TorsionKinematics k{orientation_of(l.body1), orientation_of(l.body2), omega_of(l.body1),
                                omega_of(l.body2)};
      const TorsionResult r = evaluate(torsion_params_[s], l.frames, k, torsion_inertia(l, k.q1));
      torsion_results_[s] = r;
      bodies_.torque[static_cast<std::size_t>(l.body1)] += r.torque;
      if (l.body2 != world) bodies_.torque[static_cast<std::size_t>(l.body2)] -= r.torque;
    }
  }

  /// The relative effective inertia about body 1's torsion axes x, y, z [kg m^2].
  Vec3 torsion_inertia(const TorsionLink& l, const Eigen::Quaterniond& q1) const {
    const Eigen::Matrix3d R1 = q1.normalized().toRotationMatrix();
    const Vec3 x = R1 * l.frames.x1, z = R1 * l.frames.z1, y = z.cross(x);
    const Eigen::Matrix3d inv = inverse_inertia_of(l.body1) + inverse_inertia_of(l.body2);
    // about an axis neither body can turn (restrained or prescribed): 0, no damping from a ratio
    const auto J = [&](const Vec3& n) {
      const double i = n.dot(inv * n);
      return i > 0.0 ? 1.0 / i : 0.0;
    };
    return Vec3(J(x), J(y), J(z));
  }

  CriticalStep spring_estimate(std::size_t s, bool bound = false) const {
    CriticalStep c;
    c.index = s;
    const SpringState& st = spring_states_[s];
    const SpringResult& r = spring_results_[s];
    const SpringParams& p = spring_params_[s];
    double k = r.stiffness;
    if (bound) {
      k = detail::largest_slope(p.spring);
      if (p.unload) k = std::max(k, detail::largest_slope(*p.unload));
    } else if (!st.active || st.rule_unload || r.direction.squaredNorm() == 0.0) {
      return c;
    }
    if (!(k > 0.0)) return c;
    const SpringLink& l = spring_links_[s];
    const bool plane = p.geometry == SpringGeometry::point_to_plane;
    const SpringKinematics kin = spring_kinematics(l, plane);
    const Eigen::Matrix3d K = point_k(l.body1, kin.p1) + point_k(l.body2, plane ? kin.p1 : kin.p2);
    const Vec3& e = r.direction;
    double im = 0.0;
    if (e.squaredNorm() > 0.0) {
      im = e.dot(K * e);
    } else { // undefined direction (bound only): the stiffest one
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(K, Eigen::EigenvaluesOnly);
      im = eig.eigenvalues().maxCoeff();
    }
    if (!(im > 0.0)) return c; // neither end can move along it (restrained, prescribed)
    const double m = 1.0 / im;
    c.omega = std::sqrt(k / m);
    double xi = p.damping_ratio;
    if (p.dashpot)
      xi = std::max(0.0, bound ? detail::largest_slope(*p.dashpot)
                               : detail::table_slope(*p.dashpot, r.velocity)) /
           (2.0 * std::sqrt(k * m));
    c.damping_ratio = xi;
    c.step = critical_step(c.omega, xi);
    if (p.friction > 0.0 && p.kskn > 0.0) {
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(K, Eigen::EigenvaluesOnly);
      const double wt = std::sqrt(p.kskn * k * eig.eigenvalues().maxCoeff());
      const double ht = critical_step(wt, xi);
      if (ht < c.step) {
        c.step = ht;
        c.omega = wt;
      }
    }
    return c;
  }

  /// The limiting angle of torsion spring s; with `angles`, each angle's estimate too.
  CriticalStep torsion_estimate(std::size_t s, std::array<CriticalStep, 3>* angles,
                                bool bound = false) const {
    const TorsionLink& l = torsion_links_[s];
    const TorsionSpringParams& p = torsion_params_[s];
    const TorsionResult& r = torsion_results_[s];
    const Vec3 J = torsion_inertia(l, orientation_of(l.body1));
    const std::array<const TorsionLaw*, 3> laws{&p.roll, &p.pitch, &p.yaw};
    const bool cone = p.cone[0] || p.cone[1] || p.cone[2];
    int first = -1;
    for (int a = 0; a < 3 && cone; ++a)
      if (p.cone[static_cast<std::size_t>(a)]) {
        first = a;
        break;
      }
    const double radial = cone ? cone_angle(p, r.angles) : 0.0;
    CriticalStep worst;
    worst.index = s;
    for (int a = 0; a < 3; ++a) {
      const auto ua = static_cast<std::size_t>(a);
      CriticalStep c;
      c.index = s;
      const bool coupled = cone && p.cone[ua];
      const TorsionLaw& law = *laws[static_cast<std::size_t>(coupled ? first : a)];
      const double angle = coupled ? radial : r.angles[a];
      const double rate = r.rates[a];
      const double k = !law.spring ? 0.0
                       : bound     ? detail::largest_slope(*law.spring)
                                   : detail::table_slope(*law.spring, angle);
      if (k > 0.0 && J[a] > 0.0) {
        c.omega = std::sqrt(k / J[a]);
        double xi = law.damping_ratio;
        if (law.dashpot)
          xi = std::max(0.0, bound ? detail::largest_slope(*law.dashpot)
                                   : detail::table_slope(*law.dashpot, rate)) /
               (2.0 * std::sqrt(k * J[a]));
        c.damping_ratio = xi;
        c.step = critical_step(c.omega, xi);
      }
      if (angles) (*angles)[ua] = c;
      if (c.step < worst.step) worst = c;
    }
    return worst;
  }

  double next_step(double h) {
    if (adaptive_ == 0.0) return h;
    const double hc = critical();
    return std::isfinite(hc) ? std::min(h, adaptive_ * hc) : h;
  }

  /// Stages 2 and 3 of a step: impulses at the configuration X(t) that make the drift over h
  /// close every joint gap, then the drift. The first impulse gives the joint points the relative
  /// velocity -C(t)/h; as the rotation over the step is not linear, the gap after the drift is
  /// then of order h^2 |omega|^2 |r|, and further impulses (with the same matrix, the joint
  /// directions at X(t), as in SHAKE) correct the velocity by -C(t+h)/h and the drift is made
  /// again, until the largest gap is below `joint_tolerance` (relative to the largest arm) or
  /// does not decrease any more (at most `joint_iterations` times).
  void drift_with_joints(double h) {
    factor_joints();
    impulse_half_.assign(joints_.size(), Vec3::Zero());
    const std::size_t nj = joints_.size();
    Eigen::VectorXd rhs(static_cast<Eigen::Index>(3 * nj));
    for (std::size_t j = 0; j < nj; ++j) {
      const auto [p1, p2] = joint_points(j);
      rhs.segment<3>(static_cast<Eigen::Index>(3 * j)) = -(p1 - p2) / h;
    }
    rhs -= joint_velocities();
    apply_joint_impulses(rhs, impulse_half_);
    saved_position_ = bodies_.position;
    saved_orientation_ = bodies_.orientation;
    double arm = 0.0;
    for (const auto& e : joint_ends_)
      for (const auto& x : e)
        arm = std::max(arm, x.arm.norm());
    const double tol = joint_tolerance * std::max(arm, std::numeric_limits<double>::min());
    double previous = std::numeric_limits<double>::infinity();
    for (int it = 0;; ++it) {
      joint_drifts_ = it + 1;
      saved_velocity_ = bodies_.velocity;
      saved_omega_ = bodies_.omega;
      drift(h);
      double worst = 0.0;
      for (std::size_t j = 0; j < nj; ++j) {
        const auto [p1, p2] = joint_points(j);
        const Vec3 c = p1 - p2;
        worst = std::max(worst, c.norm());
        rhs.segment<3>(static_cast<Eigen::Index>(3 * j)) = -c / h;
      }
      if (worst <= tol || worst >= 0.5 * previous || it >= joint_iterations) return;
      previous = worst;
      bodies_.position = saved_position_;
      bodies_.orientation = saved_orientation_;
      bodies_.velocity = saved_velocity_;
      bodies_.omega = saved_omega_;
      apply_joint_impulses(rhs, impulse_half_);
    }
  }

  /// Assembles J M^-1 J^T for the current configuration and factorises it; keeps the arms.
  void factor_joints() {
    const std::size_t nj = joints_.size();
    joint_ends_.assign(bodies_.size(), {});
    for (std::size_t j = 0; j < nj; ++j) {
      const BallJoint& jt = joints_[j];
      const auto [p1, p2] = joint_points(j);
      const auto b1 = static_cast<std::size_t>(jt.body1);
      joint_ends_[b1].push_back({j, 1.0, p1 - bodies_.position[b1]});
      if (jt.body2 != world) {
        const auto b2 = static_cast<std::size_t>(jt.body2);
        joint_ends_[b2].push_back({j, -1.0, p2 - bodies_.position[b2]});
      }
    }
    std::vector<Eigen::Triplet<double>> trip;
    std::vector<double> diag(3 * nj, 0.0);
    joint_inverse_inertia_.assign(bodies_.size(), Eigen::Matrix3d::Zero());
    joint_inverse_mass_.assign(bodies_.size(), Eigen::Matrix3d::Zero());
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
      if (joint_ends_[b].empty()) continue;
      const Eigen::Matrix3d inv = inverse_inertia_of(static_cast<long>(b));
      const Eigen::Matrix3d im = inverse_mass_of(static_cast<long>(b));
      joint_inverse_inertia_[b] = inv;
      joint_inverse_mass_[b] = im;
      for (const JointEnd& x : joint_ends_[b])
        for (const JointEnd& y : joint_ends_[b]) {
          const Eigen::Matrix3d blk =
              x.sign * y.sign * (im - detail::skew(x.arm) * inv * detail::skew(y.arm));
          for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c)
              trip.emplace_back(static_cast<int>(3 * x.joint) + r,
                                static_cast<int>(3 * y.joint) + c, blk(r, c));
          if (x.joint == y.joint)
            for (int r = 0; r < 3; ++r)
              diag[3 * x.joint + static_cast<std::size_t>(r)] += blk(r, r);
        }
    }
    // each row regularised relative to its own diagonal entry (a global value would make the
    // joints of heavy bodies compliant next to those of light ones)
    for (std::size_t r = 0; r < 3 * nj; ++r)
      trip.emplace_back(static_cast<int>(r), static_cast<int>(r), 1e-12 * diag[r]);
    Eigen::SparseMatrix<double> A(static_cast<Eigen::Index>(3 * nj),
                                  static_cast<Eigen::Index>(3 * nj));
    A.setFromTriplets(trip.begin(), trip.end());
    if (!joint_solver_)
      joint_solver_ = std::make_unique<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>();
    joint_solver_->compute(A);
    if (joint_solver_->info() != Eigen::Success)
      throw std::runtime_error("BodySystem: the ball-joint system could not be factorised at t = " +
                               grain::detail::to_text(time_) + " s");
  }

  /// Relative velocities u = J V of all joints (3 per joint) with the arms of `factor_joints`.
  Eigen::VectorXd joint_velocities() const {
    Eigen::VectorXd u = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(3 * joints_.size()));
    for (std::size_t b = 0; b < bodies_.size(); ++b)
      for (const JointEnd& x : joint_ends_[b])
        u.segment<3>(static_cast<Eigen::Index>(3 * x.joint)) +=
            x.sign * (bodies_.velocity[b] + bodies_.omega[b].cross(x.arm));
    return u;
  }

  /// Solves (J M^-1 J^T) lambda = rhs, applies the impulses (lambda on body 1, -lambda on body
  /// 2) to the velocities and adds lambda to `acc`.
  void apply_joint_impulses(const Eigen::VectorXd& rhs, std::vector<Vec3>& acc) {
    const Eigen::VectorXd lambda = joint_solver_->solve(rhs);
    for (std::size_t b = 0; b < bodies_.size(); ++b)
      for (const JointEnd& x : joint_ends_[b]) {
        const Vec3 l = x.sign * Vec3(lambda.segment<3>(static_cast<Eigen::Index>(3 * x.joint)));
        bodies_.velocity[b] += joint_inverse_mass_[b] * l;
        bodies_.omega[b] += joint_inverse_inertia_[b] * x.arm.cross(l);
      }
    for (std::size_t j = 0; j < joints_.size(); ++j)
      acc[j] += lambda.segment<3>(static_cast<Eigen::Index>(3 * j));
  }

  RigidBodies bodies_{};
  std::vector<Vec3> external_force_{}, external_torque_{};
  std::vector<SpringParams> spring_params_{};
  std::vector<SpringState> spring_states_{};
  std::vector<SpringLink> spring_links_{};
  std::vector<SpringResult> spring_results_{};
  std::vector<double> spring_masses_{};
  std::vector<TorsionSpringParams> torsion_params_{};
  std::vector<TorsionLink> torsion_links_{};
  std::vector<TorsionResult> torsion_results_{};
  std::vector<BallJoint> joints_{};
  std::vector<JointResult> joint_results_{};
  std::vector<Vec3> impulse_half_{}, impulse_end_{};
  struct JointEnd {
    std::size_t joint;
    double sign; // +1 body 1, -1 body 2
    Vec3 arm;    // joint point - centre [m]
  };
  std::vector<std::vector<JointEnd>> joint_ends_{};
  std::vector<Eigen::Matrix3d> joint_inverse_inertia_{}, joint_inverse_mass_{};
  std::unique_ptr<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>> joint_solver_{};
  std::vector<Vec3> saved_position_{}, saved_velocity_{}, saved_omega_{};
  std::vector<Eigen::Quaterniond> saved_orientation_{};
  std::vector<Unspring> unsprings_{};
  std::vector<BodyControl> controls_{};
  std::vector<long> control_of_{}; ///< body -> index in controls_, or -1
  std::vector<Eigen::Quaterniond> c_drift_q_{};
  std::vector<Vec3> c_drift_w_{};
  VectorTimeFunction<3> gravity_{};
  VectorTimeFunction<3> damping_linear_{}, damping_angular_{};
  bool damped_ = false;
  double adaptive_ = 0.0;
  double time_ = 0.0;
  double h_ = 0.0;
  long steps_ = 0;
  bool initialized_ = false;
  int joint_drifts_ = 0;
  std::vector<std::pair<std::size_t, MeshSurface>> meshes_{}; ///< (body index, surface)
};

} // namespace grain::bodies
