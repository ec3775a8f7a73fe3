#pragma once
/// \file material.hpp
/// Materials of particles and walls, and the effective properties of a pair of materials.
///
/// Units: density kg/m^3, moduli Pa, conductivity W/(m K), heat capacity J/(kg K).
/// Shear modulus G = E / (2 (1 + nu)) unless given. `young_real` is the real Young's modulus of
/// a material simulated with a softened `young` (used by contact-area corrections); it defaults to
/// `young`.
///
/// Pair mixing (Johnson, Contact Mechanics, 1985):
/// 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2;  1/G* = (2 - nu1)/G1 + (2 - nu2)/G2;
/// restitution and friction of a pair are the arithmetic means of the two materials unless
/// overridden for that pair.

#include <cmath>
#include <grain/core/error.hpp>
#include <grain/core/vector.hpp>
#include <numbers>
#include <string>

namespace grain {

struct Material {
  std::string name = "material";
  double density = 0.0;          ///< [kg/m^3], > 0
  double young = 0.0;            ///< Young's modulus used in the simulation [Pa], > 0
  double poisson = 0.25;         ///< Poisson ratio, in (-1, 0.5)
  double shear = 0.0;            ///< shear modulus [Pa]; 0 = derived as E/(2(1+nu))
  double young_real = 0.0;       ///< real Young's modulus [Pa]; 0 = same as `young`
  double restitution = 0.5;      ///< normal coefficient of restitution, in (0, 1]
  double friction = 0.5;         ///< Coulomb (sliding) friction coefficient, >= 0
  double friction_static = -1.0; ///< static friction coefficient; < 0 = same as `friction`
  double rolling_friction = 0.0; ///< rolling resistance coefficient, >= 0
  double conductivity = 0.0;     ///< thermal conductivity [W/(m K)], >= 0
  double heat_capacity = 0.0;    ///< specific heat capacity [J/(kg K)], >= 0
  /// Total hemispherical emissivity of the surface, in [0, 1]: read by a radiation model
  /// (grain::radiation); 0 = the material does not radiate.
  double emissivity = 0.0;

  double shear_modulus() const { return shear > 0.0 ? shear : young / (2.0 * (1.0 + poisson)); }
  double real_young() const { return young_real > 0.0 ? young_real : young; }

  /// Throws `InputError` naming this material, the value and its valid range.
  void validate() const {
    const std::string obj = "Material '" + name + "'";
    detail::require_positive(obj, "density", density);
    detail::require_positive(obj, "young", young);
    detail::require(std::isfinite(poisson) && poisson > -1.0 && poisson < 0.5, obj, "poisson",
                    poisson, "(-1, 0.5)");
    detail::require_non_negative(obj, "shear", shear);
    detail::require_non_negative(obj, "young_real", young_real);
    detail::require(std::isfinite(restitution) && restitution > 0.0 && restitution <= 1.0, obj,
                    "restitution", restitution, "(0, 1]");
    detail::require_non_negative(obj, "friction", friction);
    detail::require(std::isfinite(friction_static), obj, "friction_static", friction_static,
                    "a finite number (< 0 means same as friction)");
    detail::require_non_negative(obj, "rolling_friction", rolling_friction);
    detail::require_non_negative(obj, "conductivity", conductivity);
    detail::require_non_negative(obj, "heat_capacity", heat_capacity);
    detail::require(std::isfinite(emissivity) && emissivity >= 0.0 && emissivity <= 1.0, obj,
                    "emissivity", emissivity, "[0, 1]");
  }
};

/// The fluid around the particles (for convection and for conduction through the interstitial
/// fluid). Units: K, m/s, kg/m^3, Pa s, W/(m K), J/(kg K). There is no flow solver: temperature
/// and velocity are uniform.
template <int D>
struct Fluid {
  double temperature = 293.15;      ///< [K]
  Vec<D> velocity = Vec<D>::Zero(); ///< [m/s]
  double density = 0.0;             ///< [kg/m^3]
  double viscosity = 0.0;           ///< dynamic viscosity [Pa s]
  double conductivity = 0.0;        ///< [W/(m K)]
  double heat_capacity = 0.0;       ///< [J/(kg K)]

