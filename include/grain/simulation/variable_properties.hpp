#pragma once
/// \file variable_properties.hpp
/// `VariableProperties<D>`: properties of the particles of groups that follow a table of
/// temperature, time or speed (conditions/variable_property.hpp). `apply` updates the particles'
/// radii, masses, inertias and heat capacities in place and keeps the per-particle values of
/// the contact properties (Young's modulus, Poisson ratio, restitution, friction, rolling
/// friction, conductivity; NaN = the material's); it reports what changed, and the simulation
/// does what follows (a rebuild for a new radius, new per-contact constants for a contact
/// property). The walls' contact properties may follow tables of the wall's temperature, the
/// time or the wall's speed in the same way (`add_walls`, `apply_walls`). `material_of` and
/// `wall_material_of` give a particle's or a wall's material with its values,
/// `bounding_material` the extremes the tables reach (for the time step).

#include <grain/conditions/variable_property.hpp>
#include <grain/core/table.hpp>
#include <grain/particles/material.hpp>
#include <grain/particles/storage.hpp>
#include <grain/simulation/components.hpp>
#include <grain/simulation/params.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace grain {

template <int D>
struct VariableProperties {
  /// A variable property and the index of its group.
  struct On {
    VariableProperty vp;
    std::size_t group;
  };
  std::vector<On> list;
  /// A variable property of walls and their indices.
  struct OnWalls {
    VariableProperty vp;
    std::vector<std::uint32_t> walls;
  };
  std::vector<OnWalls> wall_list;
  /// True once a contact property varies: the contact constants are then per list entry.
  bool per_particle = false;
  /// Per-particle values of young, poisson, restitution, friction, rolling_friction and
  /// conductivity (NaN = the material's), while `per_particle`.
  std::array<std::vector<double>, 6> values;
  /// The same per wall (NaN = the wall material's); sized when a wall property is applied.
  std::array<std::vector<double>, 6> wall_values;

  /// What an update changed.
  struct Changes {
    bool any = false;     ///< some property was due
    bool radius = false;  ///< a radius changed (surfaces moved)
    bool contact = false; ///< a contact property changed
    bool thermal = false; ///< a heat capacity or conductance may have changed
  };

  bool empty() const { return list.empty() && wall_list.empty(); }

  /// Adds a property of group `group`; `n` particles exist. Returns true if this is the first
  /// contact property (the contact constants become per particle).
  bool add(VariableProperty vp, std::size_t group, std::size_t n) {
    const bool first = is_contact_property(vp.property) && start_per_particle(n);
    list.push_back({std::move(vp), group});
    return first;
  }
  /// Adds a (contact) property of the walls `walls`; `n` particles exist. Returns true if the
  /// contact constants become per list entry with it.
  bool add_walls(VariableProperty vp, std::vector<std::uint32_t> walls, std::size_t n) {
    const bool first = start_per_particle(n);
    wall_list.push_back({std::move(vp), std::move(walls)});
    return first;
  }
  /// A new particle: no values of its own.
  void append() {
    if (per_particle)
      for (auto& o : values)
        o.push_back(std::numeric_limits<double>::quiet_NaN());
  }
  /// The values follow a permutation (or a removal) of the particles.
  void permute(const std::vector<std::uint32_t>& perm) {
    if (per_particle)
      for (auto& o : values)
        detail::permute_in_place(o, perm);
  }

  /// The material `base` of particle i with its per-particle values.
  Material material_of(std::size_t i, const Material& base) const {
    if (!per_particle) return base;
    return with_values(values, i, base);
  }
  /// The material `base` of wall w with its values.
  Material wall_material_of(std::size_t w, const Material& base) const {
    if (w >= wall_values[0].size()) return base;
    return with_values(wall_values, w, base);
  }
  /// The current conductivity of wall w [W/(m K)], `base` its material's (wall_material_of
  /// without making the whole material: it is asked per contact).
  double wall_conductivity_of(std::size_t w, double base) const {
    if (w >= wall_values[5].size() || std::isnan(wall_values[5][w])) return base;
    return wall_values[5][w];
  }

