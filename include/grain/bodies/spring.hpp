#pragma once
/// \file spring.hpp
/// Translational nonlinear spring between two attachment points (the SPRING command of the
/// Parmec user manual), written as a stateless law on the kinematics of the two points: the
/// caller (a body system) supplies the world positions and velocities of the points, and applies
/// the returned force at point 1 and its negative at point 2. Nothing here knows about bodies.
///
/// Units: SI throughout (m, m/s, s, kg, N, N/m, N s/m).
///
/// ## Geometry, direction and stroke
///
/// Let d = p2 - p1. The unit direction `e` and the stroke `s` are (stroke0 is the rest length,
/// see below):
///
/// - `point_to_point`: e = d / abs(d) (follower), s = abs(d) - stroke0;
/// - `constant_direction`: e = c, the given unit direction, s = c . d - stroke0;
/// - `planar`: e = w / abs(w) with w = d - (c . d) c, s = abs(w) - stroke0;
/// - `point_to_plane`: e = -n (n: the plane normal, carried by body 2), s = n . (p1 - p2).
///
/// The length of the spring is L = e . d (abs(d), c . d or abs(w); for the plane, the signed
/// distance n . (p1 - p2)), so that in every geometry s = L - stroke0 (stroke0 = 0 for the plane)
/// and s > 0 is extension
/// (points moving apart; point 1 on the positive side of the plane) and the stroke rate is
/// v = e . (v2 - v1). For the plane, p2 is any point of the plane and v2 the velocity of the
/// material point of body 2 under point 1; the rate neglects the rotation of the normal. If
/// abs(d) (or abs(w)) is zero the direction is undefined and the spring gives no force.
///
/// ## Rest length
///
/// stroke0 is the rest (undeformed) length L0 [m], the length at which the stroke is zero and the
/// force is that of the table at s = 0. As in the Parmec manual, it is the length at creation,
/// stroke0 = e(0) . (p2(0) - p1(0)), captured by `init_spring` from the positions, unless
/// `SpringParams::rest_length` gives it: stroke0 = rest_length. A spring created at a length
/// L(0) other than its rest length starts prestressed, at the stroke s(0) = L(0) - L0 with the
/// force f(s(0)). The stroke keeps the definition s = e . d - stroke0 with stroke0 given instead
/// of captured; the force is that of Parmec's spring with the constant stroke offset
/// L0 - L(0) (f = table(L - L(0) - (L0 - L(0)))), whose stroke would be counted from L(0).
/// The plane has no rest length: its stroke is the signed distance (rest_length must not be
/// given); its table is written in that distance.
///
/// ## Force
///
///   F = f(s) + f_d(v) abs(sign(f(s)))          [N]      (the dashpot is off while f = 0)
///   force on point 1 = F e + F_t, on point 2 = -(F e + F_t)
///
/// f is the elastic (spring) force from the force-stroke table, f_d the dashpot force: either
/// the dashpot table f_d(v), or c v with c = 2 xi sqrt(k m), xi the critical damping ratio, k
/// the current tangent stiffness df/ds of the curve in use (zero outside the table's range,
/// where the end value holds) and m the effective (equivalent point) mass passed by the caller.
/// F > 0 is tension: it pulls the points together (pulls point 1 towards the plane), so a table
/// with a positive slope is restoring in every geometry. (The Parmec user manual states that
/// F e acts at point 2, which read literally makes a positive-slope table push the points apart;
/// the convention here is the restoring one, and for the plane it coincides with the manual's
/// reading, since e = -n.) A contact element against a plane is a table that is zero for s > 0,
/// e.g. {{-1, -k}, {0, 0}, {1, 0}}: penetration s < 0 gives F < 0, pushing point 1 out along n.
/// A table may have falling branches (a negative slope: softening after a peak, snap-through);
/// they are followed as given, on purpose. The dashpot of a damping ratio then uses max(k, 0)
/// (it never becomes a source of energy), and a falling branch adds no stiffness to the time
/// step's estimate; a structure that is statically unstable on such a branch moves dynamically.
///
/// ## Offset
///
/// `offset(t)` shifts all stroke values of the force-stroke table: f = table(s - offset(t)). For
/// a spring with an unloading curve it acts only until yield; its value at yield is kept.
///
/// ## Loading, unloading and yield (hysteresis)
///
/// Without an `unload` table the spring is nonlinear elastic: f = table(s - offset(t)) for
/// loading and unloading alike (`fyc`/`fyt` then only set the `yielded` flag).
///
/// With an `unload` table U (a strictly increasing force-stroke curve) the spring follows the
/// Parmec user manual's description of its nonlinear cycles, read as follows. Write
/// u = s - sigma for the argument of the loading curve L (sigma = offset(t) until yield):
///  1. Until yield the spring is elastic on L (unloading happens along the loading curve). It
///     yields the first time L(u) > fyt or L(u) < fyc (the default (0, 0) yields at the first
///     non-zero force, which gives the nonlinear loading/unloading pair of an `unload` table
///     given alone). The extremes u_max >= u_min reached on L are tracked from the start; the
///     latest tension point is (u_max, L(u_max)), the latest compression point (u_min, L(u_min)).
///  2. After yield, while u moves beyond the extremes the spring is on the loading path L and the
///     extreme follows. When the stroke turns back (u strictly inside (u_min, u_max)) unloading
///     starts: the unloading branch is U shifted in stroke through the turning point (s_r, f_r),
///     f = U(s - delta), delta = s_r - U^-1(f_r). U is extended linearly beyond its end points.
///  3. Reversals on the branch stay on it (the same delta), in both directions.
///  4. The branch ends when its force reaches that of the latest point of the path it runs
///     towards: moving up, L(u_max); moving down, L(u_min). The path is then continued from that
///     point: sigma is reset so that the latest point sits at the joining stroke s_j
///     (U(s_j - delta) = L(u_extreme), sigma = s_j - u_extreme), and f = L(s - sigma).
/// The force is continuous. With a linear U and a bilinear L with a plateau, the cycle between
/// strokes +-a is the parallelogram of elastic-perfectly-plastic behaviour, enclosing
/// 4 f_y (a - s_y) (see docs/springs.md for the worked numbers).
///
/// ## Friction
///
/// With `friction` mu > 0 a tangential force F_t acts in the plane normal to e, with the
/// relative tangential velocity v_t = (v2 - v1) - ((v2 - v1) . e) e and the Coulomb limit
/// mu abs(F):
/// - `kskn` = 0: F_t = mu abs(F) v_t / abs(v_t) (sliding only, zero for v_t = 0; no sticking);
/// - `kskn` > 0: kskn is the ratio k_t / k_n (tangential to normal; the manual's wording says
///   "normal to tangential", its code multiplies the normal values by kskn, as done here):
///   k_t = kskn k, c_t = kskn c with k the current tangent stiffness and c the dashpot coefficient
///   (2 xi sqrt(k m), or the slope of the dashpot table at v). The tangential elastic
///   displacement xi_t (state) is first projected onto the current tangent plane with its length
///   kept, then incremented by v_t h; the trial force k_t xi_t + c_t v_t is limited to mu abs(F)
///   and, when limited, xi_t is truncated to the limit ((F_t - c_t v_t) / k_t) so that a reversal
///   sticks at once (the Parmec implementation neither projects nor truncates its history).
/// F_t acts on point 1 (-F_t on point 2): it drags point 1 along with point 2.
///
/// ## State codes (the manual's 'SS' output)
///
/// -3 a regular spring, -2 a spring activated by an unspring rule, -1 an inactive (dormant or
/// undone) spring giving no force, >= 0 a spring being unloaded by an unspring rule (the index of
/// its unloading curve in that rule); see unspring.hpp.

