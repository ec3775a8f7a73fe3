#pragma once
/// \file state_check.hpp
/// The checks that stop a run which has gone wrong, and a set-up that would make it go wrong.
///
/// | check | when | limit | raises |
/// |---|---|---|---|
/// | finite position, velocity, angular velocity, force, torque, temperature | each neighbour rebuild, each output, the end of `steps` | a finite number | NumericalError |
/// | speed | the same | abs(v) dt <= f R, abs(w) dt <= f rad, f = max_step_travel (1) | NumericalError |
/// | overlap of two particles | each output, the end of `steps` | the centre of neither inside the other, abs(x_j - x_i) > max(R_i, R_j) | NumericalError |
/// | particle behind a plane | the same | signed distance >= 0 | NumericalError |
/// | overlap at the start | `initialize`, for particles and walls added since the last start | delta <= max_start_overlap min(R_i, R_j) (walls: R_i) | InputError |
///
/// A particle that moves more than its radius in one step cannot have its contacts resolved (a
/// contact lasts tens of steps at a stable step); one whose centre is inside another has passed
/// through it. Both are the marks of a time step above the stable limit, a load or property that
/// is not finite, or a set-up that fires particles apart. The messages name the particle (or both
/// particles), the quantity, its value, the step and the time, with the stable limits computed at
/// the start of the run (the state of a failed step gives none).
///
/// A component of `Simulation` (simulation.hpp): static functions over the simulation's state,
/// which declares it a friend.

#include <grain/core/error.hpp>
#include <grain/search/search.hpp>
#include <grain/simulation/components.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace grain::detail {

template <class Sim>
struct StateCheck {
  using V = typename Sim::V;
  using A = typename Sim::A;
  static constexpr int D = Sim::D;
  static constexpr bool thermal = Sim::thermal;
  static constexpr long parallel_threshold = Sim::parallel_threshold;

  /// Throws NumericalError naming the first particle with a quantity that is not finite or a
  /// speed beyond one radius per step. O(N); run at each neighbour rebuild (a non-finite or fast
  /// particle forces one: its displacement passes the skin) and before each output.
  static void particles(const Sim& s) {
    const auto& p = s.particles_;
    const long n = static_cast<long>(p.size());
    const double dt = s.initialized_ ? s.dt_ : 0.0;
    bool all = true;
#pragma omp parallel for reduction(&& : all) schedule(static) if (n >= parallel_threshold)
    for (long i = 0; i < n; ++i)
      all = all && sound(s, static_cast<std::size_t>(i), dt);
    if (all) [[likely]]
      return;
    std::size_t i = 0;
    while (sound(s, i, dt))
      ++i;
    const auto [what, valid] = what_is_wrong(s, i, dt);
    throw NumericalError("Simulation: particle " + std::to_string(p.id[i]) + " has " + what +
                         at(s) + "; valid range: " + valid + "." + diagnosis(s));
  }

  /// Throws NumericalError naming the first pair of listed particles with the centre of one
  /// inside the other, or the first particle with its centre behind a plane wall. O(contacts).
  static void overlaps(const Sim& s) {
    const auto& p = s.particles_;
    const std::size_t rows = std::min(s.list_.rows(), p.size());
    for (std::size_t i = 0; i < rows; ++i) {
      for (const auto e : s.list_.pair_entries(i)) {
        const auto j = s.list_.partners[e];
        const double reach = std::max(p.radius[i], p.radius[j]);
        const double d2 = s.separation(i, j).squaredNorm();
        if (d2 > reach * reach || (s.fixed_particle(i) && s.fixed_particle(j))) [[likely]]
          continue;
        const double d = std::sqrt(d2);
        throw NumericalError(
            "Simulation: particles " + std::to_string(p.id[i]) + " and " + std::to_string(p.id[j]) +
            " overlap by " + detail::to_text(p.radius[i] + p.radius[j] - d) +
            " m, beyond the smaller radius " + detail::to_text(std::min(p.radius[i], p.radius[j])) +
            " m (centre distance " + detail::to_text(d) + " m)" + at(s) +
            "; valid: centre distance > max(R_i, R_j) = " + detail::to_text(reach) + " m." +
            diagnosis(s));
      }
      for (const auto e : s.list_.wall_entries(i)) {
        const auto w = s.list_.walls[e];
        const double d = s.walls_[w].proximity(p.position[i]).distance;
        if (d >= 0.0) [[likely]]
          continue;
        throw NumericalError("Simulation: particle " + std::to_string(p.id[i]) +
                             " has its centre " + detail::to_text(-d) + " m behind wall " +
                             wall_name(s, w) + at(s) + "; valid: a centre in front of the wall." +
                             diagnosis(s));
      }
    }
  }

