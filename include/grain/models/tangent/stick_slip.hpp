#pragma once
/// \file stick_slip.hpp
/// Mechanics shared by the tangential-force models (namespace `grain::tangent::detail`): the
/// spring elongation carried as a vector in the tangent plane, the Coulomb test with static and
/// dynamic friction, the truncation of the spring at the Coulomb limit, and the damping
/// coefficients derived from a tangential restitution coefficient.
///
/// Conventions (SI units): the force is the tangential force on particle i; the elongation xi [m]
/// is the accumulated tangential displacement of i relative to its partner at the contact point,
/// so swapping the partners of a pair negates it. One step of a spring model:
/// 1. xi is rotated into the current tangent plane keeping its length (the contact frame turns);
/// 2. xi += v_s dt (v_s = `ContactGeometry::slip_velocity` [m/s], the tangential relative
///    velocity at the contact point that moved the contact over the step);
/// 3. trial force F = -f(|xi|) xi/|xi| - eta v_t, f the spring law [N], eta [N s/m], v_t =
///    `ContactGeometry::tangential_velocity` (with velocity Verlet the velocity predicted at the
///    end of the step; otherwise equal to v_s);
/// 4. Coulomb: the contact slides if |F| > mu |F_n| with mu = mu_s (static) after a sticking step
///    and mu = mu_d (dynamic) after a sliding step; a sliding contact carries exactly
///    mu_d |F_n| along F, and its spring is truncated so that the spring alone holds that force,
///    xi = -f^-1(mu_d |F_n|) F/|F| (no damping while sliding).
/// Friction coefficients come from the pair (`PairProperties::friction` = mu_d,
/// `friction_static` = mu_s; mu_s < mu_d is read as mu_s = mu_d).

#include <algorithm>
#include <cmath>
#include <cstring>
#include <grain/models/concepts.hpp>
#include <numbers>
#include <type_traits>