  /// The material `m` with the extremes its tables reach that bound the time step: the largest
  /// Young's modulus and conductivity, the smallest density and heat capacity.
  /// The tables of particles and walls alike bound every material (a safe side).
  Material bounding_material(Material m) const {
    auto bound = [&](const VariableProperty& vp) {
      const auto& y = vp.table->y();
      if (vp.property == Property::young) {
        m.young = std::max(m.young, *std::max_element(y.begin(), y.end()));
        m.shear = 0.0;
      } else if (vp.property == Property::density) {
        m.density = std::min(m.density, *std::min_element(y.begin(), y.end()));
      } else if (vp.property == Property::conductivity) {
        m.conductivity = std::max(m.conductivity, *std::max_element(y.begin(), y.end()));
      } else if (vp.property == Property::heat_capacity) {
        m.heat_capacity = std::min(m.heat_capacity, *std::min_element(y.begin(), y.end()));
      }
    };
    for (const auto& v : list)
      bound(v.vp);
    for (const auto& v : wall_list)
      bound(v.vp);
    return m;
  }
  /// The smallest radius a radius table reaches (+inf without one), and whether a radius or a
  /// density varies (the sizes of the time step are then bounded).
  std::pair<double, bool> radius_bound() const {
    double rb = std::numeric_limits<double>::infinity();
    bool bounded = false;
    for (const auto& v : list) {
      if (v.vp.property == Property::radius)
        for (double y : v.vp.table->y())
          rb = std::min(rb, y);
      bounded = bounded || v.vp.property == Property::radius || v.vp.property == Property::density;
    }
    return {rb, bounded};
  }
  /// The largest radius a radius table reaches (0 without one).
  double largest_radius() const {
    double r = 0.0;
    for (const auto& v : list)
      if (v.vp.property == Property::radius)
        for (double y : v.vp.table->y())
          r = std::max(r, y);
    return r;
  }

  /// Applies the properties that are due at time t and step `step` (all active ones if `all`)
  /// to the particles `p` of their groups (`members[group]`: current indices), or only to those
  /// with only[i] != 0. `shape` gives volumes and inertia factors. Masses follow a radius at
  /// constant density and a density at constant volume; heat capacities keep the specific heat
  /// capacity; fixed particles (inverse mass 0) stay fixed.
  template <class Particles, class Shape>
  Changes apply(Particles& p, const Shape& shape,
                const std::vector<std::vector<std::uint32_t>>& members, double t, long step,
                bool all, const std::vector<char>* only = nullptr) {
    Changes c;
    for (const auto& [vp, g] : list) {
      if (!vp.active(t) || (!all && step % vp.every != 0)) continue;
      c.any = true;
      const Table& tab = *vp.table;
      std::size_t hint = 0;
      for (const auto i : members[g]) {
        if (only && !(*only)[i]) continue;
        set_property(vp.property, tab(variable_of(vp.variable, p, i, t), hint), p, shape, i, c);
      }
    }
    return c;
  }

  /// Applies the wall properties that are due at time t and step `step` (all active ones if
  /// `all`) to the walls `w` (a wall's temperature, the time, or its translational speed).
  template <class Walls>
  Changes apply_walls(const Walls& w, double t, long step, bool all) {
    Changes c;
    if (wall_list.empty()) return c;
    for (auto& o : wall_values)
      o.resize(w.size(), std::numeric_limits<double>::quiet_NaN());
    for (const auto& [vp, ws] : wall_list) {
      if (!vp.active(t) || (!all && step % vp.every != 0)) continue;
      c.any = true;
      const Table& tab = *vp.table;
      std::size_t hint = 0;
      for (const auto k : ws) {
        double x = t;
        if (vp.variable == Variable::temperature) x = w[k].temperature;
        if (vp.variable == Variable::speed) x = w[k].options.velocity.norm();
        const double y = tab(x, hint);
        const std::size_t slot = value_slot(vp.property);
        if (y != wall_values[slot][k]) {
          wall_values[slot][k] = y;
          c.contact = true;
          c.thermal = c.thermal || vp.property == Property::conductivity;
        }
      }
    }
    return c;
  }

