#pragma once
/// \file zhou_yu_zulli.hpp
/// Thermal radiation of a particle in a packed or fluidised bed with its local environment
/// (Z. Y. Zhou, A. B. Yu, P. Zulli, "Particle scale study of heat transfer in packed and bubbling
/// fluidized beds", AIChE J. 55 (2009) 868-884):
///
///   Q_i = sigma eps_i A_i (T_local,i^4 - T_i^4)                                        [W]
///   T_local,i = phi T_f + (1 - phi) (1/k) sum_{j in Omega, j != i} T_j                 [K]
///
/// sigma = 5.670374419e-8 W/(m^2 K^4) the Stefan-Boltzmann constant, eps_i the emissivity of
/// particle i's material (`Material::emissivity`), A_i its surface (4 pi R^2; 2 pi R L for a
/// disk of length L), T_f the fluid temperature (`Fluid::temperature`), Omega the sphere (disk)
/// of radius `domain` x 2 R_i about the particle's centre (1.5 particle diameters in the paper:
/// the particle's nearest neighbours and the next shell partly), k the number of other particles
/// whose centres lie in Omega and phi the porosity of Omega seen from particle i: the fraction of
/// its volume outside particle i not taken by those k particles (whole particles counted,
/// clamped to [0, 1]; phi = 1 and T_local = T_f without neighbours). Walls are not part of the
/// environment.
///
/// Each particle exchanges with its own environment: the model does not conserve energy between
/// particles (the radiation a particle loses is not the sum of what its neighbours gain), as in
/// the paper. Gas radiation is neglected (low gas emissivity). Validity: packed and bubbling
/// beds of grey, opaque, mono-sized particles at a few hundred to about 1500 K, where a particle
/// sees mostly its neighbours; the paper validates the bed's effective conductivity against
/// measurements up to 1300 K.

#include <cmath>
#include <grain/core/error.hpp>
#include <grain/models/concepts.hpp>
#include <limits>

namespace grain::radiation {

struct ZhouYuZulli {
  static constexpr Slot slot = Slot::radiation;
  static constexpr const char* name = "Zhou-Yu-Zulli";
  static constexpr bool active = true;
  /// Stefan-Boltzmann constant [W/(m^2 K^4)].
  static constexpr double sigma = 5.670374419e-8;
  struct Params {
    /// Radius of the local domain Omega in particle diameters (1.5 in the paper), > 0.5.
    double domain = 1.5;
  };
  static void validate(const Params& p) {
    detail::require(std::isfinite(p.domain) && p.domain > 0.5, "radiation::ZhouYuZulli", "domain",
                    p.domain, "(0.5, inf) particle diameters (1.5 in the paper)");
  }
  /// Radius of Omega about a particle of radius R [m].
  static double domain_radius(double R, const Params& p) { return 2.0 * p.domain * R; }
  /// T_local [K] from the porosity phi of Omega, the fluid temperature and the mean
  /// temperature of the other particles in Omega.
  static double local_temperature(double phi, double t_fluid, double t_mean, const Params&) {
    return phi * t_fluid + (1.0 - phi) * t_mean;
  }
  /// Q = sigma eps A (T_local^4 - T^4) [W] into the particle.
  static double heat_rate(double emissivity, double area, double t_local, double t, const Params&) {
    const double l2 = t_local * t_local, t2 = t * t;
    return sigma * emissivity * area * (l2 * l2 - t2 * t2);
  }
};

} // namespace grain::radiation
