#pragma once
/// \file setup_api.hpp
/// The set-up of a Simulation, its public API for it: materials and the parameters of their
/// pairs, particles (added, removed), walls, gravity and global damping, and where particles
/// leave (a bounding box, sinks).
///
/// `Simulation` derives from `SetUp<Simulation, D, Contact>` (a base that knows its derived
/// class: no virtual function), so these are members of every simulation.

#include <grain/conditions/regions.hpp>
#include <grain/core/error.hpp>
#include <grain/core/time_function.hpp>
#include <grain/core/vector.hpp>
#include <grain/particles/material.hpp>
#include <grain/setup/insertion.hpp>
#include <grain/simulation/components.hpp>
#include <grain/simulation/pair_table.hpp>
#include <grain/simulation/params.hpp>
#include <grain/walls/walls.hpp>

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
class SetUp {
  using V = Vec<D>;
  Sim& self() { return static_cast<Sim&>(*this); }
  const Sim& self() const { return static_cast<const Sim&>(*this); }

public:
  /// Adds a material; returns its index.
  std::uint32_t add_material(const Material& m) {
    Sim& s = self();
    const auto k = s.table_.add_material(m);
    s.initialized_ = false;
    return k;
  }
  /// Overrides mixed restitution / friction for one pair of materials.
  void set_pair(std::uint32_t a, std::uint32_t b, const PairOverride& o) {
    Sim& s = self();
    s.table_.check_material(a, "set_pair");
    s.table_.check_material(b, "set_pair");
    s.table_.set_override(a, b, o, "Simulation::set_pair");
    s.initialized_ = false;
  }

  /// Contact-model parameters for one pair of materials (either order), replacing
  /// SimulationParams::contact (the default pair) for the contacts of these materials, particle-
  /// particle and particle-wall: the table of contact parameters per pair of surface colours of
  /// the third seed's GRANULAR command, for any contact model. Throws InputError naming the pair
  /// for invalid parameters or materials.
  void set_pair_parameters(std::uint32_t a, std::uint32_t b, const typename Contact::Params& p) {
    Sim& s = self();
    s.table_.check_material(a, "set_pair_parameters");
    s.table_.check_material(b, "set_pair_parameters");
    s.table_.set_parameters(a, b, p, "Simulation::set_pair_parameters");
    s.initialized_ = false;
  }
  /// The contact-model parameters of a pair of materials (SimulationParams::contact unless
  /// set_pair_parameters gave the pair its own).
  const typename Contact::Params& contact_params(std::size_t a, std::size_t b) const {
    const Sim& s = self();
    return s.table_.parameters(a, b);
  }
  /// The materials and the properties and contact parameters of their pairs.
  const PairTable<Contact>& pair_table() const { return self().table_; }

  /// Adds a particle; returns its id. Throws InputError on bad input. A particle with a creation
  /// time later than the current time waits, inactive, until then.
  std::int64_t add_particle(const ParticleSpec<D>& spec) {
    return LifecycleStep<Sim>::add_particle(self(), spec);
  }

  /// Removes the particle with this id (active or not yet created) with its contacts, now:
  /// between runs, or before the first. Its id is not used again (removed_ids). Throws
  /// InputError for an id that is not a particle of the simulation.
  void remove_particle(std::int64_t id) { LifecycleStep<Sim>::remove_particle(self(), id); }

  /// Adds a wall; returns its index. Throws InputError on bad geometry.
  template <class G>
  std::uint32_t add_wall(const G& geometry, WallOptions<D> options = {}) {
    Sim& s = self();
    static_assert(std::is_constructible_v<WallGeometry<D>, G>,
                  "grain::Simulation::add_wall: this wall type does not exist in this dimension "
                  "(2D: walls::Segment, walls::Circle; 3D: walls::Plane, walls::Triangle)");
    Wall<D> w;
    w.geometry = geometry;
    w.options = options;
    w.validate();
    s.table_.check_material(options.material, "Wall '" + options.name + "'");
    w.pivot = options.has_pivot ? options.pivot : Wall<D>::default_pivot(w.geometry);
    w.take_snapshot();
    s.walls_.push_back(w);
    s.initialized_ = false;
    return static_cast<std::uint32_t>(s.walls_.size() - 1);
  }

