#pragma once
/// \file epsd.hpp
/// Elastic-plastic spring-dashpot rolling resistance, EPSD ("model C" of Ai, Chen, Rotter &
/// Ooi, Powder Technol. 206 (2011) 269; rolling stiffness after Iwashita & Oda, J. Eng. Mech.
/// 124 (1998) 285).
///
///   k_r = 2.25 k_n mu_r^2 R*^2                                                [N m/rad]
///   M_k <- M_k - k_r w_r dt,  |M_k| <= M_m = mu_r R* |F_n|  (full mobilisation)        [N m]
///   M_d = -C_r w_r (f C_r w_r at full mobilisation),  C_r = 2 eta_r sqrt(I_r k_r)  [N m s]
///   M_i = M_k + M_d,  M_j = -M_i                                                     [N m]
///
/// k_n [N/m] is the normal model's tangent stiffness (K for a linear spring, 2 E* a for Hertz;
/// codes that use the Hertz secant F_n/delta get 2/3 of this k_r), mu_r [-] the
/// rolling-resistance coefficient, R* [m] the effective radius, F_n [N] the normal force and w_r
/// [rad/s] the rolling part of w_i - w_j (relative_rotation.hpp). The spring torque M_k is the
/// history: a vector in the tangent plane (3D, rotated with the contact like the tangential
/// spring) or a scalar (2D). It is incremented with the rolling part of
/// `ContactGeometry::slip_omega_rel` (the angular velocities that turned the particles over the
/// step; with velocity Verlet the damping torque M_d sees those predicted at the end of the step,
/// `omega_rel`) and truncated at M_m, which gives a true static regime
/// (a ball at rest on a slope below the rolling angle stays at rest) and, once mobilised, the
/// constant resistance of rolling::Constant. The torque on the partner is equal and opposite.
/// Elastic energy |M_k|^2 / (2 k_r).
///
/// I_r [kg m^2] is the moment of inertia of the rolling mode about the contact point. Ai et al.
/// use 1/I_r = 1/(I_i + m_i R_i^2) + 1/(I_j + m_j R_j^2); the contact geometry carries only the
/// pair's m* and R*, so here I_r = (1 + c) m* R*^2 with c = I/(m R^2) (2/5 sphere, 1/2 solid
/// disk). This is exact for a particle on a wall; for two equal particles it is 1/4 of Ai's
/// I_r, so a given eta_r damps a pair's rolling mode at half the ratio eta_r.
///
/// - mu_r: `coefficient` if >= 0, else the pair's `rolling_friction` (default -1).
/// - k_r [N m/rad]: `stiffness` if > 0, else 2.25 k_n mu_r^2 R*^2 (default 0).
/// - eta_r [-]: `damping_ratio` (default 0.3), the viscous damping ratio of the rolling mode.
/// - f: `damping_at_limit` (default false: f = 0, no damping torque while fully mobilised).
/// - c: `inertia_factor` if > 0, else 2/5 (3D) or 1/2 (2D); the model does not see the shape,
///   so 2D disks with sphere mass need `inertia_factor` = 0.4.

#include <algorithm>
#include <cmath>
#include <grain/models/rolling/relative_rotation.hpp>
#include <type_traits>

namespace grain::rolling {

struct EPSD {
  static constexpr Slot slot = Slot::rolling;
  static constexpr const char* name = "EPSD";

  struct Params {
    double coefficient = -1.0;     ///< mu_r [-]; < 0 = the pair's rolling_friction
    double stiffness = 0.0;        ///< k_r [N m/rad]; 0 = 2.25 k_n mu_r^2 R*^2
    double damping_ratio = 0.3;    ///< eta_r [-]
    bool damping_at_limit = false; ///< keep the damping torque at full mobilisation (f = 1)
    double inertia_factor = 0.0;   ///< c = I/(m R^2); 0 = 2/5 (3D) or 1/2 (2D)
  };
  /// The spring torque M_k [N m]: a scalar in 2D, a vector in 3D.
  template <int D>
  struct History {
    std::conditional_t<D == 2, double, PlainVec<3>> torque{};
  };