  /// Throws InputError naming the first pair (particle and particle, or particle and wall) that
  /// overlaps by more than SimulationParams::max_start_overlap times the smaller radius, among
  /// the particles and walls added since the last start (all of them at the first). Run by
  /// `initialize` after the neighbour list is built; forgets the particles and walls checked.
  static void start_overlaps(Sim& s) {
    const double limit = s.params_.max_start_overlap;
    const auto& p = s.particles_;
    if (!s.fresh_ids_.empty() || s.checked_walls_ < s.walls_.size()) {
      std::sort(s.fresh_ids_.begin(), s.fresh_ids_.end());
      auto fresh = [&](std::size_t i) {
        return std::binary_search(s.fresh_ids_.begin(), s.fresh_ids_.end(), p.id[i]);
      };
      const std::size_t rows = std::min(s.list_.rows(), p.size());
      for (std::size_t i = 0; i < rows && std::isfinite(limit); ++i) {
        const bool fi = fresh(i);
        for (const auto e : s.list_.pair_entries(i)) {
          const auto j = s.list_.partners[e];
          const double rs = std::min(p.radius[i], p.radius[j]);
          const double delta = p.radius[i] + p.radius[j] - s.separation(i, j).norm();
          if (delta <= limit * rs || !(fi || fresh(j)) ||
              (s.fixed_particle(i) && s.fixed_particle(j)))
            continue;
          throw InputError("Simulation: particles " + std::to_string(p.id[i]) + " and " +
                           std::to_string(p.id[j]) + " overlap by " + detail::to_text(delta) +
                           " m = " + detail::to_text(delta / rs) +
                           " of the smaller radius at the start (t = " + detail::to_text(s.time_) +
                           " s); valid range: [0, " + detail::to_text(limit) +
                           "] of the smaller radius (SimulationParams::max_start_overlap; such "
                           "an overlap would fire them apart). Move them apart, or raise "
                           "max_start_overlap to allow it");
        }
        for (const auto e : s.list_.wall_entries(i)) {
          const auto w = s.list_.walls[e];
          const double delta = p.radius[i] - s.walls_[w].proximity(p.position[i]).distance;
          if (delta <= limit * p.radius[i] || !(fi || w >= s.checked_walls_)) continue;
          throw InputError("Simulation: particle " + std::to_string(p.id[i]) + " overlaps wall " +
                           wall_name(s, w) + " by " + detail::to_text(delta) +
                           " m = " + detail::to_text(delta / p.radius[i]) +
                           " of its radius at the start (t = " + detail::to_text(s.time_) +
                           " s); valid range: [0, " + detail::to_text(limit) +
                           "] of the radius (SimulationParams::max_start_overlap; a particle "
                           "behind a plane overlaps it by more than its radius). Move it, or "
                           "raise max_start_overlap to allow it");
        }
      }
    }
    s.fresh_ids_.clear();
    s.checked_walls_ = s.walls_.size();
  }

