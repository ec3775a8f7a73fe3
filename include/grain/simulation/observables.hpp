#pragma once
/// \file observables.hpp
/// What a program reads from a Simulation: the loads on the walls, the contacts (visited as the
/// contact pass evaluates them), the properties of particles and pairs, and the energies.
///
/// `Simulation` derives from `Observables<Simulation, D, Contact>` (a base that knows its
/// derived class: no virtual function), so these are members of every simulation.

#include <grain/contact/frame.hpp>
#include <grain/core/error.hpp>
#include <grain/core/vector.hpp>
#include <grain/particles/material.hpp>
#include <grain/simulation/components.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace grain::detail {

template <class Sim, int D, class Contact>
class Observables {
  using V = Vec<D>;
  using A = Angular<D>;
  using History = typename Contact::template History<D>;
  Sim& self() { return static_cast<Sim&>(*this); }
  const Sim& self() const { return static_cast<const Sim&>(*this); }

public:
  /// Force the particles exert on wall w at the last force evaluation [N] (the sum of the
  /// reactions of its contacts, in list order: the same bits for any thread count). Zero before
  /// the first step and after loading a checkpoint, until the next step.
  V wall_force(std::size_t w) const {
    const Sim& s = self();
    s.check_wall(w, "wall_force");
    s.collect_wall_loads();
    return s.wall_loads_.force(w);
  }
  /// Torque the particles exert on wall w about its pivot at the last force evaluation [N m]
  /// (forces at the contact points plus the couples of rolling resistance).
  A wall_torque(std::size_t w) const {
    const Sim& s = self();
    s.check_wall(w, "wall_torque");
    s.collect_wall_loads();
    return s.wall_loads_.torque(w);
  }
  /// Visits every touching particle-wall contact of the last force evaluation with the forces
  /// that were applied: f(particle id, wall index, point [m], force on the wall [N]); used to
  /// spread the load of a wall over its nodes.
  template <class F>
  void for_each_wall_load(F&& f) const {
    const Sim& s = self();
    s.collect_wall_loads();
    for (const auto& c : s.wall_loads_.contacts())
      f(c.id, static_cast<std::size_t>(c.wall), c.point, c.force);
  }
  std::size_t size() const { return self().particles_.size(); }

  /// True if a prescribed motion (fix_velocity, fix_omega, prescribe_motion) or a restraint
  /// covers the particle with this id.
  bool motion_controlled(std::int64_t id) const {
    const Sim& s = self();
    s.ensure_groups();
    for (const auto& c : s.cond_.controls)
      if (c.id == id) return true;
    return false;
  }
  /// Current index of the particle with this id (particles are re-sorted by the cell list).
  std::size_t index_of(std::int64_t id) const {
    const Sim& s = self();
    for (std::size_t i = 0; i < s.particles_.size(); ++i)
      if (s.particles_.id[i] == id) return i;
    throw InputError("Simulation::index_of: id = " + std::to_string(id) +
                     " is invalid; valid range: ids of existing particles");
  }

  /// Effective properties of two materials.
  const PairProperties& pair_properties(std::size_t a, std::size_t b) const {
    const Sim& s = self();
    return s.table_.properties(a, b);
  }
  /// The material of particle i (current index) with its variable properties applied.
  Material material_of(std::size_t i) const {
    const Sim& s = self();
    return s.vprops_.material_of(i, s.table_.material(s.particles_.material[i]));
  }
  /// The material of wall w with its variable properties applied.
  Material wall_material(std::size_t w) const {
    const Sim& s = self();
    return s.vprops_.wall_material_of(w, s.table_.material(s.walls_[w].options.material));
  }
  /// Effective properties of the contact of particle i with particle j (wall = false) or with
  /// wall j (wall = true), with variable properties applied.
  PairProperties contact_pair(std::size_t i, std::size_t j, bool wall) const {
    const Sim& s = self();
    const auto mi = s.particles_.material[i];
    const auto mj = wall ? s.walls_[j].options.material : s.particles_.material[j];
    const auto k = s.table_.index(mi, mj);
    if (!s.vprops_.per_particle) return s.table_.properties(k);
    return s.table_.mix_of(material_of(i), wall ? wall_material(j) : material_of(j), k);
  }

  /// The view of one contact that for_each_contact passes to a one-argument callable.
  using ContactViewType = ContactView<D, typename Contact::template Result<D>, History>;