  static void validate(const Params& p) {
    constexpr const char* m = "rolling::EPSD";
    detail::validate_coefficient(m, p.coefficient);
    grain::detail::require_non_negative(m, "stiffness", p.stiffness);
    grain::detail::require_non_negative(m, "damping_ratio", p.damping_ratio);
    grain::detail::require(
        std::isfinite(p.inertia_factor) && p.inertia_factor >= 0.0 && p.inertia_factor <= 1.0, m,
        "inertia_factor", p.inertia_factor, "(0, 1], or 0 for 2/5 (3D) and 1/2 (2D)");
  }

  /// Swapping the partners negates the spring torque.
  template <int D>
  static void reverse(History<D>& h) {
    if constexpr (D == 2)
      h.torque = -h.torque;
    else
      for (auto& c : h.torque)
        c = -c;
  }

  /// k_r [N m/rad] of a contact.
  template <int D>
  static double rolling_stiffness(const ContactGeometry<D>& g, const PairProperties& pair,
                                  const NormalResult& n, const Params& p) {
    if (p.stiffness > 0.0) return p.stiffness;
    const double mu = detail::coefficient(p.coefficient, pair);
    return 2.25 * std::max(n.stiffness, 0.0) * mu * mu * g.r_eff * g.r_eff;
  }

  /// Elastic energy |M_k|^2 / (2 k_r) [J] of a history.
  template <int D>
  static double elastic_energy(const History<D>& h, double kr) {
    if (!(kr > 0.0)) return 0.0;
    if constexpr (D == 2)
      return 0.5 * h.torque * h.torque / kr;
    else
      return 0.5 * load<3>(h.torque).squaredNorm() / kr;
  }

  template <int D, class A>
  GRAIN_INLINE static void torque(const ContactGeometry<D>& g, const PairProperties& pair,
                                  const NormalResult& n, const Params& p, History<D>& h, double dt,
                                  A& ti, A& tj) {
    if (!(g.overlap > 0.0)) {
      h = History<D>{};
      return;
    }
    const double mu = detail::coefficient(p.coefficient, pair);
    const double kr = rolling_stiffness<D>(g, pair, n, p);
    const A w = detail::rolling_omega(g);
    A mk = spring_torque(h, g.normal);
    mk -= kr * dt * detail::rolling_slip_omega(g);
    const double limit = mu * g.r_eff * std::max(n.force, 0.0);
    const double size = norm(mk);
    const bool full = size > limit;
    if (full) mk *= size > 0.0 ? limit / size : 0.0;
    const double c = p.inertia_factor > 0.0 ? p.inertia_factor : (D == 3 ? 0.4 : 0.5);
    const double ir = (1.0 + c) * g.m_eff * g.r_eff * g.r_eff;
    const double cr =
        (full && !p.damping_at_limit) ? 0.0 : 2.0 * p.damping_ratio * std::sqrt(ir * kr);
    if constexpr (D == 2)
      h.torque = mk;
    else
      store<3>(h.torque, mk);
    detail::apply<A>(A(mk - cr * w), ti, tj);
  }

private:
  /// The stored spring torque, rotated into the current tangent plane (3D) keeping its size.
  static double spring_torque(const History<2>& h, const Vec2&) { return h.torque; }
  static Vec3 spring_torque(const History<3>& h, const Vec3& n) {
    Vec3 m = load<3>(h.torque);
    const double old2 = m.squaredNorm();
    if (old2 > 0.0) {
      m -= m.dot(n) * n;
      const double new2 = m.squaredNorm();
      m = new2 > 0.0 ? Vec3(m * std::sqrt(old2 / new2)) : Vec3(Vec3::Zero());
    }
    return m;
  }
};

} // namespace grain::rolling
