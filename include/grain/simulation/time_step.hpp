#pragma once
/// \file time_step.hpp
/// The limits of the time step, as functions of the quantities they depend on (SI units). The
/// simulation takes the smallest over its particles, pairs of materials and contacts
/// (Simulation::critical_time_step) and runs at `auto_time_step_factor` times it unless given a
/// step, which must not exceed it.
///
/// | limit | formula | applies when |
/// |---|---|---|
/// | Rayleigh time | pi R sqrt(rho / G) / (0.1631 nu + 0.8766) | forces move particles |
/// | contact limit | 2 sqrt(m* / k), k the contact law's stiffness estimate | forces move particles |
/// | conduction limit | min_i C_i / (sum_j H_ij + h_i S_i / 2) | temperatures advance |
/// | diffusion time (automatic step only) | R^2 rho c / k | temperatures advance |
///
/// The contact limit is the stability limit of the undamped oscillator for the symplectic
/// schemes. Forward Euler of the temperatures is stable for dt < 2 / lambda_max, lambda_max the
/// largest eigenvalue of C^-1 L (L the conductance Laplacian); by Gershgorin's theorem
/// lambda_max <= max_i 2 sum_j H_ij / C_i, so the conduction limit is sufficient, and exact for
/// two particles.

#include <grain/core/error.hpp>
#include <grain/particles/material.hpp>
#include <grain/simulation/components.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

namespace grain::time_step {

inline constexpr double unlimited = std::numeric_limits<double>::infinity();

/// Rayleigh time [s] of a particle of radius r [m] made of m.
inline double rayleigh(double r, const Material& m) {
  return std::numbers::pi * r * std::sqrt(m.density / m.shear_modulus()) /
         (0.1631 * m.poisson + 0.8766);
}
/// Stability limit 2 sqrt(m / k) [s] of an undamped oscillator of mass m [kg] and stiffness
/// k [N/m]; unlimited for k <= 0.
inline double oscillator(double m, double k) { return k > 0 ? 2.0 * std::sqrt(m / k) : unlimited; }
/// Time heat takes to diffuse across a particle of radius r [m] made of m, R^2 rho c / k [s];
/// unlimited for a material that does not conduct.
inline double diffusion(double r, const Material& m) {
  return m.conductivity > 0 ? r * r * m.density * m.heat_capacity / m.conductivity : unlimited;
}
/// Conduction limit min_i C_i / h_i [s] over the particles with h_i > 0 (C_i the heat capacity
/// [J/K], h_i the sum of its conductances [W/K]).
inline double conduction(const std::vector<double>& heat_capacity, const std::vector<double>& h) {
  double t = unlimited;
  for (std::size_t i = 0; i < h.size(); ++i)
    if (h[i] > 0) t = std::min(t, heat_capacity[i] / h[i]);
  return t;
}

} // namespace grain::time_step

namespace grain::detail {

/// The time-step limits of a Simulation over its particles (present and to come), pairs of
/// materials and contacts, with the bounds that variable properties reach, and the choice of the
/// step of a run. A component of `Simulation` (simulation.hpp): static functions over the
/// simulation's state, which declares it a friend.
template <class Sim>
struct TimeStepLimits {
  using Contact = typename Sim::contact_type;
  using ConvectionT = typename Sim::ConvectionT;
  static constexpr bool thermal = Sim::thermal;
  using Heat = HeatStep<Sim>;

  /// Sim::rayleigh_time.
  static double rayleigh_time(const Sim& s) {
    double t = std::numeric_limits<double>::infinity();
    for_each_size(s, [&](double r, std::uint32_t k, double) {
      t = std::min(t, grain::time_step::rayleigh(r, bounding_material(s, k)));
    });
    return t;
  }

  /// Sim::contact_time_step.
  static double contact_time_step(const Sim& s) {
    if (s.particles_.size() + s.life_.pending.size() == 0)
      return std::numeric_limits<double>::infinity();
    const double v = reference_speed(s);
    double t = std::numeric_limits<double>::infinity();
    // smallest particle of each material
    const auto nm = s.table_.size();
    std::vector<double> rmin(nm, std::numeric_limits<double>::infinity()), mmin(nm, 0.0);
    for_each_size(s, [&](double r, std::uint32_t k, double mass) {
      if (r < rmin[k]) {
        rmin[k] = r;
        mmin[k] = mass;
      }
    });
    std::vector<bool> wall_material(nm, false);
    for (const auto& w : s.walls_)
      wall_material[w.options.material] = true;
    for (std::size_t a = 0; a < nm; ++a) {
      if (!std::isfinite(rmin[a])) continue;
      for (std::size_t b = 0; b < nm; ++b) {
        const bool pair = std::isfinite(rmin[b]);
        if (pair) {
          const double re = rmin[a] * rmin[b] / (rmin[a] + rmin[b]);
          const double me = mmin[a] * mmin[b] / (mmin[a] + mmin[b]);
          const double k = Contact::stiffness_estimate(bounding_pair(s, a, b),
                                                       s.contact_params(a, b), re, me, v);
          t = std::min(t, grain::time_step::oscillator(me, k));
        }
        if (wall_material[b]) {
          const double k = Contact::stiffness_estimate(bounding_pair(s, a, b),
                                                       s.contact_params(a, b), rmin[a], mmin[a], v);
          t = std::min(t, grain::time_step::oscillator(mmin[a], k));
        }
      }
    }
    return t;
  }