  /// The position of a contact property in `values` and `wall_values`.
  static std::size_t value_slot(Property p) {
    switch (p) {
    case Property::young:
      return 0;
    case Property::poisson:
      return 1;
    case Property::restitution:
      return 2;
    case Property::friction:
      return 3;
    case Property::rolling_friction:
      return 4;
    default:
      return 5;
    }
  }

private:
  /// Per-particle values exist from the first contact property on; true at that first one.
  bool start_per_particle(std::size_t n) {
    if (per_particle) return false;
    per_particle = true;
    for (auto& o : values)
      o.assign(n, std::numeric_limits<double>::quiet_NaN());
    return true;
  }

  /// `base` with the values of element i in `v` (NaN = kept).
  static Material with_values(const std::array<std::vector<double>, 6>& v, std::size_t i,
                              const Material& base) {
    Material m = base;
    auto take = [&](const std::vector<double>& o, double& x) {
      if (!std::isnan(o[i])) x = o[i];
    };
    take(v[0], m.young);
    take(v[1], m.poisson);
    take(v[2], m.restitution);
    take(v[3], m.friction);
    take(v[4], m.rolling_friction);
    take(v[5], m.conductivity);
    if (!std::isnan(v[0][i]) || !std::isnan(v[1][i])) m.shear = 0.0; // G from E, nu
    // a softened modulus keeps its ratio to the real one; a static friction below the new
    // sliding friction is raised to it by the mixing rule
    if (!std::isnan(v[0][i]) && base.young_real > 0.0)
      m.young_real = base.young_real * (m.young / base.young);
    return m;
  }

  /// The value of a table's variable for particle i at time t.
  template <class Particles>
  static double variable_of(Variable v, const Particles& p, std::size_t i, double t) {
    constexpr bool thermal = requires { p.temperature; };
    double x = 0.0;
    switch (v) {
    case Variable::temperature:
      if constexpr (thermal) x = p.temperature[i];
      break;
    case Variable::time:
      x = t;
      break;
    case Variable::speed:
      x = p.velocity[i].norm();
      break;
    }
    return x;
  }

  /// Sets property `prop` of particle i to y, with what follows from it (mass, inertia, heat
  /// capacity), and notes in c what changed.
  template <class Particles, class Shape>
  void set_property(Property prop, double y, Particles& p, const Shape& shape, std::size_t i,
                    Changes& c) {
    constexpr bool thermal = requires { p.temperature; };
    const double vol = shape.volume(p.radius[i]);
    const double density = p.mass[i] / vol;
    [[maybe_unused]] double cs = 0.0; // specific heat capacity, kept
    if constexpr (thermal) cs = p.heat_capacity[i] / p.mass[i];
    auto set_mass = [&](double mass) {
      p.mass[i] = mass;
      if (p.inv_mass[i] != 0.0) p.inv_mass[i] = 1.0 / mass;
      p.inertia[i] = shape.inertia_factor() * mass * p.radius[i] * p.radius[i];
      if (p.inv_inertia[i] != 0.0) p.inv_inertia[i] = 1.0 / p.inertia[i];
      if constexpr (thermal) {
        p.heat_capacity[i] = mass * cs;
        if (p.inv_heat_capacity[i] != 0.0) p.inv_heat_capacity[i] = 1.0 / p.heat_capacity[i];
      }
    };
    auto set_value = [&](std::size_t k) {
      values[k][i] = y;
      c.contact = true;
    };
    switch (prop) {
    case Property::radius:
      if (y != p.radius[i]) {
        p.radius[i] = y;
        set_mass(density * shape.volume(y));
        c.radius = true;
        c.thermal = true; // heat capacity and conductances change
      }
      break;
    case Property::density:
      set_mass(y * vol);
      c.thermal = true; // the heat capacity m c changes
      break;
    case Property::heat_capacity:
      c.thermal = true;
      if constexpr (thermal) {
        p.heat_capacity[i] = p.mass[i] * y;
        p.inv_heat_capacity[i] = 1.0 / p.heat_capacity[i];
      }
      break;
    case Property::young:
      set_value(0);
      break;
    case Property::poisson:
      set_value(1);
      break;
    case Property::restitution:
      set_value(2);
      break;
    case Property::friction:
      set_value(3);
      break;
    case Property::rolling_friction:
      set_value(4);
      break;
    case Property::conductivity:
      set_value(5);
      c.thermal = true;
      break;
    }
  }
};

} // namespace grain

