#pragma once
/// \file heat.hpp
/// The heat step of a Simulation: fluid-cell radii for the Voronoi conduction models, conductances
/// across gaps, convection to the fluid, dissipation heating, the stored conductances of a
/// thermal analysis (a static packing) and the forward-Euler update of the temperatures.
///
/// A component of `Simulation` (simulation.hpp): static functions over the simulation's state,
/// which declares it a friend.

#include <grain/contact/geometry.hpp>
#include <grain/core/config.hpp>
#include <grain/core/vector.hpp>
#include <grain/simulation/components.hpp>
#include <grain/simulation/params.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

namespace grain::detail {

template <class Sim>
struct HeatStep {
  using Contact = typename Sim::contact_type;
  using V = typename Sim::V;
  using A = typename Sim::A;
  using History = typename Sim::History;
  static constexpr int D = Sim::D;
  static constexpr bool thermal = Sim::thermal;
  static constexpr long parallel_threshold = Sim::parallel_threshold;
  using CellSizeT = typename Sim::CellSizeT;
  using ConvectionT = typename Sim::ConvectionT;
  using Pass = ContactPass<Sim>;

  /// Fluid-cell radii of the list entries (Voronoi conduction models only).
  static void update_cells(Sim& s) {
    if constexpr (Contact::needs_cell_radius) {
      const auto& p = s.particles_;
      auto r = CellSizeT::template compute<D>(
          s.params_.cells, std::span<const V>(p.position.data(), p.size()),
          std::span<const double>(p.radius.data(), p.size()), s.list_, s.walls_, s.cutoff_);
      s.cell_pair_ = std::move(r.pair);
      s.cell_wall_ = std::move(r.wall);
      s.steps_since_cells_ = 0;
    }
  }
  static void maybe_update_cells(Sim& s) {
    if constexpr (Contact::needs_cell_radius) {
      const long f = s.params_.cells.update_frequency;
      if (s.steps_since_rebuild_ == 0) return; // the rebuild has just updated them
      if (f > 0 && ++s.steps_since_cells_ >= f) update_cells(s);
    }
  }

  /// Heat rate [W] into each partner from the power dissipated at a contact (see
  /// SimulationParams::dissipation_heating).
  template <class R>
  static double dissipation_heat(const Sim& s, const ContactGeometry<D>& g, const R& r) {
    const double f = s.params_.dissipation_heating;
    if (f == 0.0) return 0.0;
    double power = r.normal.damping * g.normal_velocity * g.normal_velocity;
    if (r.tangent.sliding) power -= r.tangent.force.dot(g.tangential_velocity);
    return 0.5 * f * std::max(power, 0.0);
  }

  /// Cylinder length of 2D disks for the conduction models (0 for spheres and sphere-mass disks).
  static double length(const Sim& s) {
    if constexpr (requires {
                    s.shape_.thickness;
                    s.shape_.sphere_mass;
                  })
      return s.shape_.sphere_mass ? 0.0 : s.shape_.thickness;
    else
      return 0.0;
  }
  /// Fluid-cell radius of list entry e (infinite, i.e. no cell, when the radii were not computed:
  /// a mechanical analysis of a thermal contact).
  static double cell_radius_pair(const Sim& s, std::size_t e) {
    if constexpr (Contact::needs_cell_radius)
      return e < s.cell_pair_.size() ? s.cell_pair_[e] : std::numeric_limits<double>::infinity();
    else {
      (void)e;
      return std::numeric_limits<double>::infinity();
    }
  }
  static double cell_radius_wall(const Sim& s, std::size_t e) {
    if constexpr (Contact::needs_cell_radius)
      return e < s.cell_wall_.size() ? s.cell_wall_[e] : std::numeric_limits<double>::infinity();
    else {
      (void)e;
      return std::numeric_limits<double>::infinity();
    }
  }
  /// Conductance across the gap of a pair that does not touch (0 beyond the cutoff).
  static double gap_pair_conductance(const Sim& s, std::size_t i, std::size_t j, std::size_t e,
                                     ContactGeometry<D>& g) {
    const auto& p = s.particles_;
    const V d = s.separation(i, j);
    const double dist = d.norm();
    const double gap = dist - p.radius[i] - p.radius[j];
    if (!(gap < s.cutoff_) || dist <= 0) return 0.0;
    gap_pair_geometry<D>(g, V(d / dist), dist, p.radius[i], p.radius[j], p.mass[i], p.mass[j]);
    History h{};
    const auto law = Pass::pair_law(s, e, i, j);
    return Contact::gap_conductance(g, law.pair, law.params, h, s.dt_, length(s),
                                    cell_radius_pair(s, e));
  }
  static double gap_wall_conductance(const Sim& s, std::size_t i, std::size_t w, std::size_t e,
                                     ContactGeometry<D>& g) {
    const auto& p = s.particles_;
    const auto prox = s.walls_[w].proximity(p.position[i]);
    if (!(prox.distance - p.radius[i] < s.cutoff_)) return 0.0;
    gap_wall_geometry<D>(g, prox, p.radius[i], p.mass[i]);
    History h{};
    const auto law = Pass::wall_law(s, e, i, w);
    return Contact::gap_conductance(g, law.pair, law.params, h, s.dt_, length(s),
                                    cell_radius_wall(s, e));
  }

