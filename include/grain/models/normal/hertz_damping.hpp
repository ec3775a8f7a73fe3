#pragma once
/// \file hertz_damping.hpp
/// Damping policies of `normal::Hertz<Damping>`: the viscous part F_v = eta(delta) d(delta)/dt
/// added to the Hertz elastic force K_hz delta^(3/2), K_hz = 4/3 E* sqrt(R*).
///
// clang-format off
/// | policy | eta(delta) [N s/m] | parameter (in `Hertz<P>::Params::damping`) | restitution |
/// |---|---|---|---|
/// | `TsujiDamping` | alpha sqrt(m* K_hz) delta^(1/4) | `alpha` (dimensionless, default from e) | e(alpha), independent of v |
/// | `CriticalRatioDamping` | xi sqrt(8 E* m* sqrt(R*)) delta^(1/4) | `ratio` xi (required) | e(xi sqrt(6)) as Tsuji |
/// | `KuwabaraKonoDamping` | eta_KK delta^(1/2) | `coefficient` eta_KK [N s/m^(3/2)] (required) | decreases with v |
/// | `LeeHerrmannDamping` | eta_LH m* | `coefficient` eta_LH [1/s] (required) | depends on v |
// clang-format on
///
/// A policy is a struct with `name` (its C++ name, used in error messages), `Params` (default
/// constructible), `static void validate(const Params&, const std::string& object)` (throws
/// `InputError` through `detail::require*`) and `static double coefficient(const PairProperties&,
/// const Params&, double k_secant, double r_eff, double m_eff, double delta)` returning eta
/// [N s/m] at the overlap delta, where k_secant = K_hz sqrt(delta) = 4/3 E* a [N/m] is the secant
/// stiffness F_el/delta (a = sqrt(R* delta), computed once per contact); optionally `hertz_name`,
/// the readable name of the whole model.

#include <cmath>
#include <grain/core/config.hpp>
#include <grain/core/error.hpp>
#include <grain/particles/material.hpp>
#include <numbers>
#include <string>

