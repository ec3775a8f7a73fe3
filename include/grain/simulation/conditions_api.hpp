#pragma once
/// \file conditions_api.hpp
/// The groups and conditions of a Simulation, its public API for them: named groups of
/// particles and walls, initial conditions (velocities, temperatures), prescribed loads and heat,
/// fixed velocities and temperatures, prescribed motion (velocity or acceleration histories) and
/// restraints. They are stored in the simulation's `detail::ConditionSet` (conditions/conditions.hpp),
/// which the step applies.
///
/// `Simulation` derives from `GroupsAndConditions<Simulation, D>` (a base that knows its derived
/// class: no virtual function), so these are members of every simulation.

#include <grain/conditions/conditions.hpp>
#include <grain/conditions/variable_property.hpp>
#include <grain/core/error.hpp>
#include <grain/core/time_function.hpp>
#include <grain/core/vector.hpp>
#include <grain/simulation/components.hpp>

#include <algorithm>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace grain::detail {

template <class Sim, int D>
class GroupsAndConditions {
  using V = Vec<D>;
  using A = Angular<D>;
  Sim& self() { return static_cast<Sim&>(*this); }
  /// A condition of temperature needs particles that have one.
  static void check_argument(const char* who, const std::string& group, Variable of) {
    if (of == Variable::temperature && !Sim::thermal)
      throw InputError(std::string("Simulation::") + who + " (group '" + group +
                       "'): of = temperature is invalid without a conduction model; valid "
                       "values: time, speed (or give the Interaction a conduction model)");
  }
  const Sim& self() const { return static_cast<const Sim&>(*this); }

public:
  /// Adds a named group of particles (by id) and walls (by index); returns its index. The name
  /// "all" is reserved for the group of every particle and wall.
  std::size_t add_group(std::string name, std::vector<std::int64_t> particle_ids,
                        std::vector<std::uint32_t> wall_indices = {}) {
    Sim& s = self();
    const std::string obj = "Simulation::add_group '" + name + "'";
    for (const auto w : wall_indices)
      if (w >= s.walls_.size())
        throw InputError(obj + ": wall = " + std::to_string(w) + " is invalid; valid range: [0, " +
                         std::to_string(s.walls_.size()) + ") (indices returned by add_wall)");
    std::vector<std::int64_t> known = s.particles_.id;
    for (const auto& sp : s.life_.pending)
      known.push_back(sp.id);
    std::sort(known.begin(), known.end());
    for (const auto id : particle_ids)
      if (!std::binary_search(known.begin(), known.end(), id))
        throw InputError(obj + ": particle id = " + std::to_string(id) +
                         " is invalid; valid: ids of added particles");
    const auto g = s.cond_.add(
        Group{std::move(name), false, std::move(particle_ids), std::move(wall_indices)});
    s.groups_dirty_ = true;
    return g;
  }
  /// Adds a group of the current (active) particles for which pred(position, radius) is true,
  /// and of the given walls.
  template <class Pred>
  requires std::predicate<Pred&, const V&, double> std::size_t
  add_group_where(std::string name, Pred pred, std::vector<std::uint32_t> wall_indices = {}) {
    Sim& s = self();
    std::vector<std::int64_t> ids;
    for (std::size_t i = 0; i < s.particles_.size(); ++i)
      if (pred(s.particles_.position[i], s.particles_.radius[i])) ids.push_back(s.particles_.id[i]);
    return add_group(std::move(name), std::move(ids), std::move(wall_indices));
  }
  /// The group of this name (throws InputError naming the known groups otherwise).
  const Group& group(const std::string& name) const {
    const Sim& s = self();
    return s.cond_.groups[s.cond_.find(name)];
  }
  /// Every group, in the order they were added: first the reserved group "all" (`everything`
  /// set, no ids), then those of add_group.
  const std::vector<Group>& groups() const { return self().cond_.groups; }
  /// Current indices of the active particles of a group.
  const std::vector<std::uint32_t>& group_indices(const std::string& name) const {
    const Sim& s = self();
    s.ensure_groups();
    return s.cond_.members[s.cond_.find(name)];
  }
  /// True if particle i (current index) is moved by forces: not fixed and not under prescribed
  /// motion (restrained particles are free in their other directions).
  bool is_free(std::size_t i) const {
    const Sim& s = self();
    if (s.particles_.inv_mass[i] == 0.0) return false;
    s.ensure_groups();
    const auto& c = s.cond_.controls;
    const auto it = std::lower_bound(c.begin(), c.end(), i,
                                     [](const auto& x, std::size_t k) { return x.i < k; });
    return it == c.end() || it->i != i || (it->linear < 0 && it->angular < 0);
  }

