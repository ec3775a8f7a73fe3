#pragma once
/// \file lifecycle.hpp
/// `Lifecycle<D>`: which particles exist. It holds the particles still to come (a creation time
/// in the future), the destruction times, the bounding box and the sinks, and the ids removed so
/// far; `decide` says, at a time t, which particles go and which arrive. The simulation applies
/// the decision (renumbering its arrays, rebuilding its list).

#include <grain/conditions/regions.hpp>
#include <grain/core/vector.hpp>
#include <grain/simulation/components.hpp>
#include <grain/simulation/params.hpp>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

namespace grain {

template <int D>
struct Lifecycle {
  using V = Vec<D>;

  std::optional<TimedRegion<D>> bounding_box;          ///< particles outside it are removed
  std::vector<TimedRegion<D>> sinks;                   ///< particles inside one are removed
  std::vector<ParticleSpec<D>> pending;                ///< inactive until their creation time
  std::vector<std::pair<double, std::int64_t>> doomed; ///< (destruction time, id)
  std::vector<std::int64_t> removed_ids;      ///< ids removed so far, in order (never given again)
  std::vector<std::int64_t> removal_requests; ///< ids removed between runs, not yet carried out

  /// True if anything may change in a step (else `decide` is never needed).
  bool active() const {
    return !pending.empty() || !doomed.empty() || bounding_box || !sinks.empty();
  }
  /// True if `id` waits for its creation time.
  bool is_pending(std::int64_t id) const {
    return std::any_of(pending.begin(), pending.end(),
                       [&](const ParticleSpec<D>& s) { return s.id == id; });
  }
  /// True if `id` was removed, or is to be removed, and may not be given again.
  bool was_removed(std::int64_t id) const {
    return std::find(removed_ids.begin(), removed_ids.end(), id) != removed_ids.end();
  }
  bool removal_requested(std::int64_t id) const {
    return std::find(removal_requests.begin(), removal_requests.end(), id) !=
           removal_requests.end();
  }
  /// Forgets the destruction time of `id` and counts it as removed.
  void forget(std::int64_t id) {
    std::erase_if(doomed, [&](const auto& d) { return d.second == id; });
    removed_ids.push_back(id);
  }

  /// What `decide` found: `changed` is false if nothing happens; otherwise the particles keep
  /// their arrays' entries `kept` (ascending old indices; all of them if `removed` is false) and
  /// the particles `born` are appended after them, in this order.
  struct Decision {
    bool changed = false;
    bool removed = false;
    std::vector<std::uint32_t> kept;
    std::vector<ParticleSpec<D>> born;
  };