namespace grain::detail {

/// The variable-property step of a Simulation: applies the properties that are due and makes the
/// simulation follow what changed (a fresh neighbour list after a radius change, the per-entry
/// contact properties, the stored conductances of a thermal analysis, the conduction limit). A
/// component of `Simulation` (simulation.hpp): static functions over the simulation's state,
/// which declares it a friend.
template <class Sim>
struct VariablePropertyStep {
  using SearchT = typename Sim::search_type;
  static constexpr bool thermal = Sim::thermal;
  using Heat = HeatStep<Sim>;
  using Neighbours = NeighbourRebuild<Sim>;

  /// Applies the variable properties that are due (all active ones if `all`) at the current time;
  /// returns true if something changed.
  static bool apply(Sim& s, bool all, const std::vector<char>* only = nullptr) {
    if (s.vprops_.empty()) return false;
    s.ensure_groups();
    auto& p = s.particles_;
    const auto changes = s.vprops_.apply(p, s.shape_, s.cond_.members, s.time_, s.step_, all, only);
    const auto walls =
        only ? decltype(changes){} : s.vprops_.apply_walls(s.walls_, s.time_, s.step_, all);
    const bool radius = changes.radius, contact = changes.contact || walls.contact;
    const bool any = changes.any || walls.any;
    const bool thermal_change = changes.thermal || walls.thermal;
    if (radius) {
      // a radius change moves particle surfaces: a fresh neighbour list with the new sizes
      for (double r : p.radius)
        s.r_max_ = std::max(s.r_max_, r);
      s.skin_ = s.moves() ? SearchT::skin(s.params_.search, s.r_max_) : 0.0;
      if (s.heats()) s.cutoff_ = s.largest_cutoff();
      s.gap_reach_ = s.largest_gap_reach();
      if (s.initialized_) Neighbours::rebuild(s);
    } else if (contact && s.initialized_) {
      Neighbours::refresh_pair_cache(s);
    }
    if constexpr (thermal) {
      if (any && s.initialized_ && s.analysis() == Analysis::thermal) Heat::store_conductances(s);
      if (thermal_change && s.initialized_ && s.heats()) {
        // the conduction limit moves with the conductivities and heat capacities
        if (!TimeStepLimits<Sim>::conduction_stable(s, s.dt_)) {
          const double limit = s.conduction_time_step();
          throw InputError(
              "Simulation: time_step = " + detail::to_text(s.dt_) +
              " s is above the conduction limit 2 / lambda_max(C^-1 L) = " +
              detail::to_text(limit) + " s reached at t = " + detail::to_text(s.time_) +
              " s by a variable property (conductivity, heat capacity, density or radius); valid "
              "range: (0, " +
              detail::to_text(limit) + ") s (give a smaller time_step or auto_time_step_factor)");
        }
      }
    }
    return any;
  }
};

} // namespace grain::detail
