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
/// | conduction limit | 2 / lambda_max, lambda_max the largest eigenvalue of C^-1 (L + K) | temperatures advance |
/// | diffusion time (automatic step only) | R^2 rho c / k | temperatures advance |
///
/// The contact limit is the stability limit of the undamped oscillator for the symplectic
/// schemes. Forward Euler of the temperatures, T += dt C^-1 (-(L + K) T + ...), is stable for
/// dt < 2 / lambda_max: C is the diagonal of heat capacities [J/K], L the Laplacian of the
/// conductances H_ij between particles [W/K], K the diagonal of the conductances to walls and to
/// the fluid (h_i S_i). lambda_max is estimated by the Lanczos method on the symmetric form
/// C^-1/2 (L + K) C^-1/2 (`time_step::largest_rate`): the largest Ritz value plus its residual
/// bound, which is an eigenvalue's distance to it; at most Gershgorin's bound
/// max_i (2 sum_j H_ij + K_i) / C_i. The bound alone, `conduction_bound` = min_i C_i / (sum_j H_ij
/// + K_i) (half the Gershgorin step, with the wall and fluid terms counted twice), is what a
/// check uses first: a step below it is stable without the estimate. Both are exact for two
/// particles; for a chain between two walls the bound is C / (2 H) and the limit
/// C / (H (1 - cos(N pi / (N + 1)))), up to twice as long.

#include <grain/core/error.hpp>
#include <grain/particles/material.hpp>
#include <grain/simulation/components.hpp>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
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

/// A network of heat conduction: node i has the heat capacity capacity[i] [J/K] and the
/// conductance ground[i] [W/K] to fixed temperatures (walls, the fluid); a link (i, j, H) joins
/// two nodes with the conductance H [W/K].
struct ConductionNetwork {
  struct Link {
    std::uint32_t i, j;
    double conductance;
  };
  std::vector<double> capacity, ground;
  std::vector<Link> links;

  /// The sum of the conductances at each node [W/K], the links counted once.
  std::vector<double> row_sums() const {
    std::vector<double> h = ground;
    for (const auto& l : links) {
      h[l.i] += l.conductance;
      h[l.j] += l.conductance;
    }
    return h;
  }
  /// y = C^-1/2 (L + K) C^-1/2 x, the symmetric form of the rate matrix C^-1 (L + K).
  void apply(const std::vector<double>& s, const std::vector<double>& x,
             std::vector<double>& y) const {
    for (std::size_t i = 0; i < x.size(); ++i)
      y[i] = ground[i] * s[i] * x[i];
    for (const auto& l : links) {
      const double q = l.conductance * (s[l.i] * x[l.i] - s[l.j] * x[l.j]);
      y[l.i] += q;
      y[l.j] -= q;
    }
    for (std::size_t i = 0; i < x.size(); ++i)
      y[i] *= s[i];
  }
};

/// Gershgorin's bound on the largest eigenvalue of C^-1 (L + K) [1/s]: max_i (2 sum_j H_ij +
/// K_i) / C_i over the nodes with C_i > 0.
inline double gershgorin_rate(const ConductionNetwork& n) {
  std::vector<double> h(n.ground.size(), 0.0);
  for (const auto& l : n.links) {
    h[l.i] += 2.0 * l.conductance;
    h[l.j] += 2.0 * l.conductance;
  }
  double rate = 0.0;
  for (std::size_t i = 0; i < h.size(); ++i)
    if (n.capacity[i] > 0) rate = std::max(rate, (h[i] + n.ground[i]) / n.capacity[i]);
  return rate;
}

