#pragma once
/// \file dmt.hpp
/// Adhesion of Derjaguin, Muller and Toporov (DMT) added to an elastic normal model `Base`
/// (default `normal::Hertz<>`, the DMT theory's own elastic law):
///
///   F_n = F_base(delta, d(delta)/dt) - 2 pi w R*                                    [N]
///
/// while the surfaces touch (delta > 0); nothing across a gap. (Derjaguin, Muller & Toporov,
/// J. Colloid Interface Sci. 53 (1975) 314; Maugis, Contact, Adhesion and Rupture of Elastic
/// Solids, 2000, ch. 5.) w [J/m^2] is the work of adhesion (`work_of_adhesion`: 2 gamma for two
/// surfaces of one material of surface energy gamma), R* [m] the effective radius of the pair
/// (R* = R on a flat wall). The adhesive force is the DMT pull-off force F_c = 2 pi w R*, which
/// the contact reaches as delta falls to 0 (the elastic part vanishes there); the contact breaks
/// at delta = 0. DMT suits stiff, small particles with little adhesion (Tabor parameter below
/// about 0.1); `normal::Jkr` the soft, strongly adhesive ones.
///
/// Friction under tension: the tangential and rolling models limit their forces with the load
/// F_n + F_c, the base model's compressive force (`NormalResult::adhesion` = F_c), so the
/// adhesion presses the surfaces together as an applied load would.
///
/// Stiffness, damping and history are the base model's (F_c does not depend on delta); the
/// elastic energy is the base model's minus F_c delta (the adhesion's work since first touch).

#include <cmath>
#include <grain/core/error.hpp>
#include <grain/models/concepts.hpp>
#include <grain/models/normal/hertz.hpp>
#include <numbers>

namespace grain::normal {

template <class Base = Hertz<>>
struct Dmt {
  static_assert(NormalModel<Base>,
                "grain::normal::Dmt<Base>: Base must be an elastic normal-force model such as "
                "normal::Hertz<> or normal::LinearSpringDashpot (see docs/cohesion.md)");
  static_assert(!cohesive_model<Base>,
                "grain::normal::Dmt<Base>: Base must not be adhesive itself; use normal::Hertz<> "
                "or normal::LinearSpringDashpot as Base, or normal::Jkr on its own");
  static constexpr Slot slot = Slot::normal;
  static constexpr const char* name = "DMT adhesion";
  static constexpr const char* object = "normal::Dmt";
  static constexpr bool cohesive = true;

  struct Params {
    double work_of_adhesion = 0.0; ///< w [J/m^2] (>= 0)
    typename Base::Params base{};  ///< the elastic model's coefficients
  };
  template <int D>
  using History = typename Base::template History<D>;

  static void validate(const Params& p) {
    detail::require(std::isfinite(p.work_of_adhesion) && p.work_of_adhesion >= 0.0, object,
                    "work_of_adhesion", p.work_of_adhesion, "[0, inf) J/m^2");
    Base::validate(p.base);
  }
  static Params resolve(Params p, const PairProperties& pair) {
    if constexpr (requires { Base::resolve(p.base, pair); }) p.base = Base::resolve(p.base, pair);
    return p;
  }
  template <int D>
  static void reverse(History<D>& h) {
    reverse_history<Base, D>(h);
  }

  /// The DMT force acts in contact only.
  static double reach(const Params&, const PairProperties&, double) { return 0.0; }

  /// F_c = 2 pi w R* [N].
  static double pull_off(const Params& p, double r_eff) {
    return 2.0 * std::numbers::pi * p.work_of_adhesion * r_eff;
  }

  template <int D>
  GRAIN_INLINE static NormalResult force(const ContactGeometry<D>& g, const PairProperties& pair,
                                         const Params& p, History<D>& h) {
    NormalResult n = Base::force(g, pair, p.base, h);
    const double fc = pull_off(p, g.r_eff);
    n.force -= fc;
    n.elastic_energy -= fc * g.overlap;
    n.adhesion = fc;
    return n;
  }

  static double stiffness_estimate(const PairProperties& pair, const Params& p, double r_eff,
                                   double m_eff, double v) {
    return Base::stiffness_estimate(pair, p.base, r_eff, m_eff, v);
  }
};

} // namespace grain::normal