  /// Visits every touching contact (and, with an adhesive normal model, every pair bonded across
  /// a gap, with a negative overlap): f(i, j_or_wall, is_wall, geometry, result), or, if f takes a
  /// sixth argument, also the heat rate into particle i through the contact [W] (0 without heat
  /// conduction or across an insulated wall), or, if f takes one argument, a `ContactView`
  /// (partners, geometry, result, model data, heat rate and the local frame; see
  /// contact/frame.hpp). The contact models are evaluated on copies of the histories, so the
  /// state is not changed.
  template <class F>
  void for_each_contact(F&& f) const {
    Diagnostics<Sim>::for_each_contact(self(), f);
  }

  /// Visits the conductance of every conducting pair of the current list without changing any
  /// state: f(i, j_or_wall, is_wall, H).
  /// In a thermal analysis the contacts are at rest (particles never move, whatever velocities
  /// they were given).
  template <class F>
  void for_each_conductance(F&& f) const {
    Diagnostics<Sim>::for_each_conductance(self(), f);
  }

  /// Number of touching particle-particle and particle-wall contacts.
  std::pair<std::size_t, std::size_t> contact_counts() const {
    return Diagnostics<Sim>::contact_counts(self());
  }

  /// Translational + rotational kinetic energy [J].
  double kinetic_energy() const {
    const Sim& s = self();
    double e = 0.0;
    for (std::size_t i = 0; i < s.particles_.size(); ++i)
      e += 0.5 * s.particles_.mass[i] * s.particles_.velocity[i].squaredNorm() +
           0.5 * s.particles_.inertia[i] * squared_norm(s.particles_.omega[i]);
    return e;
  }
  /// Elastic energy stored in all contacts [J].
  double elastic_energy() const {
    double e = 0.0;
    for_each_contact([&](auto, auto, bool, const auto&, const auto& r) {
      e += r.normal.elastic_energy + r.tangent.elastic_energy;
    });
    return e;
  }
  /// Energy dissipated since the start [J] (NaN unless SimulationParams::track_dissipation):
  /// the work the contacts and the global damping took from the bodies minus the growth of the
  /// elastic energy stored in the contacts. It covers every dissipative part of the contact
  /// laws (viscous damping, friction, plastic hysteresis, rolling resistance) and the energy a
  /// tangential spring holds when its contact opens. The work is summed with the velocities the
  /// forces see (second order with velocity Verlet).
  double dissipated_energy() const {
    const Sim& s = self();
    if (!s.params_.track_dissipation) return std::numeric_limits<double>::quiet_NaN();
    const double start = std::isnan(s.elastic_start_) ? 0.0 : s.elastic_start_;
    return -s.work_in_ - (elastic_energy() - start);
  }
  /// Gravitational potential energy relative to the origin [J].
  /// With gravity that changes in time (set_gravity with a function), the potential of the
  /// current gravity. With periodic boundaries, of the unwrapped positions (a particle that
  /// wraps along a tilted gravity keeps the energy it lost falling).
  double potential_energy() const {
    const Sim& s = self();
    double e = 0.0;
    const V g = s.gravity();
    for (std::size_t i = 0; i < s.particles_.size(); ++i)
      e -= s.particles_.mass[i] *
           g.dot(s.periodic_.on ? s.unwrapped_position(i) : V(s.particles_.position[i]));
    return e;
  }

  /// Heat content sum C_i T_i of the particles [J] (0 without a thermal state); constant in an
  /// insulated system.
  double thermal_energy() const {
    const Sim& s = self();
    double e = 0.0;
    if constexpr (Sim::thermal)
      for (std::size_t i = 0; i < s.particles_.size(); ++i)
        e += s.particles_.heat_capacity[i] * s.particles_.temperature[i];
    return e;
  }
  /// Mean particle temperature [K] (NaN without particles or thermal state).
  double mean_temperature() const {
    const Sim& s = self();
    double t = 0.0;
    if constexpr (Sim::thermal) {
      if (s.particles_.size() == 0) return std::numeric_limits<double>::quiet_NaN();
      for (double x : s.particles_.temperature)
        t += x;
      return t / static_cast<double>(s.particles_.size());
    } else {
      return std::numeric_limits<double>::quiet_NaN();
    }
  }
};

} // namespace grain::detail