  /// What is wrong with a run state just read (from a checkpoint): "" if it can be run, else the
  /// first item that cannot, for the reader's message. Checks what later steps index with or
  /// divide by, so that a corrupt file fails at the load and not in a step: particle values
  /// finite, radii, masses and inertias positive, materials, unique ids below the next id, the
  /// run counters, the neighbour list with its histories (contact histories whose bytes are not a
  /// history of the models, a truth value of 2 say), the stored conductances and the particles
  /// waiting for their creation time.
  static std::string loaded(const Sim& s) {
    const auto& p = s.particles_;
    const std::size_t n = p.size(), materials = s.materials().size();
    auto num = [](double x) { return detail::to_text(x); };
    auto positive = [](double x) { return std::isfinite(x) && x > 0.0; };
    auto non_negative = [](double x) { return std::isfinite(x) && x >= 0.0; };
    if (s.step_ < 0 || s.step0_ < 0 || s.step0_ > s.step_ || s.steps_since_rebuild_ < 0 ||
        s.steps_since_cells_ < 0)
      return "the step counters (step " + std::to_string(s.step_) + ", start " +
             std::to_string(s.step0_) + ")";
    for (std::size_t i = 0; i < n; ++i) {
      const std::string who = "particle " + std::to_string(i);
      if (!(p.position[i].allFinite() && finite(p.velocity[i]) && finite(p.omega[i]) &&
            finite(p.force[i]) && finite(p.torque[i]) && finite_orientation(p.orientation[i])))
        return "a value of " + who + " that is not finite";
      if (!positive(p.radius[i])) return "the radius " + num(p.radius[i]) + " m of " + who;
      if (!non_negative(p.mass[i]) || !non_negative(p.inv_mass[i]) || !non_negative(p.inertia[i]) ||
          !non_negative(p.inv_inertia[i]))
        return "the mass or inertia of " + who;
      if (p.material[i] >= materials)
        return "material " + std::to_string(p.material[i]) + " of " + who + " (" +
               std::to_string(materials) + " materials)";
      if (p.id[i] < 0 || p.id[i] >= s.next_id_)
        return "id " + std::to_string(p.id[i]) + " of " + who + " (next id " +
               std::to_string(s.next_id_) + ")";
      if constexpr (thermal)
        if (!std::isfinite(p.temperature[i]) || !std::isfinite(p.heat_rate[i]) ||
            !non_negative(p.heat_capacity[i]) || !non_negative(p.inv_heat_capacity[i]))
          return "a thermal value of " + who;
    }
    std::vector<std::int64_t> ids(p.id.begin(), p.id.end());
    std::sort(ids.begin(), ids.end());
    if (std::adjacent_find(ids.begin(), ids.end()) != ids.end()) return "a repeated particle id";
    if (s.initialized_ && !positive(s.dt_)) return "the time step " + num(s.dt_) + " s";
    if (!std::isfinite(s.time_) || !std::isfinite(s.time_offset_) || std::isnan(s.end_time_))
      return "the time " + num(s.time_) + " s";
    if (!non_negative(s.r_max_) || !non_negative(s.skin_) || !non_negative(s.reach_) ||
        !non_negative(s.cutoff_) || !non_negative(s.gap_reach_))
      return "the search distances (skin " + num(s.skin_) + " m)";
    if (s.initialized_ && s.snapshot_.size() != n)
      return "the positions of the last rebuild (" + std::to_string(s.snapshot_.size()) + " for " +
             std::to_string(n) + " particles)";
    // the list has a row per particle once started; before (particles added since) a row for
    // each particle it was built with, the first ones
    const std::size_t rows = s.list_.offsets.empty() ? 0 : s.list_.rows();
    if (s.list_.offsets.empty() || (s.initialized_ ? rows != n : rows > n))
      return "the neighbour list (" + std::to_string(s.list_.offsets.size()) + " offsets for " +
             std::to_string(n) + " particles)";
    try {
      search::require_valid_list(s.list_, rows, "checkpoint");
    } catch (const InputError&) {
      return "the neighbour list";
    }
    for (const auto w : s.list_.walls)
      if (w >= s.walls_.size()) return "wall " + std::to_string(w) + " of the neighbour list";
    using Histories = typename Sim::Histories;
    if constexpr (!Histories::stateless) {
      if (s.hist_.pair.size() != s.list_.partners.size() ||
          s.hist_.wall.size() != s.list_.walls.size())
        return "the number of contact histories";
      for (const auto* hist : {&s.hist_.pair, &s.hist_.wall})
        for (const auto& h : *hist)
          if (!valid_history(h)) return "a contact history";
    }
    for (const auto& c : s.static_pairs_)
      if (c.i >= n || c.j >= n || !std::isfinite(c.conductance)) return "a stored conductance";
    for (const auto& c : s.static_walls_)
      if (c.i >= n || c.j >= s.walls_.size() || !std::isfinite(c.conductance))
        return "a stored wall conductance";
    for (const auto& spec : s.life_.pending)
      if (!positive(spec.radius) || spec.material >= materials || !spec.position.allFinite() ||
          std::isnan(spec.creation_time))
        return "particle " + std::to_string(spec.id) + " waiting for its creation time";
    for (const auto& [t, id] : s.life_.doomed)
      if (std::isnan(t)) return "the destruction time of particle " + std::to_string(id);
    return {};
  }