#include <grain/core/error.hpp>
#include <grain/core/table.hpp>
#include <grain/core/time_function.hpp>
#include <grain/core/vector.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <type_traits>

namespace grain::bodies {

/// How the direction and the stroke are measured (see the table in the file comment).
enum class SpringGeometry : std::uint8_t {
  point_to_point,
  constant_direction,
  planar,
  point_to_plane
};

/// State codes as the Parmec user manual's 'SS' output reports them.
namespace spring_code {
inline constexpr int regular = -3;   ///< always active
inline constexpr int activated = -2; ///< activated by an unspring rule
inline constexpr int inactive = -1;  ///< dormant or undone: no force
} // namespace spring_code

/// Parameters of one translational spring. `spring` is required; the rest is optional. Every
/// member has a default, so `SpringParams p;` compiles; the default `spring` is the empty table,
/// which `validate` rejects ("the force-stroke table f(s) must be given").
struct SpringParams {
  /// Force-stroke table f(s) [m -> N] (the loading curve when `unload` is given); required.
  Table spring{};
  /// Dashpot force-velocity table f_d(v) [m/s -> N]; excludes `damping_ratio` > 0.
  std::optional<Table> dashpot{};
  /// Critical damping ratio xi >= 0 [-]: f_d = 2 xi sqrt(k m) v.
  double damping_ratio = 0.0;
  SpringGeometry geometry = SpringGeometry::point_to_point;
  /// The constant direction c (constant_direction) or the plane normal of `planar`; need not be
  /// unit, must be non-zero.
  Vec3 direction = Vec3::Zero();
  /// Rest (undeformed) length L0 [m]: the stroke is s = L - L0 (L = abs(d), c . d or abs(w)).
  /// Absent (default): the length at creation, as in Parmec. >= 0 for point_to_point and planar,
  /// any finite value for constant_direction; not for point_to_plane.
  std::optional<double> rest_length{};
  /// Unloading curve U(s) [m -> N], forces strictly increasing; enables the hysteresis.
  std::optional<Table> unload{};
  /// Compression and tension yield forces [N], fyc <= 0 <= fyt.
  double fyc = 0.0;
  double fyt = 0.0;
  /// Create the spring dormant (no force until an unspring rule activates it).
  bool inactive = false;
  /// Stroke offset [m] as a function of time.
  TimeFunction offset{};
  /// Friction coefficient mu >= 0 [-] and the ratio kskn = k_t / k_n >= 0 [-].
  double friction = 0.0;
  double kskn = 0.0;
  /// Name used in error messages.
  std::string name = "SPRING";
};

/// Per-spring history, trivially copyable.
struct SpringState {
  double stroke0 = 0.0;     ///< rest length: `rest_length`, or e . (p2 - p1) at creation [m]
                            ///< (0 for the plane)
  double stroke = 0.0;      ///< stroke at the last evaluation [m]
  double force = 0.0;       ///< elastic force at the last evaluation [N]
  double sigma = 0.0;       ///< shift of the loading curve's argument [m]
  double delta = 0.0;       ///< shift of the unloading branch [m]
  double u_max = 0.0;       ///< latest tension extreme of the loading curve's argument [m]
  double u_min = 0.0;       ///< latest compression extreme of the loading curve's argument [m]
  PlainVec<3> tangential{}; ///< tangential elastic displacement xi_t [m]
  const Table* rule_unload = nullptr; ///< unloading curve of an unspring rule (not owned)
  double rule_force0 = 0.0;           ///< elastic force when the rule's unloading began [N]
  double rule_path = 0.0;             ///< accumulated abs(stroke increments) since then [m]
  int code = spring_code::regular;    ///< 'SS' state code
  bool active = true;                 ///< false: no force
  bool yielded = false;               ///< a yield limit has been crossed
  bool unloading = false;             ///< on an unloading branch
  bool slipping = false;              ///< tangential force at the Coulomb limit
};
static_assert(std::is_trivially_copyable_v<SpringState>);

/// The kinematics of the two attachment points (world frame).
struct SpringKinematics {
  Vec3 p1 = Vec3::Zero(); ///< point 1 [m]
  Vec3 p2 = Vec3::Zero(); ///< point 2, or a point of the plane [m]
  Vec3 v1 = Vec3::Zero(); ///< velocity of point 1 [m/s]
  Vec3 v2 = Vec3::Zero(); ///< velocity of point 2 (plane: of body 2's point under point 1) [m/s]
  Vec3 normal = Vec3::UnitZ(); ///< unit plane normal (point_to_plane only)
};

/// What one evaluation gives.
struct SpringResult {
  Vec3 force = Vec3::Zero();          ///< on point 1 [N]; point 2 gets -force
  Vec3 direction = Vec3::Zero();      ///< e (zero if undefined)
  Vec3 friction_force = Vec3::Zero(); ///< F_t, included in `force` [N]
  double length = 0.0;                ///< e . (p2 - p1) [m] (the plane: n . (p1 - p2))
  double stroke = 0.0;                ///< s [m]
  double velocity = 0.0;              ///< stroke rate v [m/s]
  double total = 0.0;                 ///< F = f + f_d abs(sign f) [N] ('F')
  double elastic = 0.0;               ///< f [N] ('SF')
  double damping = 0.0;               ///< the dashpot part of F [N]
  double friction = 0.0;              ///< abs(F_t) [N] ('FF')
  double stiffness = 0.0;             ///< current tangent stiffness k [N/m]
  int code = spring_code::regular;    ///< 'SS'