  /// Initial condition: sets the velocity [m/s] and angular velocity [rad/s] of the group's
  /// particles now.
  void set_velocity(const std::string& group, const V& v, const A& w = zero<A>()) {
    Sim& s = self();
    const std::string obj = "Simulation::set_velocity (group '" + group + "')";
    if (!all_finite(v)) detail::require(false, obj, "velocity", s.to_text(v), "finite components");
    detail::require(all_finite(w), obj, "omega", "(non-finite)", "finite components");
    for (const auto i : group_indices(group)) {
      s.particles_.velocity[i] = v;
      s.particles_.omega[i] = w;
    }
    for (auto& spec : s.life_.pending)
      if (s.in_group(group, spec.id)) {
        spec.velocity = v;
        spec.omega = w;
      }
    s.cond_.restrain_velocities(s.particles_);
  }
  /// Initial condition: sets the temperature [K] of the group's particles now.
  void set_temperature(const std::string& group, double temperature) {
    Sim& s = self();
    static_assert(Sim::thermal,
                  "grain::Simulation::set_temperature: particles have temperatures only "
                  "when the Interaction has a conduction model");
    detail::require(std::isfinite(temperature) && temperature >= 0,
                    "Simulation::set_temperature (group '" + group + "')", "temperature",
                    temperature, "[0, inf) K");
    if constexpr (Sim::thermal) {
      for (const auto i : group_indices(group))
        s.particles_.temperature[i] = temperature;
      for (auto& spec : s.life_.pending)
        if (s.in_group(group, spec.id)) spec.temperature = temperature;
    }
  }