  /// Switches wall w on or off (WallOptions::active) from the next step: an inactive wall takes
  /// no part in contacts until it is switched on again. Between runs or from a stage (from a hook
  /// inside a step: from the step after). Throws InputError for an index that is not a wall.
  void set_wall_active(std::uint32_t w, bool on) {
    Sim& s = self();
    s.check_wall(w, "set_wall_active");
    s.walls_[w].options.active = on;
    s.next_wall_event_ = -std::numeric_limits<double>::infinity(); // checked by the next step
  }
  /// Removes wall w for good from the next step: it takes no part in contacts and cannot be
  /// switched on again; it keeps its index (groups and output refer to it).
  void remove_wall(std::uint32_t w) {
    Sim& s = self();
    s.check_wall(w, "remove_wall");
    s.walls_[w].removed = true;
    s.next_wall_event_ = -std::numeric_limits<double>::infinity();
  }
  /// True if wall w took part in the contacts of the last step (or, before the first, of the
  /// start): active, created, not destroyed, not removed.
  bool wall_present(std::uint32_t w) const {
    const Sim& s = self();
    s.check_wall(w, "wall_present");
    return s.walls_[w].present;
  }

  /// Constant gravity [m/s^2].
  void set_gravity(const V& g) {
    Sim& s = self();
    for (int d = 0; d < D; ++d)
      detail::require_finite("Simulation", "gravity component", g[d]);
    s.params_.gravity = g;
    s.gravity_fn_.reset();
    s.gravity_now_ = g;
    ++s.gravity_revision_;
  }
  /// Gravity that changes in time [m/s^2] (each component a TimeFunction; 0 while inactive).
  void set_gravity(const VectorTimeFunction<D>& g) {
    Sim& s = self();
    s.gravity_fn_ = g;
    s.gravity_now_ = g(s.time_);
    ++s.gravity_revision_;
  }
  /// Gravity acting at the last force evaluation (or the constant gravity) [m/s^2].
  V gravity() const { return self().gravity_fn_ ? self().gravity_now_ : self().params_.gravity; }
  /// Gravity as a function of time [m/s^2] (a constant function for constant gravity).
  VectorTimeFunction<D> gravity_function() const {
    const Sim& s = self();
    return s.gravity_fn_ ? *s.gravity_fn_ : VectorTimeFunction<D>(s.params_.gravity);
  }
  /// Counts the calls of set_gravity (stages that keep a copy of gravity compare it).
  std::uint64_t gravity_revision() const noexcept { return self().gravity_revision_; }

  /// Global damping that changes in time: force -c_t(t) v [c_t in N s/m] and torque -c_r(t) omega
  /// [c_r in N m s], replacing SimulationParams::damping_translational / damping_rotational.
  void set_damping(TimeFunction translational, TimeFunction rotational = {}) {
    Sim& s = self();
    detail::require_non_negative("Simulation::set_damping", "translational", translational,
                                 s.time_);
    detail::require_non_negative("Simulation::set_damping", "rotational", rotational, s.time_);
    s.damping_fn_ = std::make_pair(std::move(translational), std::move(rotational));
  }
  /// Mass-proportional damping per component (the third seed's DAMPING): force -m (d (.) v) and
  /// torque -I (d_w (.) omega), (.) the componentwise product; d, d_w in 1/s, time functions.
  void set_mass_damping(VectorTimeFunction<D> linear, AngularTimeFunction<D> angular = {}) {
    Sim& s = self();
    for (int d = 0; d < D; ++d)
      detail::require(linear.value(s.time_)[d] >= 0, "Simulation::set_mass_damping",
                      "linear component", linear.value(s.time_)[d], "[0, inf) 1/s");
    if constexpr (D == 2)
      detail::require(angular.value(s.time_) >= 0, "Simulation::set_mass_damping", "angular",
                      angular.value(s.time_), "[0, inf) 1/s");
    else
      for (int d = 0; d < 3; ++d)
        detail::require(angular.value(s.time_)[d] >= 0, "Simulation::set_mass_damping",
                        "angular component", angular.value(s.time_)[d], "[0, inf) 1/s");
    s.mass_damping_ = std::make_pair(std::move(linear), std::move(angular));
  }

