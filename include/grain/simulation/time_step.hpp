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

#include <grain/particles/material.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
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