  /// Convective conductance h S [W/K] of particle i: h = Nu(Re, Pr) k_f / (2R), S its surface.
  static double convection_conductance(const Sim& s, std::size_t i) {
    if constexpr (ConvectionT::active) {
      const auto& f = s.params_.fluid;
      const double pr = f.viscosity * f.heat_capacity / f.conductivity;
      const double dia = 2.0 * s.particles_.radius[i];
      const V v = s.moves() && s.force_velocity().size() == s.particles_.size()
                      ? s.force_velocity()[i]
                      : V(V::Zero());
      const double re = f.density * dia * (f.velocity - v).norm() / f.viscosity;
      const double h = ConvectionT::nusselt(re, pr, s.params_.convection) * f.conductivity / dia;
      return h * s.shape_.surface(s.particles_.radius[i]);
    } else {
      (void)i;
      return 0.0;
    }
  }

  /// Heat exchanged with the fluid: Q = h S (T_f - T).
  static void add_convection(Sim& s) {
    if constexpr (thermal && ConvectionT::active) {
      auto& p = s.particles_;
      const double tf = s.params_.fluid.temperature;
      const long n = static_cast<long>(p.size());
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
      for (long i = 0; i < n; ++i)
        p.heat_rate[i] +=
            convection_conductance(s, static_cast<std::size_t>(i)) * (tf - p.temperature[i]);
    }
  }

  /// Thermal analysis: the conductances of the (static) packing, computed once.
  static void store_conductances(Sim& s) {
    s.static_pairs_.clear();
    s.static_walls_.clear();
    s.for_each_conductance([&](std::size_t i, std::size_t j, bool wall, double H) {
      (wall ? s.static_walls_ : s.static_pairs_)
          .push_back({static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j), H});
    });
    if constexpr (Sim::sums_by_id) {
      // pairs by (lower id, higher id): each particle then receives its pairs' heat in ascending
      // partner id (first the partners below it, then those above)
      const auto& id = s.particles_.id;
      std::sort(s.static_pairs_.begin(), s.static_pairs_.end(), [&](const auto& x, const auto& y) {
        return std::pair{id[x.i], id[x.j]} < std::pair{id[y.i], id[y.j]};
      });
    }
  }

  /// Thermal analysis: heat rates from the stored conductances (in a fixed order).
  static void static_heat_rates(Sim& s) {
    if constexpr (thermal) {
      auto& p = s.particles_;
      std::fill(p.heat_rate.begin(), p.heat_rate.end(), 0.0);
      for (const auto& c : s.static_pairs_) {
        const double q = c.conductance * (p.temperature[c.j] - p.temperature[c.i]);
        p.heat_rate[c.i] += q;
        p.heat_rate[c.j] -= q;
      }
      for (const auto& c : s.static_walls_)
        p.heat_rate[c.i] += c.conductance * (s.walls_[c.j].temperature - p.temperature[c.i]);
      add_convection(s);
      RadiationStep<Sim>::add(s);
      if (!s.cond_.heat_fluxes.empty() || !s.cond_.heat_rates.empty())
        s.cond_.add_heat(p, s.time_, [&](double r) { return s.surface_area(r); });
    }
  }

  /// Forward Euler for particle i: T += dt Q / C (also done in the fused pass).
  GRAIN_INLINE static void temperature_step(Sim& s, std::size_t i, double dt) {
    auto& p = s.particles_;
    p.temperature[i] += dt * p.heat_rate[i] * p.inv_heat_capacity[i];
  }
  /// Forward Euler for every particle.
  static void integrate_temperature(Sim& s, double dt) {
    if constexpr (thermal) {
      const long n = static_cast<long>(s.particles_.size());
      bool finite = true;
#pragma omp parallel for reduction(&& : finite) schedule(static) if (n >= parallel_threshold)
      for (long i = 0; i < n; ++i) {
        temperature_step(s, static_cast<std::size_t>(i), dt);
        finite = finite && std::isfinite(s.particles_.temperature[static_cast<std::size_t>(i)]);
      }
      if (!finite) s.require_finite_state();
    }
  }
};

} // namespace grain::detail
