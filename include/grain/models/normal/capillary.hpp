#pragma once
/// \file capillary.hpp
/// A pendular liquid bridge (capillary force) added to an elastic normal model `Base` (default
/// `normal::Hertz<>`). The bridge forms when the surfaces touch and holds the liquid volume V
/// until the gap s = -delta reaches the rupture distance s_c:
///
///   F_n = F_base(delta, d(delta)/dt) - F_0                          touching (delta > 0) [N]
///   F_n = -F_0 (1 - 1 / sqrt(1 + V / (pi R* s^2)))                  bridged gap 0 < s < s_c
///   F_0 = 4 pi R* gamma cos(theta),   s_c = (1 + theta/2) V^(1/3)
///
/// gamma [N/m] is the liquid's surface tension, theta [rad] the contact angle (in [0, pi/2]),
/// V [m^3] the liquid volume of a bridge, R* [m] the effective radius of the pair (R* = R on a
/// flat wall). F_0 is the force of a bridge at contact (Fisher 1926; 2 pi R gamma cos(theta) for
/// two spheres of radius R, 4 pi R gamma cos(theta) for a sphere on a plane). The force across a
/// gap is that of the Derjaguin approximation with a toroidal meniscus and the volume of a
/// cylinder between the two paraboloids, Rabinovich et al., Langmuir 21 (2005) 10992, Eq. 6
/// without its filling-angle term (which vanishes as V / R*^3 -> 0); the rupture distance is
/// that of Lian, Thornton & Adams, J. Colloid Interface Sci. 161 (1993) 138. Across a bridged
/// gap the bridge pulls the particles together (no damping); beyond s_c it breaks, and forms
/// again only when the surfaces touch. The search reaches s_c beyond contact (`reach`).
///
/// Friction: the tangential and rolling models limit their forces with the load F_n + F_0 (the
/// compressive force of the base model: `NormalResult::adhesion` = F_0). Across a gap only the
/// normal force acts: the tangential and rolling histories are cleared and no heat flows.
///
/// History: the base model's and whether the bridge stands (one byte).

#include <cmath>
#include <cstdint>
#include <cstring>
#include <grain/core/error.hpp>
#include <grain/models/concepts.hpp>
#include <grain/models/normal/hertz.hpp>
#include <numbers>

namespace grain::normal {

template <class Base = Hertz<>>
struct Capillary {
  static_assert(NormalModel<Base>,
                "grain::normal::Capillary<Base>: Base must be an elastic normal-force model such "
                "as normal::Hertz<> or normal::LinearSpringDashpot (see docs/cohesion.md)");
  static_assert(!cohesive_model<Base>,
                "grain::normal::Capillary<Base>: Base must not be adhesive itself; use "
                "normal::Hertz<> or normal::LinearSpringDashpot as Base");
  static constexpr Slot slot = Slot::normal;
  static constexpr const char* name = "capillary bridge";
  static constexpr const char* object = "normal::Capillary";
  static constexpr bool cohesive = true;

  struct Params {
    double surface_tension = 0.0; ///< gamma [N/m] (>= 0; water at 20 C: 0.0728)
    double contact_angle = 0.0;   ///< theta [rad], in [0, pi/2]
    double liquid_volume = 0.0;   ///< V [m^3] of one bridge (> 0)
    typename Base::Params base{}; ///< the elastic model's coefficients
  };
  template <int D>
  struct History {
    [[no_unique_address]] typename Base::template History<D> base{};
    std::uint8_t bridge = 0; ///< 1 while the liquid bridge stands
    /// False if the bytes read from a file are not a history.
    static bool valid_bytes(const History& h) {
      std::uint8_t b;
      std::memcpy(&b, &h.bridge, 1);
      if constexpr (requires { Base::template History<D>::valid_bytes(h.base); })
        if (!Base::template History<D>::valid_bytes(h.base)) return false;
      return b <= 1;
    }
  };

  static void validate(const Params& p) {
    detail::require(std::isfinite(p.surface_tension) && p.surface_tension >= 0.0, object,
                    "surface_tension", p.surface_tension, "[0, inf) N/m");
    detail::require(p.contact_angle >= 0.0 && p.contact_angle <= 0.5 * std::numbers::pi, object,
                    "contact_angle", p.contact_angle, "[0, pi/2] rad");
    detail::require(std::isfinite(p.liquid_volume) && p.liquid_volume > 0.0, object,
                    "liquid_volume", p.liquid_volume, "(0, inf) m^3 (the volume of one bridge)");
    Base::validate(p.base);
  }
  static Params resolve(Params p, const PairProperties& pair) {
    if constexpr (requires { Base::resolve(p.base, pair); }) p.base = Base::resolve(p.base, pair);
    return p;
  }
  template <int D>
  static void reverse(History<D>& h) {
    reverse_history<Base, D>(h.base);
  }

  /// s_c = (1 + theta/2) V^(1/3) [m].
  static double rupture_distance(const Params& p) {
    return (1.0 + 0.5 * p.contact_angle) * std::cbrt(p.liquid_volume);
  }
  /// The largest gap [m] across which a bridge acts: s_c.
  static double reach(const Params& p, const PairProperties&, double) {
    return rupture_distance(p);
  }
  /// F_0 = 4 pi R* gamma cos(theta) [N].
  static double contact_force(const Params& p, double r_eff) {
    return 4.0 * std::numbers::pi * r_eff * p.surface_tension * std::cos(p.contact_angle);
  }
  /// The attraction of a bridge across the gap s >= 0 [N].
  static double bridge_force(const Params& p, double r_eff, double s) {
    const double f0 = contact_force(p, r_eff);
    if (!(s > 0.0)) return f0;
    return f0 * (1.0 - 1.0 / std::sqrt(1.0 + p.liquid_volume / (std::numbers::pi * r_eff * s * s)));
  }

  template <int D>
  static NormalResult force(const ContactGeometry<D>& g, const PairProperties& pair,
                            const Params& p, History<D>& h) {
    if (g.overlap > 0.0) {
      h.bridge = 1;
      NormalResult n = Base::force(g, pair, p.base, h.base);
      const double f0 = contact_force(p, g.r_eff);
      n.force -= f0;
      n.elastic_energy -= f0 * g.overlap;
      n.adhesion = f0;
      return n;
    }
    h.base = {};
    const double s = -g.overlap;
    if (h.bridge == 0 || !(s < rupture_distance(p))) {
      h.bridge = 0;
      return {.detached = true};
    }
    const double f = bridge_force(p, g.r_eff, s);
    return {.force = -f, .detached = true, .adhesion = f};
  }

  static double stiffness_estimate(const PairProperties& pair, const Params& p, double r_eff,
                                   double m_eff, double v) {
    return Base::stiffness_estimate(pair, p.base, r_eff, m_eff, v);
  }
};

} // namespace grain::normal