  // ---------------------------------------------------------------- lifecycle
  /// Particles whose centre leaves this region are removed (with their contacts), while
  /// t_begin <= t <= t_end [s].
  void set_bounding_box(const Region<D>& region,
                        double t_begin = -std::numeric_limits<double>::infinity(),
                        double t_end = std::numeric_limits<double>::infinity()) {
    Sim& s = self();
    TimedRegion<D> r{region, t_begin, t_end};
    r.validate("Simulation::set_bounding_box");
    s.life_.bounding_box = r;
  }
  /// Particles whose centre enters this region are removed, while t_begin <= t <= t_end [s].
  void add_sink(const Region<D>& region, double t_begin = -std::numeric_limits<double>::infinity(),
                double t_end = std::numeric_limits<double>::infinity()) {
    Sim& s = self();
    TimedRegion<D> r{region, t_begin, t_end};
    r.validate("Simulation::add_sink " + std::to_string(s.life_.sinks.size()));
    s.life_.sinks.push_back(r);
  }
  // ---------------------------------------------------------------- insertion
  /// Adds an insertion of particles during the run (setup/insertion.hpp, docs/insertion.md);
  /// returns its index. Throws InputError naming the insertion, the value and the valid range
  /// for bad input. The group it names is made if it does not exist.
  std::size_t add_insertion(const Insertion<D>& insertion) {
    Sim& s = self();
    const std::size_t k = s.inserts_.entries.size();
    const std::string obj =
        "Simulation::add_insertion " +
        (insertion.name.empty() ? std::to_string(k) : "'" + insertion.name + "'");
    s.table_.check_material(insertion.material, obj);
    if constexpr (Sim::thermal) {
      const Material& m = s.table_.material(insertion.material);
      if (s.heats())
        detail::require(m.heat_capacity > 0, obj + " (material '" + m.name + "')", "heat_capacity",
                        m.heat_capacity, "(0, inf) J/(kg K) (its particles are heated)");
    }
    s.inserts_.add(insertion, obj, s.time_, s.table_.material(insertion.material).density,
                   Sim::thermal);
    auto& e = s.inserts_.entries.back();
    if (!insertion.group.empty()) {
      std::size_t g = s.inserts_.no_group;
      for (std::size_t h = 0; h < s.cond_.groups.size(); ++h)
        if (s.cond_.groups[h].name == insertion.group) g = h;
      if (g == s.inserts_.no_group) {
        try {
          g = s.cond_.add(Group{insertion.group, false, {}, {}});
        } catch (...) {
          s.inserts_.entries.pop_back();
          throw;
        }
      }
      e.group = g;
      s.groups_dirty_ = true;
    }
    s.initialized_ = false; // the search and the time step allow for its particles
    return k;
  }
  /// What insertion k (the index add_insertion returned) has done so far.
  const InsertionStatus& insertion_status(std::size_t k) const {
    const Sim& s = self();
    if (k >= s.inserts_.entries.size())
      throw InputError(std::string("Simulation::insertion_status: insertion = ")
                           .append(std::to_string(k))
                           .append(" is invalid; valid range: [0, ")
                           .append(std::to_string(s.inserts_.entries.size()))
                           .append(") (indices returned by add_insertion)"));
    return s.inserts_.entries[k].status;
  }
  /// The number of insertions added.
  std::size_t insertion_count() const { return self().inserts_.entries.size(); }

  /// Ids of the particles removed so far (bounding box, sinks, destruction time), in order.
  const std::vector<std::int64_t>& removed_ids() const { return self().life_.removed_ids; }
  /// Particles added with a creation time still in the future.
  std::size_t inactive_count() const { return self().life_.pending.size(); }
  /// True if a particle with this id is active (present in the arrays).
  bool is_active(std::int64_t id) const {
    const Sim& s = self();
    return std::find(s.particles_.id.begin(), s.particles_.id.end(), id) != s.particles_.id.end() &&
           !s.life_.removal_requested(id);
  }
};

} // namespace grain::detail
