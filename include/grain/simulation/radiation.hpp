#pragma once
/// \file radiation.hpp
/// `RadiationStep<Sim>`: thermal radiation of each particle with its local environment (a
/// radiation model from grain::radiation, an option of `Simulation`). The particles whose
/// centres lie within a particle's domain (`domain_radius`) are found from candidate lists built
/// with the neighbour list: at each rebuild of the neighbour list, every pair closer than the
/// largest domain plus the search skin is listed (both ways), and each step the candidates
/// within the domain are taken. Between rebuilds no particle moves more than half the skin from
/// where it was at the rebuild, so no particle of a domain is missed. Each particle's heat rate
/// is summed over its own row in a fixed order: the same bits for any number of threads. A
/// component of `Simulation` (simulation.hpp), which declares it a friend.

#include <grain/core/config.hpp>
#include <grain/particles/storage.hpp>
#include <grain/search/neighbor_list.hpp>
#include <grain/search/search.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace grain::detail {

/// The candidate partners of each particle's radiation domain (both directions), and the
/// neighbour list they were made with.
template <int D>
struct RadiationDomains {
  std::vector<std::uint32_t> offsets;  ///< row i is partners[offsets[i], offsets[i + 1])
  std::vector<std::uint32_t> partners; ///< candidates of row i, ascending
  /// The neighbour list they were made with (Simulation::list_generation_); none at first.
  std::uint64_t built_for = std::numeric_limits<std::uint64_t>::max();
};

template <class Sim>
struct RadiationStep {
  static constexpr int D = Sim::D;
  using V = Vec<D>;
  using RadiationT = typename Sim::RadiationT;
  static constexpr long parallel_threshold = Sim::parallel_threshold;

  /// The candidate lists for the neighbour list's build (its snapshot of the positions).
  static void build(Sim& s) {
    auto& dom = s.radiation_;
    const auto& p = s.particles_;
    const std::size_t n = p.size();
    double r_min = std::numeric_limits<double>::infinity(), rho = 0.0;
    for (const double r : p.radius) {
      r_min = std::min(r_min, r);
      rho = std::max(rho, RadiationT::domain_radius(r, s.params_.radiation));
    }
    // pairs with a gap below `reach` reach every domain at the build, plus the skin
    const double reach = n == 0 ? 0.0 : std::max(0.0, rho - 2.0 * r_min) + s.skin_;
    ParticleArrays<D> at; // what the search reads: the positions of the build, radii, count
    at.position = s.snapshot_;
    at.radius = p.radius;
    at.id = p.id;
    const std::vector<Wall<D>> none;
    NeighborList half;
    if (s.periodic_.on)
      search::detail::build_periodic(at, none, reach, s.r_max_, s.periodic_, half);
    else
      search::detail::build_cells(at, none, reach, s.r_max_, half);
    // both directions: row i holds every candidate j, ascending
    std::vector<std::uint32_t> count(n + 1, 0);
    for (std::size_t i = 0; i < n; ++i)
      for (const auto e : half.pair_entries(i)) {
        ++count[i + 1];
        ++count[half.partners[e] + 1];
      }
    dom.offsets.assign(n + 1, 0);
    for (std::size_t i = 0; i < n; ++i)
      dom.offsets[i + 1] = dom.offsets[i] + count[i + 1];
    dom.partners.resize(dom.offsets[n]);
    std::vector<std::uint32_t> fill(dom.offsets.begin(), dom.offsets.end() - 1);
    for (std::size_t i = 0; i < n; ++i) // j < i first (rows of smaller i come first) ...
      for (const auto e : half.pair_entries(i))
        dom.partners[fill[half.partners[e]]++] = static_cast<std::uint32_t>(i);
    for (std::size_t i = 0; i < n; ++i) // ... then j > i
      for (const auto e : half.pair_entries(i))
        dom.partners[fill[i]++] = half.partners[e];
    dom.built_for = s.list_generation_;
  }

  /// Adds the radiation heat rate of every particle to its heat rate.
  static void add(Sim& s) {
    if constexpr (Sim::thermal && RadiationT::active) {
      auto& p = s.particles_;
      const std::size_t n = p.size();
      auto& dom = s.radiation_;
      if (dom.offsets.size() != n + 1 || dom.built_for != s.list_generation_) build(s);
      const auto& prm = s.params_.radiation;
      const double tf = s.params_.fluid.temperature;
      const long nl = static_cast<long>(n);
#pragma omp parallel for schedule(static) if (nl >= parallel_threshold)
      for (long il = 0; il < nl; ++il) {
        const auto i = static_cast<std::size_t>(il);
        const double eps = s.table_.material(p.material[i]).emissivity;
        if (eps == 0.0) continue;
        const double rho = RadiationT::domain_radius(p.radius[i], prm);
        double k = 0.0, t_sum = 0.0, v_sum = 0.0;
        for (std::uint32_t e = dom.offsets[i]; e < dom.offsets[i + 1]; ++e) {
          const auto j = dom.partners[e];
          if (s.periodic_.separation(p.position[i], p.position[j]).squaredNorm() > rho * rho)
            continue;
          k += 1.0;
          t_sum += p.temperature[j];
          v_sum += s.shape_.volume(p.radius[j]);
        }
        double phi = 1.0, t_mean = tf;
        if (k > 0.0) {
          const double outside = s.shape_.volume(rho) - s.shape_.volume(p.radius[i]);
          phi = std::clamp(1.0 - v_sum / outside, 0.0, 1.0);
          t_mean = t_sum / k;
        }
        const double t_local = RadiationT::local_temperature(phi, tf, t_mean, prm);
        p.heat_rate[i] +=
            RadiationT::heat_rate(eps, s.surface_area(p.radius[i]), t_local, p.temperature[i], prm);
      }
    }
  }

  /// The linearised conductance dQ/dT [W/K] of particle i to its environment at temperatures up
  /// to t_max [K]: 4 sigma eps A t_max^3 (for the conduction limit of the time step).
  static double conductance_bound(const Sim& s, std::size_t i, double t_max) {
    if constexpr (Sim::thermal && RadiationT::active) {
      const double eps = s.table_.material(s.particles_.material[i]).emissivity;
      if (!(t_max > 0.0)) return 0.0;
      return 4.0 *
             RadiationT::heat_rate(eps, s.surface_area(s.particles_.radius[i]), t_max, 0.0,
                                   s.params_.radiation) /
             t_max;
    } else {
      return 0.0;
    }
  }
};

} // namespace grain::detail