  /// The decision at time t for the particles at `x` with ids `id`: those outside the bounding
  /// box or inside a sink (while active), or whose destruction time has come, go; those whose
  /// creation time has come arrive. Updates the waiting list, the destruction times and the
  /// removed ids. `check_finite()` is called for a particle outside the bounding box whose
  /// position is not finite (it did not leave: the run has failed; it should throw).
  template <class CheckFinite>
  Decision decide(double t, const std::vector<V>& x, const std::vector<std::int64_t>& id,
                  CheckFinite&& check_finite) {
    Decision out;
    const std::size_t n = x.size();
    const bool box = bounding_box && bounding_box->active(t);
    bool sink = false;
    for (const auto& k : sinks)
      sink = sink || k.active(t);
    // nothing to do in most steps: no active region, nobody due
    bool due = box || sink;
    for (std::size_t k = 0; !due && k < doomed.size(); ++k)
      due = doomed[k].first <= t;
    for (std::size_t k = 0; !due && k < pending.size(); ++k)
      due = pending[k].creation_time <= t;
    if (!due) return out;
    std::vector<char> gone(n, 0);
    bool any = false;
    if (box || sink) {
      for (std::size_t i = 0; i < n; ++i) {
        bool leaves = box && !bounding_box->contains(x[i]);
        if (leaves && !x[i].allFinite()) check_finite(); // not a particle that left
        for (const auto& k : sinks)
          if (!leaves && k.active(t) && k.contains(x[i])) leaves = true;
        if (leaves) gone[i] = 1;
        any = any || leaves;
      }
    }
    if (!doomed.empty()) {
      std::vector<std::int64_t> ending;
      std::erase_if(doomed, [&](const std::pair<double, std::int64_t>& d) {
        if (d.first > t) return false;
        ending.push_back(d.second);
        return true;
      });
      if (!ending.empty()) {
        std::sort(ending.begin(), ending.end());
        for (std::size_t i = 0; i < n; ++i)
          if (std::binary_search(ending.begin(), ending.end(), id[i])) {
            gone[i] = 1;
            any = true;
          }
        // inactive particles whose life ends before they start never appear; their ids count
        // as removed (not to be given again), as for remove_particle on a waiting particle
        std::erase_if(pending, [&](const ParticleSpec<D>& s) {
          if (!std::binary_search(ending.begin(), ending.end(), s.id)) return false;
          removed_ids.push_back(s.id);
          return true;
        });
      }
    }
    out.kept.reserve(n);
    if (any) {
      std::vector<std::int64_t> now_removed;
      for (std::size_t i = 0; i < n; ++i) {
        if (gone[i])
          now_removed.push_back(id[i]);
        else
          out.kept.push_back(static_cast<std::uint32_t>(i));
      }
      removed_ids.insert(removed_ids.end(), now_removed.begin(), now_removed.end());
      std::sort(now_removed.begin(), now_removed.end());
      std::erase_if(doomed, [&](const std::pair<double, std::int64_t>& d) {
        return std::binary_search(now_removed.begin(), now_removed.end(), d.second);
      });
    } else {
      for (std::size_t i = 0; i < n; ++i)
        out.kept.push_back(static_cast<std::uint32_t>(i));
    }
    std::vector<ParticleSpec<D>> still;
    for (const auto& s : pending) {
      if (s.creation_time <= t)
        out.born.push_back(s);
      else
        still.push_back(s);
    }
    pending.swap(still);
    out.removed = any;
    out.changed = any || !out.born.empty();
    return out;
  }
};

} // namespace grain

namespace grain::detail {

/// The lifecycle step of a Simulation: applies the decision of `Lifecycle<D>::decide`, removing
/// particles and activating those whose creation time has come, with their contacts, groups,
/// restraints and variable properties. A component of `Simulation` (simulation.hpp): static
/// functions over the simulation's state, which declares it a friend.
template <class Sim>
struct LifecycleStep {
  using Contact = typename Sim::contact_type;
  using V = typename Sim::V;
  using A = typename Sim::A;
  using History = typename Sim::History;
  static constexpr int D = Sim::D;
  static constexpr bool thermal = Sim::thermal;
  static constexpr long parallel_threshold = Sim::parallel_threshold;
  using Heat = HeatStep<Sim>;
  using Neighbours = NeighbourRebuild<Sim>;
  using Shape = typename Sim::shape_type;

  /// Sim::add_particle: validates the particle, then activates it or keeps it for its
  /// creation time.
  static std::int64_t add_particle(Sim& s, const ParticleSpec<D>& spec) {
    ParticleSpec<D> ps = spec;
    ps.id = ps.id >= 0 ? ps.id : s.next_id_;
    const std::int64_t id = ps.id;
    const std::string obj = std::string(Shape::name) + " particle " + std::to_string(id);
    // the next free id (id + 1) must exist
    if (id == std::numeric_limits<std::int64_t>::max())
      throw InputError(obj + ": id = " + std::to_string(id) + " is invalid; valid range: [0, " +
                       std::to_string(id - 1) + "] (or -1 = next free id)");
    // ids below next_id_ may be taken (an id at or above it is new)
    if (id < s.next_id_ && (s.has_particle(id) || s.life_.was_removed(id)))
      throw InputError(obj + ": id = " + std::to_string(id) +
                       " is invalid; valid: an id no other particle has or had (or -1 = next "
                       "free id)");
    // messages are formatted only for bad input (adding a particle must stay cheap)
    if (!all_finite(ps.position))
      detail::require(false, obj, "position", s.to_text(ps.position), "finite coordinates");
    detail::require_positive(obj, "radius", ps.radius);
    if (!all_finite(ps.velocity))
      detail::require(false, obj, "velocity", s.to_text(ps.velocity), "finite components");
    detail::require(all_finite(ps.omega), obj, "omega", "(non-finite)", "finite components");
    s.table_.check_material(ps.material, obj);
    detail::require(!std::isnan(ps.creation_time) &&
                        ps.creation_time < std::numeric_limits<double>::infinity(),
                    obj, "creation_time", ps.creation_time, "[-inf, inf) s");
    if (!(ps.destruction_time > ps.creation_time))
      detail::require(false, obj, "destruction_time", ps.destruction_time,
                      "(creation_time, inf] = (" + detail::to_text(ps.creation_time) + ", inf] s");
    if (!(ps.destruction_time > s.time_))
      detail::require(false, obj, "destruction_time", ps.destruction_time,
                      "(current time, inf] = (" + detail::to_text(s.time_) + ", inf] s");
    if constexpr (thermal) {
      const double t = std::isnan(ps.temperature) ? s.params_.initial_temperature : ps.temperature;
      detail::require(std::isfinite(t) && t >= 0.0, obj, "temperature", t, "[0, inf) K");
      ps.temperature = t;
    } else {
      if (!std::isnan(ps.temperature))
        throw InputError(obj + ": temperature = " + detail::to_text(ps.temperature) +
                         " K is given but the contact has no conduction model; valid: leave it "
                         "unset, or give the Interaction a conduction model");
    }
    s.next_id_ = std::max(s.next_id_, id + 1);
    if (std::isfinite(ps.destruction_time)) s.life_.doomed.push_back({ps.destruction_time, id});
    if (ps.creation_time > s.time_) {
      s.life_.pending.push_back(ps);
    } else {
      append_particle(s, ps);
      s.fresh_ids_.push_back(id); // its overlaps are checked at the next start
      s.groups_dirty_ = true;
    }
    s.initialized_ = false;
    return id;
  }