namespace grain::tangent::detail {

/// True if the byte of the bool at b is 0 or 1 (read as a byte: a bool holding any other byte
/// may not even be read).
inline bool truth_byte(const bool* b) {
  unsigned char c;
  std::memcpy(&c, b, 1);
  return c <= 1;
}

/// History of a spring with a slider: elongation vector and the sliding state of the last step.
template <int D>
struct SpringHistory {
  PlainVec<D> spring{}; ///< elongation xi [m], in the tangent plane
  bool sliding = false; ///< true if the contact slid at the last step
  /// False if the bytes of a history read from a file hold no truth value in `sliding`.
  static bool valid_bytes(const SpringHistory& h) { return truth_byte(&h.sliding); }
};

/// History of a spring without slider (elongation vector only).
template <int D>
struct ElasticHistory {
  PlainVec<D> spring{}; ///< elongation xi [m], in the tangent plane
};

/// History of a slider without spring (sliding state only).
template <int D>
struct SlipHistory {
  bool sliding = false; ///< true if the contact slid at the last step
  /// False if the bytes of a history read from a file hold no truth value in `sliding`.
  static bool valid_bytes(const SlipHistory& h) { return truth_byte(&h.sliding); }
};

/// Static friction coefficient of a pair (never below the dynamic one).
inline double static_friction(const PairProperties& p) {
  return std::max(p.friction_static, p.friction);
}

/// kappa = 1 + m R^2 / I of the particles: `given` if > 0, else 7/2 (solid sphere, 3D) or 3
/// (solid disk, 2D). The tangential relative motion of a sticking contact has the effective
/// mass m*/kappa.
template <int D>
inline double kappa(double given) {
  return given > 0.0 ? given : (D == 3 ? 3.5 : 3.0);
}

/// Damping coefficient [N s/m] of a tangential spring k [N/m] for the tangential restitution
/// coefficient e in [0, 1] (Deen et al., Chem. Eng. Sci. 62 (2007) 28):
/// eta = -2 ln(e) sqrt(m_t k / (ln^2 e + pi^2)), eta = 2 sqrt(m_t k) for e = 0, with the
/// tangential effective mass m_t = m*/kappa (m_t = 2 m*/7 for spheres, m*/3 for disks).
inline double restitution_damping(double e, double m_eff, double k, double kappa) {
  const double crit = 2.0 * std::sqrt(m_eff * k / kappa);
  if (e <= 0.0) return crit;
  const double l = std::log(e);
  return crit * (-l) / std::sqrt(l * l + std::numbers::pi * std::numbers::pi);
}

/// Validates a kappa parameter (0 = by dimension, else > 1).
inline void validate_kappa(const char* model, double k) {
  grain::detail::require(std::isfinite(k) && (k == 0.0 || k > 1.0), model, "kappa", k,
                         "(1, inf), or 0 for 7/2 (3D) and 3 (2D)");
}

/// Validates a tangential restitution parameter ([0, 1], or < 0 = not used).
inline void validate_restitution(const char* model, double e) {
  grain::detail::require(std::isfinite(e) && e <= 1.0, model, "restitution", e,
                         "[0, 1], or < 0 for not used");
}

/// The stored elongation rotated into the tangent plane of normal n, keeping its length. In 2D
/// the tangent line is spanned by t = (-n_y, n_x): xi = sign(xi . t) |xi| t (one square root,
/// no division); in 3D the projection xi - (xi . n) n is scaled back to |xi|.
template <int D>
GRAIN_INLINE Vec<D> carried(const PlainVec<D>& stored, const Vec<D>& n) {
  Vec<D> xi = load<D>(stored);
  const double old2 = xi.squaredNorm();
  if constexpr (D == 2) {
    const Vec<D> t(-n.y(), n.x());
    const double s = xi.dot(t);
    if (old2 == 0.0 || s == 0.0) return Vec<D>::Zero(); // (a NaN goes through, as in 3D)
    return std::copysign(std::sqrt(old2), s) * t;
  } else if (old2 > 0.0) {
    xi -= xi.dot(n) * n;
    const double new2 = xi.squaredNorm();
    xi = new2 > 0.0 ? Vec<D>(xi * std::sqrt(old2 / new2)) : Vec<D>(Vec<D>::Zero());
  }
  return xi;
}

/// Negates a stored vector (the partners of a pair swap roles).
template <int D>
inline void negate(PlainVec<D>& s) {
  for (auto& c : s)
    c = -c;
}

/// Coulomb test of a trial force f on a contact with normal force fn. Returns true (sliding)
/// and scales f to mu_d max(fn, 0) if |f| exceeds mu max(fn, 0) (mu = mu_d if `was_sliding`,
/// else mu_s). Only a compressive normal force carries friction: while a damped contact pulls
/// (fn < 0 at the end of an unclamped contact) there is no tangential force.
template <int D>
GRAIN_INLINE bool coulomb(Vec<D>& f, const PairProperties& pair, double fn, bool was_sliding) {
  const double mu = was_sliding ? pair.friction : static_friction(pair);
  const double limit = mu * std::max(fn, 0.0);
  const double f2 = f.squaredNorm();
  if (f2 <= limit * limit) return false;
  f *= pair.friction * std::max(fn, 0.0) / std::sqrt(f2);
  return true;
}

/// A linear spring k [N/m] with a linear dashpot eta [N s/m].
struct LinearSpring {
  double k = 0.0;
  double eta = 0.0;
  double force(double x) const { return k * x; }
  double elongation(double f) const { return k > 0.0 ? f / k : 0.0; }
  double energy(double x) const { return 0.5 * k * x * x; }
  double damping(double /*x*/, double /*speed*/) const { return eta; }
};

/// Spring law of the Mindlin-Deresiewicz loading curve used by the Langston-Tuzun-Heyes and
/// Zheng-Zhu-Yu models: f(x) = F_s (1 - (1 - x/d)^(3/2)) for x < d, F_s beyond, where
/// F_s = mu_s |F_n| [N] and d = delta_t,max [m] is the elongation at full mobilisation. Its
/// slope at x = 0 is 3 F_s / (2 d).
struct SaturatingSpring {
  double fs = 0.0;   ///< saturation force [N]
  double dmax = 0.0; ///< elongation at saturation [m]
  /// sqrt(1 - min(x, d)/d): the square root of the seed's xi, proportional to the slope.
  double root_remaining(double x) const {
    return dmax > 0.0 ? std::sqrt(1.0 - std::min(x, dmax) / dmax) : 0.0;
  }
  double force(double x) const {
    const double s = root_remaining(x);
    return fs * (1.0 - s * s * s);
  }
  double elongation(double f) const {
    if (fs <= 0.0) return 0.0;
    const double q = std::min(f / fs, 1.0);
    return dmax * (1.0 - std::pow(1.0 - q, 2.0 / 3.0));
  }
  double energy(double x) const {
    const double xc = std::min(x, dmax);
    const double s = root_remaining(xc);
    // integral of f from 0 to x: F_s (x + 2/5 d ((1 - x/d)^(5/2) - 1)), linear beyond d
    return fs * (xc + 0.4 * dmax * (s * s * s * s * s - 1.0)) + fs * (x - xc);
  }
};

/// One step of a spring (-dashpot) (-slider) with spring law `law` (members force, elongation,
/// energy, damping(x, |v_t|)); `sliding` = nullptr means no slider (no Coulomb limit).
template <int D, class Law>
GRAIN_INLINE TangentResult<D> spring_step(const ContactGeometry<D>& g, const PairProperties& pair,
                                          double fn, const Law& law, PlainVec<D>& spring,
                                          bool* sliding, double dt) {
  TangentResult<D> r;
  if (!(g.overlap > 0.0)) {
    spring = PlainVec<D>{};
    if (sliding) *sliding = false;
    return r;
  }
  Vec<D> xi = carried<D>(spring, g.normal);
  xi += g.slip_velocity * dt;
  constexpr bool linear = std::is_same_v<Law, LinearSpring>;
  if constexpr (linear) {
    // no lengths needed: F = -k xi - eta v_t, and a sliding spring holds xi = -F / k
    r.force = -law.eta * g.tangential_velocity - law.k * xi;
  } else {
    const double x = xi.norm();
    r.force = -law.damping(x, g.tangential_velocity.norm()) * g.tangential_velocity;
    if (x > 0.0) r.force -= (law.force(x) / x) * xi;
  }
  if (sliding) {
    r.sliding = coulomb<D>(r.force, pair, fn, *sliding);
    *sliding = r.sliding;
    if (r.sliding) {
      if constexpr (linear) {
        xi = law.k > 0.0 ? Vec<D>(r.force * (-1.0 / law.k)) : Vec<D>(Vec<D>::Zero());
      } else {
        const double f = r.force.norm();
        xi = f > 0.0 ? Vec<D>(r.force * (-law.elongation(f) / f)) : Vec<D>(Vec<D>::Zero());
      }
    }
  }
  if constexpr (requires { law.dmax; }) {
    // a saturated spring (|xi| >= delta_t,max: fully mobilised) slides: its elongation stays at
    // the saturation point, so that a reversal unloads it at once
    const double x = xi.norm();
    if (x >= law.dmax && x > 0.0) {
      xi *= law.dmax / x;
      r.sliding = sliding != nullptr;
      if (sliding) *sliding = true;
    }
  }
  store<D>(spring, xi);
  if constexpr (linear)
    r.elastic_energy = 0.5 * law.k * xi.squaredNorm();
  else
    r.elastic_energy = law.energy(xi.norm());
  return r;
}

/// Mindlin's ratio of tangential to normal stiffness, (1 - nu)/(1 - nu/2), nu the pair's mean
/// Poisson ratio (Mindlin, J. Appl. Mech. 16 (1949) 259).
inline double mindlin_ratio(const PairProperties& pair) {
  const double nu = pair.poisson_avg;
  return (1.0 - nu) / (1.0 - 0.5 * nu);
}

/// Stiffness [N/m] of a linear spring: `given` if > 0, else `ratio` (0 = the Mindlin ratio
/// (1 - nu)/(1 - nu/2), nu the mean Poisson ratio) times the normal model's tangent stiffness.
GRAIN_INLINE double linear_stiffness(double given, double ratio, const PairProperties& pair,
                                     const NormalResult& n) {
  if (given > 0.0) return given;
  return (ratio > 0.0 ? ratio : mindlin_ratio(pair)) * n.stiffness;
}

/// Parameters P (members stiffness, stiffness_ratio) with the Mindlin ratio of the pair filled
/// in when the stiffness follows it: the per-pair constant of linear_stiffness worked out once.
template <class P>
P resolve_stiffness_ratio(P p, const PairProperties& pair) {
  if (!(p.stiffness > 0.0) && !(p.stiffness_ratio > 0.0)) p.stiffness_ratio = mindlin_ratio(pair);
  return p;
}

/// Damping [N s/m] with the damping ratio of the normal model: eta_n sqrt(k_t / k_n).
GRAIN_INLINE double normal_ratio_damping(const NormalResult& n, double kt) {
  return n.stiffness > 0.0 ? n.damping * std::sqrt(kt / n.stiffness) : 0.0;
}

} // namespace grain::tangent::detail