  /// Prescribed force [N] on each particle of the group (summed with every other load): a
  /// function of time, or with `of` = Variable::temperature or Variable::speed a function of each
  /// particle's temperature [K] or speed [m/s] (its activity interval still in time).
  void prescribe_force(const std::string& group, VectorTimeFunction<D> f,
                       Variable of = Variable::time) {
    Sim& s = self();
    check_argument("prescribe_force", group, of);
    s.cond_.forces.push_back({s.cond_.find(group), std::move(f), of});
  }
  /// Prescribed torque [N m] on each particle of the group (a function of `of`, as for forces).
  void prescribe_torque(const std::string& group, AngularTimeFunction<D> f,
                        Variable of = Variable::time) {
    Sim& s = self();
    check_argument("prescribe_torque", group, of);
    s.cond_.torques.push_back({s.cond_.find(group), std::move(f), of});
  }
  /// Prescribed heat flux [W/m^2] into each particle of the group, times its surface: a function
  /// of time, or of each particle's temperature [K] or speed [m/s] (`of`).
  void prescribe_heat_flux(const std::string& group, TimeFunction q, Variable of = Variable::time) {
    Sim& s = self();
    static_assert(Sim::thermal,
                  "grain::Simulation::prescribe_heat_flux needs a thermal simulation: "
                  "give the Interaction a conduction model");
    s.cond_.heat_fluxes.push_back({s.cond_.find(group), std::move(q), of});
  }
  /// Prescribed heat rate [W] into each particle of the group (a function of `of`, as for the
  /// heat flux).
  void prescribe_heat_rate(const std::string& group, TimeFunction q, Variable of = Variable::time) {
    Sim& s = self();
    static_assert(Sim::thermal,
                  "grain::Simulation::prescribe_heat_rate needs a thermal simulation: "
                  "give the Interaction a conduction model");
    s.cond_.heat_rates.push_back({s.cond_.find(group), std::move(q), of});
  }
  /// Fixed velocity [m/s] of the group's particles (while the function is active) and walls
  /// (their translational velocity, 0 while inactive).
  void fix_velocity(const std::string& group, VectorTimeFunction<D> v) {
    prescribe_motion(group, std::move(v), std::nullopt, "vv");
  }
  /// Fixed angular velocity [rad/s] of the group's particles (while active) and walls (about
  /// their pivot).
  void fix_omega(const std::string& group, AngularTimeFunction<D> w) {
    prescribe_motion(group, std::nullopt, std::move(w), "vv");
  }
  /// Fixed temperature [K] of the group's particles (while the function is active) and walls.
  void fix_temperature(const std::string& group, TimeFunction T) {
    Sim& s = self();
    static_assert(Sim::thermal,
                  "grain::Simulation::fix_temperature needs a thermal simulation: give "
                  "the Interaction a conduction model");
    detail::require_non_negative("Simulation::fix_temperature (group '" + group + "')",
                                 "temperature", T, s.time_, "[0, inf) K");
    const auto g = s.cond_.find(group);
    for (auto& w : s.group_walls(g)) {
      s.walls_[w].options.temperature = T;
      s.walls_[w].temperature = std::numeric_limits<double>::quiet_NaN();
      s.walls_[w].update_temperature(s.time_);
    }
    s.cond_.temperatures.push_back({g, std::move(T)});
    s.groups_dirty_ = true;
    // a wall that starts to conduct changes the conductances (stored once by a thermal
    // analysis) and the conduction time-step limit: initialise again (the time continues)
    if (!s.group_walls(g).empty()) s.initialized_ = false;
  }
  /// Prescribed motion (the third seed's PRESCRIBE): a linear and an angular history, each
  /// optional, read as velocities or accelerations by `kind` ("vv", "va", "av", "aa"; linear
  /// first). Walls of the group take velocity histories as their velocities.
  void prescribe_motion(const std::string& group, std::optional<VectorTimeFunction<D>> linear,
                        std::optional<AngularTimeFunction<D>> angular,
                        std::string_view kind = "vv") {
    Sim& s = self();
    const auto [lk, ak] =
        motion_kinds(kind, "Simulation::prescribe_motion (group '" + group + "')");
    const auto g = s.cond_.find(group);
    if (!linear && !angular)
      throw InputError("Simulation::prescribe_motion (group '" + group +
                       "'): linear = angular = none is invalid; valid: at least one history");
    for (auto w : s.group_walls(g)) {
      if ((linear && lk == MotionKind::acceleration) || (angular && ak == MotionKind::acceleration))
        throw InputError("Simulation::prescribe_motion (group '" + group + "'): kind = '" +
                         std::string(kind) + "' is invalid for wall '" + s.walls_[w].options.name +
                         "'; valid for walls: velocities ('vv')");
      if (linear) s.walls_[w].velocity_function = *linear;
      if (angular) s.walls_[w].omega_function = *angular;
      s.walls_[w].update_motion(s.time_);
    }
    if (linear) s.cond_.linear_motion.push_back({g, std::move(*linear), lk});
    if (angular) s.cond_.angular_motion.push_back({g, std::move(*angular), ak});
    s.groups_dirty_ = true;
  }
  /// Restrains the motion of the group's particles along up to D linear directions and the
  /// rotation about up to 3 axes (3D; in 2D any non-zero entry restrains the rotation): the
  /// velocity, force, angular velocity and torque components along them are removed.
  void restrain(const std::string& group, const std::vector<V>& linear,
                const std::vector<A>& angular = {}) {
    Sim& s = self();
    const std::string obj = "Simulation::restrain (group '" + group + "')";
    typename detail::ConditionSet<D>::RestraintOn r;
    r.group = s.cond_.find(group);
    r.linear = detail::orthonormal<D>(linear, obj, "linear");
    if constexpr (D == 3) {
      r.angular = detail::orthonormal<3>(angular, obj, "angular");
    } else {
      for (double a : angular) {
        detail::require(std::isfinite(a) && a != 0.0, obj, "angular direction", a,
                        "a non-zero number (the z axis)");
        r.rotation = true;
      }
    }
    s.cond_.restraints.push_back(std::move(r));
    s.groups_dirty_ = true;
    s.ensure_groups();
    // between runs: the loads of the last evaluation, which the next first half kick uses, too
    s.cond_.restrain_loads(s.particles_);
    s.cond_.restrain_velocities(s.particles_);
  }