  void validate() const {
    detail::require_finite("Fluid", "temperature", temperature);
    detail::require(temperature >= 0.0, "Fluid", "temperature", temperature, "[0, inf) K");
    for (int d = 0; d < D; ++d)
      detail::require_finite("Fluid", "velocity component", velocity[d]);
    detail::require_non_negative("Fluid", "density", density);
    detail::require_non_negative("Fluid", "viscosity", viscosity);
    detail::require_non_negative("Fluid", "conductivity", conductivity);
    detail::require_non_negative("Fluid", "heat_capacity", heat_capacity);
  }
};

/// Optional per-pair overrides of the mixed values (negative = use the mixing rule).
struct PairOverride {
  double restitution = -1.0;
  double friction = -1.0;
  double friction_static = -1.0;
  double rolling_friction = -1.0;
};

/// Effective properties of a pair of materials; computed once per material pair.
struct PairProperties {
  double young_eff = 0.0;       ///< E* [Pa]
  double young_real_eff = 0.0;  ///< E*_0 from the real moduli [Pa]
  double shear_eff = 0.0;       ///< G* [Pa]
  double poisson_avg = 0.0;     ///< (nu1 + nu2)/2
  double restitution = 1.0;     ///< e
  double log_restitution = 0.0; ///< ln e (<= 0)
  double friction = 0.0;        ///< dynamic (sliding) friction coefficient
  double friction_static = 0.0; ///< static friction coefficient (>= dynamic)
  double rolling_friction = 0.0;
  double conductivity_eff = 0.0; ///< k1 k2/(k1 + k2) [W/(m K)]
  double conductivity_i = 0.0;   ///< k1 of the first material (particle i) [W/(m K)]
  double conductivity_j = 0.0;   ///< k2 of the second material (particle j or wall) [W/(m K)]
  double heat_capacity_i = 0.0;  ///< c1 [J/(kg K)]
  double heat_capacity_j = 0.0;  ///< c2 [J/(kg K)]
  double density_i = 0.0;        ///< rho1 [kg/m^3]
  double density_j = 0.0;        ///< rho2 [kg/m^3]
  double fluid_conductivity =
      0.0; ///< k_f of the interstitial fluid [W/(m K)] (set by the simulation)

  /// beta = ln e / sqrt(ln^2 e + pi^2), in (-1, 0]: the damping ratio that gives restitution e
  /// for a linear spring-dashpot is -beta.
  double damping_ratio() const {
    const double l = log_restitution;
    return -l / std::sqrt(l * l + std::numbers::pi * std::numbers::pi);
  }

  static PairProperties mix(const Material& a, const Material& b, const PairOverride& o = {}) {
    PairProperties p;
    p.young_eff =
        1.0 / ((1 - a.poisson * a.poisson) / a.young + (1 - b.poisson * b.poisson) / b.young);
    p.young_real_eff = 1.0 / ((1 - a.poisson * a.poisson) / a.real_young() +
                              (1 - b.poisson * b.poisson) / b.real_young());
    p.shear_eff = 1.0 / ((2 - a.poisson) / a.shear_modulus() + (2 - b.poisson) / b.shear_modulus());
    p.poisson_avg = 0.5 * (a.poisson + b.poisson);
    p.restitution = o.restitution > 0 ? o.restitution : 0.5 * (a.restitution + b.restitution);
    p.log_restitution = std::log(p.restitution);
    p.friction = o.friction >= 0 ? o.friction : 0.5 * (a.friction + b.friction);
    const double sa = a.friction_static >= 0 ? a.friction_static : a.friction;
    const double sb = b.friction_static >= 0 ? b.friction_static : b.friction;
    p.friction_static = o.friction_static >= 0 ? o.friction_static : 0.5 * (sa + sb);
    if (p.friction_static < p.friction) p.friction_static = p.friction;
    p.rolling_friction = o.rolling_friction >= 0 ? o.rolling_friction
                                                 : 0.5 * (a.rolling_friction + b.rolling_friction);
    const double ks = a.conductivity + b.conductivity;
    p.conductivity_eff = ks > 0 ? a.conductivity * b.conductivity / ks : 0.0;
    p.conductivity_i = a.conductivity;
    p.conductivity_j = b.conductivity;
    p.heat_capacity_i = a.heat_capacity;
    p.heat_capacity_j = b.heat_capacity;
    p.density_i = a.density;
    p.density_j = b.density;
    return p;
  }
};

} // namespace grain