namespace grain::normal {

/// Restitution map of `TsujiDamping`: alpha as a function of the restitution coefficient e.
enum class TsujiMap {
  exact,  ///< alpha = sqrt(5) |ln e| / sqrt(ln^2 e + pi^2) (exact inverse; default)
  norouzi ///< alpha = 2.2664 |ln e| / sqrt(ln^2 e + 10.1354) (fit used by DEMLab)
};

/// Tsuji, Tanaka & Ishida (Powder Technol. 71 (1992) 239) damping,
/// F_v = alpha sqrt(m* K_hz) delta^(1/4) d(delta)/dt.
///
/// The rebound restitution of an isolated contact depends on alpha only (not on the impact
/// velocity). By default alpha comes from the pair's restitution e through the exact inverse
/// alpha = sqrt(5) |ln e| / sqrt(ln^2 e + pi^2) (Antypov & Elliott, EPL 94 (2011) 50004; the
/// damping of LIGGGHTS' "hertz" model), so the contact rebounds with e. `TsujiMap::norouzi`
/// selects the fit alpha = 2.2664 |ln e| / sqrt(ln^2 e + 10.1354) (Norouzi et al., Coupled
/// CFD-DEM Modeling, Wiley 2016; the DEMLab default), whose rebound deviates from e by up to
/// 0.002 (e = 0.1 gives 0.0983). A given `alpha` >= 0 overrides both maps.
struct TsujiDamping {
  static constexpr const char* name = "TsujiDamping";
  static constexpr const char* hertz_name = "Hertz with Tsuji damping";
  struct Params {
    TsujiMap map = TsujiMap::exact; ///< restitution map used when alpha < 0
    double alpha = -1.0;            ///< alpha (dimensionless); < 0 = from the restitution map
  };
  static void validate(const Params& p, const std::string& object) {
    detail::require(p.map == TsujiMap::exact || p.map == TsujiMap::norouzi, object, "damping.map",
                    static_cast<int>(p.map), "TsujiMap::exact or TsujiMap::norouzi");
    detail::require(std::isfinite(p.alpha), object, "damping.alpha", p.alpha,
                    "[0, inf), or < 0 for alpha from the restitution coefficient");
  }
  /// alpha of the exact map for restitution e = exp(log_e).
  static double exact_alpha(double log_e) {
    return std::sqrt(5.0) * std::abs(log_e) /
           std::sqrt(log_e * log_e + std::numbers::pi * std::numbers::pi);
  }
  /// alpha of the Norouzi et al. fit for restitution e = exp(log_e).
  static double norouzi_alpha(double log_e) {
    return 2.2664 * std::abs(log_e) / std::sqrt(log_e * log_e + 10.1354);
  }
  /// The damping constant alpha of a pair with the default (exact) map.
  static double alpha(const PairProperties& pair) { return exact_alpha(pair.log_restitution); }
  /// The damping constant alpha of a pair with these parameters.
  static double alpha(const PairProperties& pair, const Params& p) {
    if (p.alpha >= 0.0) return p.alpha;
    return p.map == TsujiMap::norouzi ? norouzi_alpha(pair.log_restitution)
                                      : exact_alpha(pair.log_restitution);
  }
  /// alpha of the pair worked out once (given, or from its restitution by the map).
  static Params resolve(Params p, const PairProperties& pair) {
    p.alpha = alpha(pair, p);
    return p;
  }
  GRAIN_INLINE static double coefficient(const PairProperties& pair, const Params& p,
                                         double k_secant, double, double m_eff, double) {
    return alpha(pair, p) * std::sqrt(m_eff * k_secant);
  }
};

/// Damping as a ratio xi of the critical damping of the contact's tangent stiffness
/// k(delta) = 2 E* sqrt(R* delta) (DEMLab "critical_ratio"):
/// F_v = xi sqrt(8 E* m* sqrt(R*)) delta^(1/4) d(delta)/dt = xi 2 sqrt(m* k(delta)) d(delta)/dt.
/// Since 8 E* sqrt(R*) = 6 K_hz this is Tsuji damping with alpha = sqrt(6) xi, so the
/// restitution depends on xi only. `ratio` must be given.
struct CriticalRatioDamping {
  static constexpr const char* name = "CriticalRatioDamping";
  static constexpr const char* hertz_name = "Hertz with critical-ratio damping";
  struct Params {
    double ratio = -1.0; ///< xi (dimensionless), >= 0; required
  };
  static void validate(const Params& p, const std::string& object) {
    detail::require(std::isfinite(p.ratio) && p.ratio >= 0.0, object, "damping.ratio", p.ratio,
                    "[0, inf) (the critical damping ratio must be given)");
  }
  // 8 E* sqrt(R*) delta^(1/2) = 8 E* a = 6 k_secant
  GRAIN_INLINE static double coefficient(const PairProperties&, const Params& p, double k_secant,
                                         double, double m_eff, double) {
    return p.ratio * std::sqrt(6.0 * m_eff * k_secant);
  }
};

/// Kuwabara & Kono (Jpn. J. Appl. Phys. 26 (1987) 1230) viscoelastic damping, as in DEMLab:
/// F_v = eta_KK delta^(1/2) d(delta)/dt with eta_KK [N s/m^(3/2)] given (`coefficient`).
/// The restitution depends on kappa = eta_KK v^(1/5) / (K_hz^(3/5) m*^(2/5)):
/// e = 1 - 1.1534 kappa + 0.7983 kappa^2 + O(kappa^3) (Schwager & Poeschel, Phys. Rev. E 57
/// (1998) 650), so it decreases with the impact velocity v, 1 - e ~ v^(1/5).
struct KuwabaraKonoDamping {
  static constexpr const char* name = "KuwabaraKonoDamping";
  static constexpr const char* hertz_name = "Hertz with Kuwabara-Kono damping";
  struct Params {
    double coefficient = -1.0; ///< eta_KK [N s/m^(3/2)], >= 0; required
  };
  static void validate(const Params& p, const std::string& object) {
    detail::require(std::isfinite(p.coefficient) && p.coefficient >= 0.0, object,
                    "damping.coefficient", p.coefficient,
                    "[0, inf) N s/m^1.5 (the Kuwabara-Kono coefficient must be given)");
  }
  GRAIN_INLINE static double coefficient(const PairProperties&, const Params& p, double, double,
                                         double, double delta) {
    return p.coefficient * std::sqrt(delta);
  }
};

/// Lee & Herrmann (J. Phys. A 26 (1993) 373) damping, as in DEMLab: F_v = eta_LH m* d(delta)/dt
/// with eta_LH [1/s] given (`coefficient`); the restitution depends on the impact velocity.
struct LeeHerrmannDamping {
  static constexpr const char* name = "LeeHerrmannDamping";
  static constexpr const char* hertz_name = "Hertz with Lee-Herrmann damping";
  struct Params {
    double coefficient = -1.0; ///< eta_LH [1/s], >= 0; required
  };
  static void validate(const Params& p, const std::string& object) {
    detail::require(std::isfinite(p.coefficient) && p.coefficient >= 0.0, object,
                    "damping.coefficient", p.coefficient,
                    "[0, inf) 1/s (the Lee-Herrmann coefficient must be given)");
  }
  GRAIN_INLINE static double coefficient(const PairProperties&, const Params& p, double, double,
                                         double m_eff, double) {
    return p.coefficient * m_eff;
  }
};

} // namespace grain::normal