/// An estimate from above of the largest eigenvalue lambda_max [1/s] of C^-1 (L + K) of the
/// network (0 for a network without conductance): Lanczos iterations on the symmetric form from
/// a fixed pseudo-random start (the same result on every run), stopped when the residual bound
/// of the largest Ritz value theta falls below `tolerance` theta (or after `max_iterations`);
/// the result is theta plus that bound (an eigenvalue lies within it of theta), at most
/// Gershgorin's bound. Nodes of zero heat capacity are left out (they do not advance).
inline double largest_rate(const ConductionNetwork& net, double tolerance = 1e-4,
                           int max_iterations = 150) {
  const double gershgorin = gershgorin_rate(net);
  if (!(gershgorin > 0.0)) return 0.0;
  const std::size_t n = net.capacity.size();
  std::vector<double> s(n), q(n), q_prev(n, 0.0), w(n);
  std::uint64_t state = 0x9E3779B97F4A7C15ull;
  double norm = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    s[i] = net.capacity[i] > 0 ? 1.0 / std::sqrt(net.capacity[i]) : 0.0;
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    q[i] = s[i] > 0 ? 0.5 + static_cast<double>(state >> 11) * 0x1.0p-53 : 0.0;
    norm += q[i] * q[i];
  }
  for (auto& v : q)
    v /= std::sqrt(norm);
  std::vector<double> alpha, beta;
  double estimate = gershgorin, b = 0.0;
  for (int k = 0; k < max_iterations; ++k) {
    net.apply(s, q, w);
    double a = 0.0;
    for (std::size_t i = 0; i < n; ++i)
      a += q[i] * w[i];
    double bn = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      w[i] -= a * q[i] + b * q_prev[i];
      bn += w[i] * w[i];
    }
    bn = std::sqrt(bn);
    alpha.push_back(a);
    Eigen::VectorXd d = Eigen::Map<const Eigen::VectorXd>(alpha.data(), Eigen::Index(alpha.size()));
    Eigen::VectorXd e = Eigen::Map<const Eigen::VectorXd>(beta.data(), Eigen::Index(beta.size()));
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> t;
    t.computeFromTridiagonal(d, e, Eigen::ComputeEigenvectors);
    const Eigen::Index top = d.size() - 1; // eigenvalues in increasing order
    const double theta = t.eigenvalues()[top];
    const double residual = bn * std::abs(t.eigenvectors()(top, top));
    estimate = std::min(gershgorin, theta + residual);
    if (residual <= tolerance * theta || bn <= 1e-14 * gershgorin ||
        alpha.size() == n) // an invariant subspace: theta is exact
      break;
    beta.push_back(bn);
    b = bn;
    for (std::size_t i = 0; i < n; ++i) {
      q_prev[i] = q[i];
      q[i] = w[i] / bn;
    }
  }
  return estimate;
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
    if (s.particles_.size() + s.life_.pending.size() == 0 && !s.inserts_.active())
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

  /// The conduction network of the current contacts: capacities, conductances to walls and to
  /// the fluid, links between particles (empty before the neighbour list is built).
  static grain::time_step::ConductionNetwork conduction_network(const Sim& s) {
    grain::time_step::ConductionNetwork net;
    if constexpr (thermal) {
      if (s.list_.rows() != s.particles_.size() || !s.heats()) return net;
      const std::size_t n = s.particles_.size();
      net.capacity = s.particles_.heat_capacity;
      net.ground.assign(n, 0.0);
      s.for_each_conductance([&](std::size_t i, std::size_t j, bool wall, double H) {
        if (wall)
          net.ground[i] += H;
        else
          net.links.push_back({static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j), H});
      });
      if constexpr (ConvectionT::active)
        for (std::size_t i = 0; i < n; ++i)
          net.ground[i] += Heat::convection_conductance(s, i);
      if constexpr (Sim::RadiationT::active) {
        // radiation linearised at the hottest temperature present (particles, walls, fluid)
        double t_max = s.params_.fluid.temperature;
        for (const double t : s.particles_.temperature)
          t_max = std::max(t_max, t);
        for (const auto& w : s.walls_)
          if (w.conducts()) t_max = std::max(t_max, w.temperature);
        for (std::size_t i = 0; i < n; ++i)
          net.ground[i] += RadiationStep<Sim>::conductance_bound(s, i, t_max);
      }
    }
    return net;
  }

  /// Sim::conduction_bound: min_i C_i / (sum_j H_ij + K_i) [s], a step below which is stable.
  static double conduction_bound(const Sim& s) {
    if constexpr (thermal) {
      const auto net = conduction_network(s);
      if (!net.capacity.empty()) return grain::time_step::conduction(net.capacity, net.row_sums());
    }
    return unlimited();
  }

  /// Sim::conduction_time_step: 2 / lambda_max [s] (time_step::largest_rate), at least the bound
  /// (which it is for two particles, up to rounding).
  static double conduction_time_step(const Sim& s) {
    if constexpr (thermal) {
      const auto net = conduction_network(s);
      if (!net.capacity.empty()) {
        const double rate = grain::time_step::largest_rate(net);
        if (rate > 0.0)
          return std::max(2.0 / rate, grain::time_step::conduction(net.capacity, net.row_sums()));
      }
    }
    return unlimited();
  }

  /// True if forward Euler of the temperatures is stable at the step dt: below the bound, or
  /// strictly below the estimated limit (at it, the slowest-decaying difference flips sign each
  /// step without decaying). Computes the estimate only for a step above the bound.
  static bool conduction_stable(const Sim& s, double dt) {
    return dt < conduction_bound(s) || dt < conduction_time_step(s);
  }

  /// The conduction limits for a message: the limit and the bound.
  static std::string conduction_text(const Sim& s) {
    return "conduction limit 2 / lambda_max(C^-1 L) = " + detail::to_text(conduction_time_step(s)) +
           " s (bound min C_i / sum H_ij = " + detail::to_text(conduction_bound(s)) + " s)";
  }

  static constexpr double unlimited() { return std::numeric_limits<double>::infinity(); }

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
    // the smallest and largest particle each insertion can still give
    s.inserts_.for_each_bound([&](double r, std::uint32_t k) {
      visit(r, k, s.table_.material(k).density * s.shape_.volume(r));
    });
  }

  static double reference_speed(const Sim& s) {
    double v = 0.0;
    for (const auto& u : s.particles_.velocity)
      v = std::max(v, u.norm());
    for (const auto& spec : s.life_.pending)
      v = std::max(v, spec.velocity.norm());
    for (const auto& w : s.walls_)
      v = std::max(v, w.options.velocity.norm());
    v = std::max(v, s.inserts_.largest_speed());
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
  /// (InputError otherwise, naming the limit that applies), else the automatic one, a fraction of
  /// the smallest limit.
  static double choose(const Sim& s) {
    const double dt = s.params_.time_step;
    if (dt > 0.0) {
      const double mechanical = s.forces_move() ? s.mechanical_time_step() : unlimited();
      // forward Euler of the temperatures is stable only strictly below the conduction limit
      // (at it, the slowest-decaying difference flips sign each step without decaying)
      const bool conducts = !s.heats() || conduction_stable(s, dt);
      if (dt > mechanical || !conducts) {
        std::string why;
        if (s.forces_move())
          why += "Rayleigh time " + detail::to_text(rayleigh_time(s)) +
                 " s, contact limit 2 sqrt(m*/k) = " + detail::to_text(contact_time_step(s)) + " s";
        if (s.heats()) why += std::string(why.empty() ? "" : ", ") + conduction_text(s);
        const double critical = s.critical_time_step();
        const bool at_conduction_limit = dt == critical && !conducts;
        const char* which = dt > mechanical       ? " s is above the stable limit"
                            : at_conduction_limit ? " s is at the conduction limit"
                                                  : " s is above the conduction limit";
        throw InputError("Simulation: time_step = " + detail::to_text(dt) + which +
                         "; valid range: (0, " + detail::to_text(critical) +
                         (conducts ? "] s (" : ") s (") + why + ")");
      }
      return dt;
    }
    double t = s.critical_time_step();
    if (s.heats()) t = std::min(t, thermal_time_step(s));
    if (!std::isfinite(t))
      throw InputError("Simulation: time_step = 0 (automatic) needs particles (and, in a "
                       "thermal analysis, conducting contacts) to estimate it; valid range: "
                       "(0, inf) s");
    return s.params_.auto_time_step_factor * t;
  }
};

} // namespace grain::detail
