#pragma once
/// \file spring_dashpot_slider.hpp
/// Linear spring-dashpot-slider tangential force with an incremental spring (Cundall & Strack,
/// Geotechnique 29 (1979) 47; history handling as in Luding, Granular Matter 10 (2008) 235).
///
///   F_t = -k_t xi - eta_t v_t,  |F_t| <= mu |F_n|                                     [N]
///
/// History: the spring elongation xi [m], a vector in the tangent plane, rotated with the contact,
/// incremented by the slip velocity that moved the contact (`ContactGeometry::slip_velocity`)
/// and truncated at the Coulomb limit (see stick_slip.hpp); sliding at mu_d, sticking tested
/// against mu_s. v_t is the tangential relative velocity at the contact point seen by the forces.
///
/// - k_t [N/m]: `stiffness` if > 0, else `stiffness_ratio` x the normal model's tangent
///   stiffness k_n; the default ratio (1 - nu)/(1 - nu/2) (nu: mean Poisson ratio of the pair)
///   makes k_t the Mindlin no-slip stiffness 8 G* a for a Hertz contact of equal materials.
/// - eta_t [N s/m], in this order:
///   `damping` if >= 0;
///   else from the tangential restitution coefficient `restitution` = e_t in [0, 1] if given
///   (Deen, van Sint Annaland, van der Hoef & Kuipers, Chem. Eng. Sci. 62 (2007) 28):
///   eta_t = -2 ln(e_t) sqrt(m* k_t / (kappa (ln^2 e_t + pi^2))), eta_t = 2 sqrt(m* k_t/kappa)
///   for e_t = 0, where m*/kappa is the effective mass of the tangential motion of a sticking
///   contact, kappa = 1 + m R^2/I: 7/2 for spheres (Deen's 2 m*/7), 3 for solid disks; set
///   `kappa` = 3.5 for 2D disks with sphere mass;
///   else `damping_factor` f if >= 0: eta_t = f eta_n (the third seed's GRANULAR law takes
///   f = kskn = k_t / k_n, both coefficients scaled by the same ratio);
///   else the normal damping scaled by the stiffnesses, eta_t = eta_n sqrt(k_t / k_n) (LIGGGHTS'
///   convention; as the sticking contact moves with m*/kappa, its damping ratio is sqrt(kappa)
///   times the normal one).
/// - mu_s, mu_d: the pair's static and dynamic friction coefficients.
///
/// Defaults: stiffness 0 (derived), stiffness_ratio 0 (Mindlin), damping -1 (normal ratio),
/// restitution -1 (not used), kappa 0 (by dimension), damping_factor -1 (not used).

#include <cmath>
#include <grain/models/tangent/stick_slip.hpp>

namespace grain::tangent {

struct SpringDashpotSlider {
  static constexpr Slot slot = Slot::tangent;
  static constexpr const char* name = "spring-dashpot-slider";

  struct Params {
    double stiffness = 0.0;       ///< k_t [N/m]; 0 = stiffness_ratio x normal stiffness
    double stiffness_ratio = 0.0; ///< k_t/k_n; 0 = (1 - nu)/(1 - nu/2)
    double damping = -1.0;        ///< eta_t [N s/m]; < 0 = from restitution or normal ratio
    double restitution = -1.0;    ///< tangential restitution e_t in [0, 1]; < 0 = not used
    double kappa = 0.0;           ///< 1 + m R^2/I; 0 = 7/2 (3D) or 3 (2D)
    double damping_factor = -1.0; ///< eta_t / eta_n; < 0 = not used
  };
  template <int D>
  using History = detail::SpringHistory<D>;

  /// The Mindlin stiffness ratio of the pair worked out once (see Interaction::resolve).
  static Params resolve(Params p, const PairProperties& pair) {
    return detail::resolve_stiffness_ratio(p, pair);
  }
  static void validate(const Params& p) {
    constexpr const char* m = "tangent::SpringDashpotSlider";
    grain::detail::require_non_negative(m, "stiffness", p.stiffness);
    grain::detail::require_non_negative(m, "stiffness_ratio", p.stiffness_ratio);
    grain::detail::require(std::isfinite(p.damping), m, "damping", p.damping,
                           "[0, inf), or < 0 for restitution or the normal damping ratio");
    detail::validate_restitution(m, p.restitution);
    detail::validate_kappa(m, p.kappa);
    grain::detail::require(std::isfinite(p.damping_factor), m, "damping_factor", p.damping_factor,
                           "[0, inf), or < 0 when not used");
  }

  template <int D>
  static void reverse(History<D>& h) {
    detail::negate<D>(h.spring);
  }

  /// k_t [N/m] and eta_t [N s/m] of a contact.
  template <int D>
  GRAIN_INLINE static detail::LinearSpring spring(const ContactGeometry<D>& g,
                                                  const PairProperties& pair, const NormalResult& n,
                                                  const Params& p) {
    const double kt = detail::linear_stiffness(p.stiffness, p.stiffness_ratio, pair, n);
    double eta;
    if (p.damping >= 0.0)
      eta = p.damping;
    else if (p.restitution >= 0.0)
      eta = detail::restitution_damping(p.restitution, g.m_eff, kt, detail::kappa<D>(p.kappa));
    else if (p.damping_factor >= 0.0)
      eta = p.damping_factor * n.damping;
    else
      eta = detail::normal_ratio_damping(n, kt);
    return {kt, eta};
  }

  template <int D>
  GRAIN_INLINE static TangentResult<D> force(const ContactGeometry<D>& g,
                                             const PairProperties& pair, const NormalResult& n,
                                             const Params& p, History<D>& h, double dt) {
    return detail::spring_step<D>(g, pair, n.force, spring<D>(g, pair, n, p), h.spring, &h.sliding,
                                  dt);
  }
};

} // namespace grain::tangent