  template <class Archive>
  void serialize(Archive& ar) {
    ar(force, direction, friction_force, length, stroke, velocity, total, elastic, damping,
       friction, stiffness, code);
  }
};

namespace detail {

/// Slope of a table at x: that of the segment containing x, zero outside [x_front, x_back].
inline double table_slope(const Table& t, double x) {
  if (!(x >= t.x_front() && x <= t.x_back())) return 0.0;
  const std::size_t i = t.segment(x);
  return (t.y()[i + 1] - t.y()[i]) / (t.x()[i + 1] - t.x()[i]);
}

/// The largest slope of a table's segments (0 if none rises).
inline double largest_slope(const Table& t) {
  double k = 0.0;
  for (std::size_t i = 0; i + 1 < t.x().size(); ++i)
    k = std::max(k, (t.y()[i + 1] - t.y()[i]) / (t.x()[i + 1] - t.x()[i]));
  return k;
}

/// A table continued linearly beyond its end points (by its first and last segments).
inline double extended(const Table& t, double x) {
  const auto& X = t.x();
  const auto& Y = t.y();
  const std::size_t i = t.segment(x);
  return Y[i] + (x - X[i]) * (Y[i + 1] - Y[i]) / (X[i + 1] - X[i]);
}

/// Slope of the linearly continued table at x.
inline double extended_slope(const Table& t, double x) {
  const std::size_t i = t.segment(x);
  return (t.y()[i + 1] - t.y()[i]) / (t.x()[i + 1] - t.x()[i]);
}

/// Inverse of the linearly continued table (ordinates strictly increasing): x with t(x) = f.
inline double extended_inverse(const Table& t, double f) {
  const auto& X = t.x();
  const auto& Y = t.y();
  const auto it = std::upper_bound(Y.begin() + 1, Y.end() - 1, f);
  const std::size_t i = static_cast<std::size_t>(it - Y.begin()) - 1;
  return X[i] + (f - Y[i]) * (X[i + 1] - X[i]) / (Y[i + 1] - Y[i]);
}

inline void require_finite_vec(const std::string& object, const char* name, const Vec3& v) {
  if (!v.allFinite())
    throw InputError(object + ": " + name + " = (" + grain::detail::to_text(v.x()) + ", " +
                     grain::detail::to_text(v.y()) + ", " + grain::detail::to_text(v.z()) +
                     ") is invalid; valid range: finite components");
}

/// The elastic force and tangent stiffness of the loading/unloading model; updates the state.
inline double hysteretic_force(const SpringParams& p, SpringState& st, double s, double offset,
                               double& k) {
  const Table& L = p.spring;
  const Table& U = *p.unload;
  const double s_prev = st.stroke;
  if (!st.yielded) {
    const double u = s - offset;
    st.u_max = std::max(st.u_max, u);
    st.u_min = std::min(st.u_min, u);
    const double f = L(u);
    k = table_slope(L, u);
    if (f > p.fyt || f < p.fyc) {
      st.yielded = true;
      st.sigma = offset;
    }
    return f;
  }
  if (!st.unloading) {
    const double u = s - st.sigma;
    if (u >= st.u_max || u <= st.u_min) {
      st.u_max = std::max(st.u_max, u);
      st.u_min = std::min(st.u_min, u);
      k = table_slope(L, u);
      return L(u);
    }
    // the stroke turned back: start an unloading branch through the previous point
    st.unloading = true;
    st.delta = s_prev - extended_inverse(U, st.force);
  }
  const double fb = extended(U, s - st.delta);
  const double f_top = L(st.u_max), f_bottom = L(st.u_min);
  double extreme = 0.0, f_join = 0.0;
  bool join = false;
  if (s > s_prev && fb >= f_top) {
    join = true;
    extreme = st.u_max;
    f_join = f_top;
  } else if (s < s_prev && fb <= f_bottom) {
    join = true;
    extreme = st.u_min;
    f_join = f_bottom;
  }
  if (!join) {
    k = extended_slope(U, s - st.delta);
    return fb;
  }
  // the branch has reached the latest point of the path: continue the path from there
  const double s_join = st.delta + extended_inverse(U, f_join);
  st.sigma = s_join - extreme;
  st.unloading = false;
  const double u = s - st.sigma;
  st.u_max = std::max(st.u_max, u);
  st.u_min = std::min(st.u_min, u);
  k = table_slope(L, u);
  return L(u);
}

} // namespace detail

/// Checks the parameters; throws `InputError` naming the spring, the value and the valid range.
inline void validate(const SpringParams& p) {
  using grain::detail::require;
  using grain::detail::to_text;
  const std::string& obj = p.name;
  grain::detail::require_given(p.spring, obj, "spring", "the force-stroke table f(s)");
  if (p.dashpot)
    grain::detail::require_given(*p.dashpot, obj, "dashpot",
                                 "a given dashpot table f_d(v) (or leave it absent)");
  if (p.unload)
    grain::detail::require_given(*p.unload, obj, "unload",
                                 "a given unloading curve U(s) (or leave it absent)");
  if (p.rest_length) {
    const double l0 = *p.rest_length;
    switch (p.geometry) {
    case SpringGeometry::point_to_point:
    case SpringGeometry::planar:
      require(std::isfinite(l0) && l0 >= 0.0, obj, "rest_length", l0,
              "[0, inf) m (the length at which the stroke is zero)");
      break;
    case SpringGeometry::constant_direction:
      require(std::isfinite(l0), obj, "rest_length", l0,
              "a finite length [m] (the length c . d at which the stroke is zero)");
      break;
    case SpringGeometry::point_to_plane:
      require(false, obj, "rest_length", l0,
              "none for the point_to_plane geometry (its stroke is the signed distance "
              "n . (p1 - p2); write the table in that distance)");
      break;
    }
  }
  require(std::isfinite(p.damping_ratio) && p.damping_ratio >= 0.0, obj, "damping_ratio",
          p.damping_ratio, "[0, inf) (a critical damping ratio)");
  if (p.dashpot && p.damping_ratio > 0.0)
    throw InputError(obj + ": damping_ratio = " + to_text(p.damping_ratio) +
                     " is invalid; valid range: 0 when a dashpot table is given (give one of "
                     "the two)");
  if (p.geometry == SpringGeometry::constant_direction || p.geometry == SpringGeometry::planar) {
    detail::require_finite_vec(obj, "direction", p.direction);
    require(p.direction.norm() > 0.0, obj, "|direction|", p.direction.norm(),
            "(0, inf) (a non-zero direction)");
  }
  require(std::isfinite(p.fyc) && p.fyc <= 0.0, obj, "fyc", p.fyc,
          "(-inf, 0] (the compression yield force)");
  require(std::isfinite(p.fyt) && p.fyt >= 0.0, obj, "fyt", p.fyt,
          "[0, inf) (the tension yield force)");
  require(std::isfinite(p.friction) && p.friction >= 0.0, obj, "friction", p.friction, "[0, inf)");
  require(std::isfinite(p.kskn) && p.kskn >= 0.0, obj, "kskn", p.kskn,
          "[0, inf) (the ratio k_t / k_n)");
  if (p.unload) {
    const auto& y = p.unload->y();
    for (std::size_t i = 1; i < y.size(); ++i)
      if (!(y[i] > y[i - 1]))
        throw InputError(obj + ": unload " + p.unload->label() + " y[" + std::to_string(i) +
                         "] = " + to_text(y[i]) + " is invalid; valid range: (" +
                         to_text(y[i - 1]) + ", inf), above y[" + std::to_string(i - 1) +
                         "] (the unloading curve must increase strictly)");
  }
}

namespace detail {

/// The length L = e . (p2 - p1) of the spring's geometry [m] (the plane: n . (p1 - p2)).
inline double spring_length(const SpringParams& p, const SpringKinematics& k) {
  const Vec3 d = k.p2 - k.p1;
  switch (p.geometry) {
  case SpringGeometry::point_to_point:
    return d.norm();
  case SpringGeometry::constant_direction:
    return p.direction.normalized().dot(d);
  case SpringGeometry::planar: {
    const Vec3 c = p.direction.normalized();
    return (d - c.dot(d) * c).norm();
  }
  case SpringGeometry::point_to_plane:
    return k.normal.normalized().dot(-d);
  }
  return 0.0;
}

} // namespace detail

/// The stroke0 (rest length) of a spring created with the kinematics `k` [m]: `rest_length` if
/// given, else the length of the spring's geometry for these positions; 0 for the plane.
inline double initial_stroke(const SpringParams& p, const SpringKinematics& k) {
  if (p.geometry == SpringGeometry::point_to_plane) return 0.0;
  if (p.rest_length) return *p.rest_length;
  return detail::spring_length(p, k);
}

/// Validates the parameters and makes the state of a spring created with the kinematics `k0` at
/// time `t0` [s]: stroke0 (the rest length), the stroke at creation (0 unless `rest_length` is
/// given, or for the plane), the activity, the state code, the starting extremes.
inline SpringState init_spring(const SpringParams& p, const SpringKinematics& k0, double t0 = 0.0) {
  validate(p);
  detail::require_finite_vec(p.name, "p1", k0.p1);
  detail::require_finite_vec(p.name, "p2", k0.p2);
  SpringState st;
  st.stroke0 = initial_stroke(p, k0);
  st.active = !p.inactive;
  st.code = p.inactive ? spring_code::inactive : spring_code::regular;
  st.stroke = detail::spring_length(p, k0) - st.stroke0;
  const double o = p.offset(t0);
  st.u_max = st.u_min = st.stroke - o;
  st.force = p.spring(st.stroke - o);
  return st;
}

namespace detail {

/// The unit direction e of a spring (zero if undefined) and its length L = e . (p2 - p1) [m].
struct SpringAxis {
  Vec3 e = Vec3::Zero();
  double length = 0.0;
};

/// The direction and length of the spring's geometry for the kinematics `k` (see the table in
/// the file comment; the plane: e = -n).
inline SpringAxis spring_axis(const SpringParams& p, const SpringKinematics& k) {
  const Vec3 d = k.p2 - k.p1;
  Vec3 e = Vec3::Zero();
  double length = 0.0;
  switch (p.geometry) {
  case SpringGeometry::point_to_point:
    length = d.norm();
    if (length > 0.0) e = d / length;
    break;
  case SpringGeometry::constant_direction:
    e = p.direction.normalized();
    length = e.dot(d);
    break;
  case SpringGeometry::planar: {
    const Vec3 c = p.direction.normalized();
    const Vec3 w = d - c.dot(d) * c;
    length = w.norm();
    if (length > 0.0) e = w / length;
    break;
  }
  case SpringGeometry::point_to_plane:
    e = -k.normal.normalized();
    length = e.dot(d);
    break;
  }
  return {e, length};
}

/// The elastic force [N] of a spring being unloaded by an unspring rule, at the stroke s [m]:
/// abs(f) decreases by the rule's curve of the accumulated abs(stroke increments); at zero force
/// or the end of the curve the spring becomes inactive. Updates the state's rule path and
/// activity.
inline double rule_unloading_force(SpringState& st, double s) {
  st.rule_path += std::abs(s - st.stroke);
  const double drop = (*st.rule_unload)(st.rule_path);
  double f = std::abs(st.rule_force0) - drop;
  if (f <= 0.0 || st.rule_path >= st.rule_unload->x_back()) {
    f = 0.0;
    st.rule_unload = nullptr;
    st.active = false;
    st.code = spring_code::inactive;
  }
  return std::copysign(f, st.rule_force0);
}

/// The elastic force f [N] at the stroke s [m] and time t [s], and its tangent stiffness k
/// [N/m]: the loading/unloading model if `unload` is given, else table(s - offset(t)). Updates
/// the yield and hysteresis state.
inline double elastic_force(const SpringParams& p, SpringState& st, double s, double t, double& k) {
  const double o = st.yielded && p.unload ? st.sigma : p.offset(t);
  if (p.unload) return hysteretic_force(p, st, s, o, k);
  const double f = p.spring(s - o);
  k = table_slope(p.spring, s - o);
  if (f > p.fyt || f < p.fyc) st.yielded = true;
  return f;
}

/// The dashpot coefficient c [N s/m] and force f_d [N] at the stroke rate v [m/s]: the dashpot
/// table and its slope, or c = 2 xi sqrt(k m) with the tangent stiffness k [N/m] and the
/// effective mass m [kg]; both zero without damping.
inline void dashpot_force(const SpringParams& p, double v, double k, double effective_mass,
                          double& c, double& fd) {
  if (p.dashpot) {
    fd = (*p.dashpot)(v);
    c = table_slope(*p.dashpot, v);
  } else if (p.damping_ratio > 0.0) {
    c = 2.0 * p.damping_ratio * std::sqrt(std::max(k, 0.0) * effective_mass);
    fd = c * v;
  }
}

/// The tangential friction force F_t [N] on point 1 for the total axial force F [N], the relative
/// velocity vrel = v2 - v1 [m/s] with stroke rate v [m/s] along e, the tangent stiffness k
/// [N/m], the dashpot coefficient c [N s/m] and the step h [s] (see Friction in the file
/// comment); zero without friction. Updates the tangential displacement and the slip flag.
inline Vec3 friction_force(const SpringParams& p, SpringState& st, const Vec3& e, const Vec3& vrel,
                           double v, double F, double k, double c, double h) {
  Vec3 ft = Vec3::Zero();
  st.slipping = false;
  if (!(p.friction > 0.0)) return ft;
  const Vec3 vt = vrel - v * e;
  const double limit = p.friction * std::abs(F);
  if (p.kskn == 0.0) {
    const double n = vt.norm();
    if (n > 0.0) ft = (limit / n) * vt;
    st.slipping = n > 0.0;
    return ft;
  }
  Vec3 xi = load<3>(st.tangential);
  const double len = xi.norm();
  xi -= xi.dot(e) * e;
  const double plen = xi.norm();
  if (plen > 0.0) xi *= len / plen;
  xi += h * vt;
  const double ks = p.kskn * k, cs = p.kskn * c;
  ft = ks * xi + cs * vt;
  const double n = ft.norm();
  if (n > limit) {
    ft *= limit / n;
    xi = ks > 0.0 ? Vec3((ft - cs * vt) / ks) : Vec3(Vec3::Zero());
    st.slipping = true;
  }
  store<3>(st.tangential, xi);
  return ft;
}

} // namespace detail

/// Evaluates the spring at time t [s] after a step h [s] (h is the increment used for the
/// tangential history), with the effective mass m >= 0 [kg] for the damping ratio. Updates `st`.
/// The parameters must have passed `validate` (done by `init_spring`).
inline SpringResult evaluate(const SpringParams& p, SpringState& st, const SpringKinematics& k,
                             double t, double h, double effective_mass) {
  SpringResult r;
  const auto [e, length] = detail::spring_axis(p, k);
  const double s = length - st.stroke0;
  const Vec3 vrel = k.v2 - k.v1;
  const double v = e.dot(vrel);
  r.direction = e;
  r.length = length;
  r.stroke = s;
  r.velocity = v;

  const auto finish = [&](double f) {
    st.stroke = s;
    st.force = f;
    r.code = st.code;
    return r;
  };
  if (!st.active || e.squaredNorm() == 0.0) {
    if (!st.active) st.tangential = {};
    return finish(st.active ? st.force : 0.0);
  }

  // being unloaded by an unspring rule: abs(f) decreases with every stroke increment
  if (st.rule_unload) {
    const double f = detail::rule_unloading_force(st, s);
    r.elastic = r.total = f;
    r.force = f * e;
    return finish(f);
  }

  double kt = 0.0;
  const double f = detail::elastic_force(p, st, s, t, kt);
  double c = 0.0, fd = 0.0;
  detail::dashpot_force(p, v, kt, effective_mass, c, fd);
  if (f == 0.0) fd = 0.0;
  const double F = f + fd;
  const Vec3 ft = detail::friction_force(p, st, e, vrel, v, F, kt, c, h);

  r.elastic = f;
  r.damping = fd;
  r.total = F;
  r.stiffness = kt;
  r.friction_force = ft;
  r.friction = ft.norm();
  r.force = F * e + ft;
  return finish(f);
}

/// The spring switched off (zero force from now on), as an unspring rule undoes it at once.
inline void deactivate(SpringState& st) {
  st.active = false;
  st.rule_unload = nullptr;
  st.code = spring_code::inactive;
  st.tangential = {};
}

/// A dormant spring switched on (state code -2).
inline void activate(SpringState& st) {
  st.active = true;
  st.rule_unload = nullptr;
  st.code = spring_code::activated;
}

} // namespace grain::bodies