  /// Sim::remove_particle.
  static void remove_particle(Sim& s, std::int64_t id) {
    if (s.life_.is_pending(id)) {
      std::erase_if(s.life_.pending, [&](const ParticleSpec<D>& ps) { return ps.id == id; });
      s.life_.forget(id);
      return;
    }
    if (!s.has_particle(id))
      throw InputError("Simulation::remove_particle: id = " + std::to_string(id) +
                       " is invalid; valid: the id of a particle of the simulation");
    if (s.initialized_) {
      // as a destruction time that has come: the list is renumbered, the other contacts keep
      // their histories
      s.life_.doomed.push_back({-std::numeric_limits<double>::infinity(), id});
      lifecycle(s);
      return;
    }
    s.life_.forget(id);
    if (s.list_.rows() == 0) { // no list yet: nothing refers to the indices
      std::vector<std::uint32_t> kept;
      for (std::size_t i = 0; i < s.particles_.size(); ++i)
        if (s.particles_.id[i] != id) kept.push_back(static_cast<std::uint32_t>(i));
      Neighbours::keep_particles(s, kept);
      return;
    }
    s.life_.removal_requests.push_back(id); // carried out by initialize, which maps the old list
  }

  /// Appends a validated particle to the arrays (its mass, inertia and heat capacity from its
  /// material), with its fields and variable-property slots.
  static void append_particle(Sim& s, const ParticleSpec<D>& ps) {
    const Material& m = s.table_.material(ps.material);
    const double mass = m.density * s.shape_.volume(ps.radius);
    const double inertia = s.shape_.inertia_factor() * mass * ps.radius * ps.radius;
    auto& p = s.particles_;
    p.id.push_back(ps.id);
    p.position.push_back(ps.position);
    p.velocity.push_back(ps.velocity);
    p.omega.push_back(ps.omega);
    p.orientation.push_back(identity_orientation<D>());
    p.force.push_back(V::Zero());
    p.torque.push_back(zero<A>());
    p.radius.push_back(ps.radius);
    p.mass.push_back(mass);
    p.inv_mass.push_back(ps.fixed ? 0.0 : 1.0 / mass);
    p.inertia.push_back(inertia);
    p.inv_inertia.push_back(ps.fixed ? 0.0 : 1.0 / inertia);
    p.material.push_back(ps.material);
    std::apply([](auto&... f) { (f.emplace_back(), ...); }, s.fields_);
    if (s.periodic_.on) {
      s.image_.emplace_back();
      s.shear_shift_.push_back(0.0);
    }
    s.vprops_.append();
    if constexpr (thermal) {
      const double c = mass * m.heat_capacity;
      p.temperature.push_back(ps.temperature);
      p.heat_rate.push_back(0.0);
      p.heat_capacity.push_back(c);
      p.inv_heat_capacity.push_back(c > 0 ? 1.0 / c : 0.0);
    }
  }