  /// Sim::thermal_time_step.
  static double thermal_time_step(const Sim& s) {
    double t = std::numeric_limits<double>::infinity();
    if constexpr (thermal) {
      for_each_size(s, [&](double r, std::uint32_t k, double) {
        t = std::min(t, grain::time_step::diffusion(r, bounding_material(s, k)));
      });
    }
    return t;
  }

  /// Sim::conduction_time_step.
  static double conduction_time_step(const Sim& s) {
    double t = std::numeric_limits<double>::infinity();
    if constexpr (thermal) {
      if (s.list_.rows() != s.particles_.size() || !s.heats()) return t;
      std::vector<double> h(s.particles_.size(), 0.0);
      s.for_each_conductance([&](std::size_t i, std::size_t j, bool wall, double H) {
        h[i] += H;
        if (!wall) h[j] += H;
      });
      // convection adds h S to the diagonal of C^-1 L only: half of it to the row sum
      if constexpr (ConvectionT::active)
        for (std::size_t i = 0; i < h.size(); ++i)
          h[i] += 0.5 * Heat::convection_conductance(s, i);
      t = grain::time_step::conduction(s.particles_.heat_capacity, h);
    }
    return t;
  }

  /// Visits (radius, material, mass) of every active and inactive particle.
  /// With variable properties, the smallest radius and density and the largest Young's modulus
  /// their tables reach bound these values (for the time step).
  template <class F>
  static void for_each_size(const Sim& s, F&& f) {
    const auto bound = s.vprops_.radius_bound();
    const double rb = bound.first;
    const bool bounded = bound.second;
    auto visit = [&](double r, std::uint32_t k, double mass) {
      if (bounded) {
        const double r2 = std::min(r, rb);
        mass = std::min(mass * s.shape_.volume(r2) / s.shape_.volume(r),
                        bounding_material(s, k).density * s.shape_.volume(r2));
        r = r2;
      }
      f(r, k, mass);
    };
    for (std::size_t i = 0; i < s.particles_.size(); ++i)
      visit(s.particles_.radius[i], s.particles_.material[i], s.particles_.mass[i]);
    for (const auto& spec : s.life_.pending)
      visit(spec.radius, spec.material,
            s.table_.material(spec.material).density * s.shape_.volume(spec.radius));
  }

  static double reference_speed(const Sim& s) {
    double v = 0.0;
    for (const auto& u : s.particles_.velocity)
      v = std::max(v, u.norm());
    for (const auto& spec : s.life_.pending)
      v = std::max(v, spec.velocity.norm());
    for (const auto& w : s.walls_)
      v = std::max(v, w.options.velocity.norm());
    return std::max(s.params_.reference_velocity, 2.0 * v);
  }

  static Material bounding_material(const Sim& s, std::uint32_t k) {
    return s.vprops_.bounding_material(s.table_.material(k));
  }

  static PairProperties bounding_pair(const Sim& s, std::uint32_t a, std::uint32_t b) {
    if (s.vprops_.empty()) return s.pair_properties(a, b);
    return PairProperties::mix(bounding_material(s, a), bounding_material(s, b),
                               s.table_.override_of(a, b));
  }

  /// The time step of a run [s]: SimulationParams::time_step if it is below the stable limit
  /// (InputError otherwise), else the automatic one, a fraction of the smallest limit.
  static double choose(const Sim& s) {
    const double critical = s.critical_time_step();
    if (s.params_.time_step > 0.0) {
      // forward Euler of the temperatures is stable only strictly below the conduction limit
      // (at it, the difference of two particles flips sign each step without decaying)
      const bool at_conduction_limit = s.heats() && s.params_.time_step == conduction_time_step(s);
      if (s.params_.time_step > critical || at_conduction_limit) {
        std::string why;
        if (s.forces_move())
          why += "Rayleigh time " + detail::to_text(rayleigh_time(s)) +
                 " s, contact limit 2 sqrt(m*/k) = " + detail::to_text(contact_time_step(s)) + " s";
        if (s.heats())
          why += std::string(why.empty() ? "" : ", ") + "conduction limit min C_i / sum H_ij = " +
                 detail::to_text(conduction_time_step(s)) + " s";
        throw InputError("Simulation: time_step = " + detail::to_text(s.params_.time_step) +
                         (at_conduction_limit ? " s is at the conduction limit"
                                              : " s is above the stable limit") +
                         "; valid range: (0, " + detail::to_text(critical) +
                         (at_conduction_limit ? ") s (" : "] s (") + why + ")");
      }
      return s.params_.time_step;
    } else {
      double t = critical;
      if (s.heats()) t = std::min(t, thermal_time_step(s));
      if (!std::isfinite(t))
        throw InputError("Simulation: time_step = 0 (automatic) needs particles (and, in a "
                         "thermal analysis, conducting contacts) to estimate it; valid range: "
                         "(0, inf) s");
      return s.params_.auto_time_step_factor * t;
    }
  }
};

} // namespace grain::detail