  /// Adds a property that follows a table of temperature, time or speed for the particles of a
  /// group (see conditions/variable_property.hpp); applied at initialisation and every
  /// `every` steps while active.
  void add_variable_property(VariableProperty vp) {
    Sim& s = self();
    vp.validate();
    const auto g = s.cond_.find(vp.group);
    if (vp.variable == Variable::temperature && !Sim::thermal)
      throw InputError(std::string("VariableProperty (") + property_name(vp.property) +
                       "): variable = temperature is invalid without a thermal state; valid: "
                       "time or speed (or give the Interaction a conduction model)");
    if constexpr (!Sim::thermal)
      if (vp.property == Property::heat_capacity || vp.property == Property::conductivity)
        throw InputError(std::string("VariableProperty: property = ") + property_name(vp.property) +
                         " is invalid without a thermal state; valid: mechanical properties");
    if constexpr (Sim::contact_type::cohesive)
      if (vp.property == Property::young || vp.property == Property::poisson)
        throw InputError(std::string("VariableProperty (") + property_name(vp.property) +
                         "): a variable elastic property is invalid with the adhesive normal "
                         "model " +
                         Sim::contact_type::normal_model::object +
                         " (its reach across gaps is sized from the materials' E*); valid: "
                         "restitution, friction, rolling_friction, radius, density or thermal "
                         "properties");
    if (s.vprops_.add(std::move(vp), g, s.particles_.size())) s.table_.set_per_particle(true);
    per_entry_from_now(s);
  }

  /// Adds a contact property of walls (their indices from add_wall) that follows a table of the
  /// wall's temperature, the time or the wall's translational speed: Young's modulus, Poisson
  /// ratio, restitution, friction, rolling friction or conductivity of the wall's material, for
  /// these walls only. Applied at initialisation and every `vp.every` steps while active, like
  /// a particle property; the contacts with these walls take the mixed values. `vp.group` is
  /// not used (it names particles).
  void add_wall_variable_property(const std::vector<std::size_t>& walls, VariableProperty vp) {
    Sim& s = self();
    vp.validate();
    const std::string obj =
        std::string("VariableProperty (") + property_name(vp.property) + ", walls)";
    if (!is_contact_property(vp.property))
      throw InputError(obj + ": property = " + property_name(vp.property) +
                       " is invalid for a wall (rigid, without mass or heat capacity); valid: "
                       "young, poisson, restitution, friction, rolling_friction or conductivity");
    if (walls.empty()) throw InputError(obj + ": walls = {} is invalid; valid: wall indices");
    std::vector<std::uint32_t> ws;
    for (const auto w : walls) {
      if (w >= s.walls_.size())
        throw InputError(obj + ": wall = " + std::to_string(w) + " is invalid; valid range: [0, " +
                         std::to_string(s.walls_.size()) + ") (indices returned by add_wall)");
      if (vp.variable == Variable::temperature && !s.walls_[w].conducts())
        throw InputError(obj + ": variable = temperature is invalid for wall " + std::to_string(w) +
                         " ('" + s.walls_[w].options.name +
                         "'), which has no temperature; valid: time or speed (or give the wall "
                         "a temperature)");
      ws.push_back(static_cast<std::uint32_t>(w));
    }
    if constexpr (!Sim::thermal)
      if (vp.property == Property::conductivity)
        throw InputError(obj + ": property = conductivity is invalid without a thermal state; "
                               "valid: mechanical properties");
    if constexpr (Sim::contact_type::cohesive)
      if (vp.property == Property::young || vp.property == Property::poisson)
        throw InputError(obj +
                         ": a variable elastic property is invalid with the adhesive "
                         "normal model " +
                         Sim::contact_type::normal_model::object +
                         " (its reach across gaps is sized from the materials' E*); valid: "
                         "restitution, friction, rolling_friction or conductivity");
    if (s.vprops_.add_walls(std::move(vp), std::move(ws), s.particles_.size()))
      s.table_.set_per_particle(true);
    per_entry_from_now(s);
  }
  /// The same for one wall.
  void add_wall_variable_property(std::size_t wall, VariableProperty vp) {
    add_wall_variable_property(std::vector<std::size_t>{wall}, std::move(vp));
  }

private:
  /// The contact pass and the visits of contacts read per-entry properties from now on.
  static void per_entry_from_now(Sim& s) {
    if (s.vprops_.per_particle && Diagnostics<Sim>::listed_rows(s) == s.particles_.size())
      NeighbourRebuild<Sim>::refresh_pair_cache(s);
    s.initialized_ = false;
  }
};

} // namespace grain::detail