  /// Adds to the decision `d` the particles the insertions place at the current time, tested
  /// against the particles that stay and those that arrive (setup/insertion.hpp).
  static void insert(Sim& s, typename Lifecycle<D>::Decision& d) {
    auto& p = s.particles_;
    const double temperature =
        thermal ? s.params_.initial_temperature : std::numeric_limits<double>::quiet_NaN();
    const std::size_t placed = s.inserts_.place(
        s.time_, p.position, p.radius, d.removed ? &d.kept : nullptr, d.born, s.r_max_,
        [&](double r) { return s.shape_.volume(r); }, temperature, s.next_id_, s.cond_.groups);
    if (placed == 0 || d.changed) return;
    // nothing else changed: every particle keeps its place
    d.changed = true;
    d.kept.resize(p.size());
    for (std::size_t i = 0; i < d.kept.size(); ++i)
      d.kept[i] = static_cast<std::uint32_t>(i);
  }

  /// Sets which walls take part in contacts at time t [s] (WallOptions::active, creation and
  /// destruction times, removal) and the next time one appears or disappears
  /// (`next_wall_event_`). Returns true if a wall appeared or disappeared.
  static bool update_walls(Sim& s, double t) {
    bool changed = false;
    double next = std::numeric_limits<double>::infinity();
    for (auto& w : s.walls_) {
      const bool now = w.exists_at(t);
      changed = changed || now != w.present;
      w.present = now;
      if (w.removed || !w.options.active) continue;
      if (w.options.creation_time > t)
        next = std::min(next, w.options.creation_time);
      else if (w.options.destruction_time > t)
        next = std::min(next, w.options.destruction_time);
    }
    s.next_wall_event_ = next;
    return changed;
  }

  /// At the start of a step whose forces are evaluated at time t: walls that appear or disappear
  /// by then. Their contacts start or end with a rebuild of the list (the other contacts keep
  /// their histories).
  static void wall_events(Sim& s, double t) {
    if (!update_walls(s, t)) return;
    s.collect_wall_loads(); // the loads of the last step, before the list changes
    Neighbours::rebuild(s);
    if constexpr (thermal)
      if (s.analysis() == Analysis::thermal) Heat::store_conductances(s);
  }

  /// Removes the particles that left the bounding box, entered a sink or reached their
  /// destruction time, and activates those whose creation time has come (Lifecycle::decide);
  /// `place`: also run the insertions due now (not at the start of a run: they place their
  /// particles after its steps).
  static void lifecycle(Sim& s, bool place = true) {
    auto& p = s.particles_;
    const double t = s.time_;
    auto d = s.life_.decide(t, p.position, p.id, [&] { s.require_finite_state(); });
    if (place && s.inserts_.active()) insert(s, d);
    if (!d.changed) return;
    s.collect_wall_loads(); // before the particles are renumbered
    if (d.removed) Neighbours::keep_particles(s, d.kept);
    std::vector<std::int64_t> born_ids;
    for (const auto& spec : d.born) {
      append_particle(s, spec);
      p.force.back() = p.mass.back() * s.gravity(); // its first half kick feels its weight
      d.kept.push_back(Sim::none);
      born_ids.push_back(p.id.back());
    }
    const bool born = !d.born.empty();
    s.origin_ = std::move(d.kept);
    s.groups_dirty_ = true;
    Neighbours::rebuild(s);
    s.ensure_groups();
    if (born) {
      s.cond_.restrain_loads(p); // the first half kick of a newborn particle too
      s.cond_.restrain_velocities(p);
      if constexpr (thermal)
        if (s.heats()) s.cond_.fix_temperatures(p, t);
      if (!s.vprops_.empty()) {
        // a newborn particle takes its variable properties now, not at the next update
        std::sort(born_ids.begin(), born_ids.end());
        std::vector<char> newborn(p.size(), 0);
        for (std::size_t i = 0; i < p.size(); ++i)
          newborn[i] = std::binary_search(born_ids.begin(), born_ids.end(), p.id[i]) ? 1 : 0;
        VariablePropertyStep<Sim>::apply(s, true, &newborn);
      }
    }
    if constexpr (thermal)
      if (s.analysis() == Analysis::thermal) Heat::store_conductances(s);
  }
};

} // namespace grain::detail