  /// The stable limits at the start of the run, for the messages of a failed step (the
  /// conduction limit itself only if the step is above its bound; else the bound).
  static std::string limits_text(const Sim& s) {
    std::string t = "the time step " + detail::to_text(s.dt_) + " s; at the start of the run ";
    std::string why;
    if (s.forces_move())
      why = "the Rayleigh time " + detail::to_text(s.rayleigh_time()) +
            " s, the contact limit 2 sqrt(m*/k) " + detail::to_text(s.contact_time_step()) + " s";
    if (s.heats()) {
      const double bound = s.conduction_bound();
      why += std::string(why.empty() ? "" : ", ") +
             (s.dt_ < bound ? "the conduction limit above its bound " + detail::to_text(bound)
                            : "the conduction limit " + detail::to_text(s.conduction_time_step())) +
             " s";
    }
    return t + (why.empty() ? "no stable limit applied" : why);
  }

private:
  static double magnitude(const V& v) { return v.norm(); }
  static double magnitude(double w) { return std::abs(w); }
  static bool finite(const V& v) { return v.allFinite(); }
  static bool finite(double w) { return std::isfinite(w); }
  static bool finite_orientation(double a) { return std::isfinite(a); }
  template <class Q>
  static bool finite_orientation(const Q& q) {
    return q.coeffs().allFinite();
  }
  /// True unless the history's bytes are not a history of the models (a model says which
  /// bytes are valid with a static `valid_bytes`, as one holding a truth value does).
  template <class H>
  static bool valid_history(const H& h) {
    if constexpr (requires { H::valid_bytes(h); })
      return H::valid_bytes(h);
    else
      return true;
  }

  static bool sound(const Sim& s, std::size_t i, double dt) {
    const auto& p = s.particles_;
    if constexpr (thermal)
      if (!std::isfinite(p.temperature[i])) return false;
    if (!(p.position[i].allFinite() && finite(p.velocity[i]) && finite(p.omega[i]) &&
          finite(p.force[i]) && finite(p.torque[i])))
      return false;
    const double f = s.params_.max_step_travel, v2 = p.velocity[i].squaredNorm();
    const double r = f * p.radius[i];
    return v2 * dt * dt <= r * r && magnitude(p.omega[i]) * dt <= f;
  }

  /// What is wrong with particle i (the quantity with its value) and the valid range.
  static std::pair<std::string, std::string> what_is_wrong(const Sim& s, std::size_t i, double dt) {
    const auto& p = s.particles_;
    auto text = [](const auto& v) {
      if constexpr (std::is_same_v<std::decay_t<decltype(v)>, double>)
        return detail::to_text(v);
      else {
        std::string out = "(";
        out += detail::vector_text(v);
        out += ")";
        return out;
      }
    };
    const std::string finite_range = "a finite number";
    if (!p.position[i].allFinite())
      return {"position = " + text(p.position[i]) + " m", finite_range};
    if (!finite(p.velocity[i])) return {"velocity = " + text(p.velocity[i]) + " m/s", finite_range};
    if (!finite(p.omega[i]))
      return {"angular velocity = " + text(p.omega[i]) + " rad/s", finite_range};
    if (!finite(p.force[i])) return {"force = " + text(p.force[i]) + " N", finite_range};
    if (!finite(p.torque[i])) return {"torque = " + text(p.torque[i]) + " N m", finite_range};
    if constexpr (thermal)
      if (!std::isfinite(p.temperature[i]))
        return {"temperature = " + text(p.temperature[i]) + " K", finite_range};
    const double r = p.radius[i], f = s.params_.max_step_travel;
    const double v = p.velocity[i].norm();
    const std::string travel = detail::to_text(f);
    if (v * dt > f * r)
      return {"speed abs(v) = " + detail::to_text(v) + " m/s (" + detail::to_text(v * dt / r) +
                  " radii per step; no contact can be resolved at that speed)",
              "abs(v) dt <= " + travel + " R, abs(v) <= " + detail::to_text(f * r / dt) +
                  " m/s (R = " + detail::to_text(r) + " m; SimulationParams::max_step_travel)"};
    const double w = magnitude(p.omega[i]);
    return {"angular speed abs(w) = " + detail::to_text(w) + " rad/s (" + detail::to_text(w * dt) +
                " rad per step)",
            "abs(w) dt <= " + travel + " rad, abs(w) <= " + detail::to_text(f / dt) +
                " rad/s (SimulationParams::max_step_travel)"};
  }

  static std::string at(const Sim& s) {
    return " in the step from t = " + detail::to_text(s.time_) + " s (step " +
           std::to_string(s.step_) + ")";
  }

  static std::string diagnosis(const Sim& s) {
    return " The time step may be above the stable limit, or a load, property or table may not "
           "be finite (" +
           (s.start_limits_.empty() ? std::string("the run has not started") : s.start_limits_) +
           ")";
  }

  static std::string wall_name(const Sim& s, std::size_t w) {
    const auto& name = s.walls_[w].options.name;
    return std::to_string(w) + (name.empty() ? "" : " '" + name + "'");
  }
};

} // namespace grain::detail
