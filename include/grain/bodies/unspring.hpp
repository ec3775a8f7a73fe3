#pragma once
/// \file unspring.hpp
/// Rule-based failure and activation of translational springs (the UNSPRING command of the
/// Parmec user manual), on the springs' latest values and states only: no bodies are involved.
///
/// A rule watches the "test" springs and, once triggered, undoes the "modified" springs:
///
///   value = OP_{i in tsprings} E_i        (OP = SUM, MIN or MAX; E_i = abs(E_i) if `abs`)
///
/// with the entity E one of stroke [m] ('STROKE'), total force F [N] ('F'), elastic force f [N]
/// ('SF', the default) or friction force abs(F_t) [N] ('FF') of `SpringResult`. The value is
/// checked every `nsteps` calls of `update` (one call per time step; the first check is at the
/// nsteps-th call). It is outside the limits if value < min or value > max (either limit may be
/// absent). After `nfreq` consecutive checks outside the limits (a check inside resets the count)
/// the rule fires, once:
/// - each modified spring with an unloading curve g (x = accumulated stroke increments [m],
///   y = force decrease [N]; g(0) = 0, non-decreasing) is unloaded along it: with f0 its elastic
///   force when the rule fires and D the sum of abs(stroke increments) since then,
///   f = sign(f0) max(0, abs(f0) - g(D)), so that increments of either sign lower the force; the
///   dashpot and friction are off meanwhile; at zero force, or once D reaches the curve's last
///   abscissa (the end of the unloading), the spring is undone for good. Its
///   state code is the index of the curve in `UnspringRule::unload`;
/// - every other modified spring is undone at once (zero force, state code -1);
/// - once all modified springs are undone, the springs listed in `activate` become active
///   (state code -2).
/// The modified springs keep being evaluated by `evaluate` (spring.hpp), which carries out the
/// gradual unloading; `update` only reads the results and changes the states.

#include <grain/bodies/spring.hpp>
#include <grain/core/error.hpp>
#include <grain/core/table.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace grain::bodies {

/// The scalar spring entity a rule tests.
enum class SpringEntity : std::uint8_t {
  stroke,         ///< 'STROKE' [m]
  total_force,    ///< 'F' [N]
  elastic_force,  ///< 'SF' [N]
  friction_force, ///< 'FF' [N]
};

/// How the test springs' values are combined.
enum class SpringOperator : std::uint8_t { sum, min, max };

/// The parameters of one rule; spring numbers index the caller's arrays of results and states.
struct UnspringRule {
  std::vector<std::size_t> tsprings; ///< test springs (non-empty, unique)
  std::vector<std::size_t> msprings; ///< modified springs (non-empty, unique)
  std::optional<double> min{};       ///< lower limit (absent: none)
  std::optional<double> max{};       ///< upper limit (absent: none); min < max
  SpringEntity entity = SpringEntity::elastic_force;
  SpringOperator op = SpringOperator::sum;
  bool abs = false; ///< take abs of each value before combining
  int nsteps = 1;   ///< calls of `update` between checks (>= 1)
  int nfreq = 1;    ///< consecutive checks outside the limits before firing (>= 1)
  /// Gradual unloading curves: (modified spring, curve); the others are undone at once.
  std::vector<std::pair<std::size_t, Table>> unload{};
  std::vector<std::size_t> activate{}; ///< dormant springs to activate after the unloading
  std::string name = "UNSPRING";       ///< name used in error messages
};

/// What one call of `Unspring::update` did.
struct UnspringEvent {
  bool checked = false;   ///< the rule was checked at this call
  bool outside = false;   ///< ... and the value was outside the limits
  bool fired = false;     ///< the rule fired at this call
  bool activated = false; ///< the `activate` springs were switched on at this call
  double value = 0.0;     ///< the combined value (when checked)
};

/// One rule with its counters. No virtual functions, no heap work in `update`.
class Unspring {
public:
  /// Validates the rule against `spring_count` springs; throws `InputError` for bad input.
  Unspring(UnspringRule rule, std::size_t spring_count) : rule_(std::move(rule)) {
    validate(spring_count);
  }
  /// Springs being unloaded point to the rule's curves: a rule is moved, never copied, and must
  /// outlive that unloading.
  Unspring(const Unspring&) = delete;
  Unspring& operator=(const Unspring&) = delete;
  Unspring(Unspring&&) noexcept = default;
  Unspring& operator=(Unspring&&) noexcept = default;

  /// The combined value of the entity over the test springs.
  double value(std::span<const SpringResult> results) const {
    double acc = rule_.op == SpringOperator::sum   ? 0.0
                 : rule_.op == SpringOperator::min ? std::numeric_limits<double>::infinity()
                                                   : -std::numeric_limits<double>::infinity();
    for (const std::size_t i : rule_.tsprings) {
      double x = entity_value(results[i]);
      if (rule_.abs) x = std::abs(x);
      switch (rule_.op) {
      case SpringOperator::sum:
        acc += x;
        break;
      case SpringOperator::min:
        acc = std::min(acc, x);
        break;
      case SpringOperator::max:
        acc = std::max(acc, x);
        break;
      }
    }
    return acc;
  }

  /// One time step: checks the rule when due, fires it, activates springs when the modified
  /// ones are all undone. `results` and `states` hold all springs (indexed by spring number).
  UnspringEvent update(std::span<const SpringResult> results, std::span<SpringState> states) {
    UnspringEvent ev;
    ++calls_;
    if (!fired_ && calls_ % static_cast<std::uint64_t>(rule_.nsteps) == 0) {
      ev.checked = true;
      ev.value = value(results);
      ev.outside = (rule_.min && ev.value < *rule_.min) || (rule_.max && ev.value > *rule_.max);
      count_ = ev.outside ? count_ + 1 : 0;
      if (count_ >= rule_.nfreq) {
        fire(results, states);
        ev.fired = true;
      }
    }
    if (fired_ && !activated_) {
      const bool all_undone = std::all_of(rule_.msprings.begin(), rule_.msprings.end(),
                                          [&](std::size_t i) { return !states[i].active; });
      if (all_undone) {
        for (const std::size_t i : rule_.activate)
          bodies::activate(states[i]);
        activated_ = true;
        ev.activated = !rule_.activate.empty();
      }
    }
    return ev;
  }

  bool fired() const noexcept { return fired_; }
  bool activated() const noexcept { return activated_; }
  /// Consecutive checks outside the limits so far.
  int count() const noexcept { return count_; }
  const UnspringRule& rule() const noexcept { return rule_; }

  /// The rule's state in a checkpoint (BodySystem::serialize).
  template <class Archive>
  void serialize(Archive& ar) {
    ar(calls_, count_, fired_, activated_);
  }

private:
  double entity_value(const SpringResult& r) const {
    switch (rule_.entity) {
    case SpringEntity::stroke:
      return r.stroke;
    case SpringEntity::total_force:
      return r.total;
    case SpringEntity::elastic_force:
      return r.elastic;
    case SpringEntity::friction_force:
      return r.friction;
    }
    return 0.0;
  }

  void fire(std::span<const SpringResult> results, std::span<SpringState> states) {
    fired_ = true;
    for (const std::size_t i : rule_.msprings) {
      SpringState& st = states[i];
      std::size_t curve = rule_.unload.size();
      for (std::size_t j = 0; j < rule_.unload.size(); ++j)
        if (rule_.unload[j].first == i) curve = j;
      if (curve == rule_.unload.size() || !st.active || results[i].elastic == 0.0) {
        deactivate(st);
        continue;
      }
      st.rule_unload = &rule_.unload[curve].second;
      st.rule_force0 = results[i].elastic;
      st.rule_path = 0.0;
      st.code = static_cast<int>(curve);
      st.tangential = {};
    }
  }

  void validate(std::size_t n) const {
    using grain::detail::require;
    using grain::detail::to_text;
    const std::string& obj = rule_.name;
    const auto check_list = [&](const std::vector<std::size_t>& list, const char* what,
                                bool non_empty) {
      if (non_empty && list.empty())
        throw InputError(obj + ": number of " + what + " = 0 is invalid; valid range: [1, inf)");
      for (std::size_t j = 0; j < list.size(); ++j) {
        require(list[j] < n, obj, (std::string(what) + "[" + std::to_string(j) + "]").c_str(),
                list[j], "[0, " + std::to_string(n) + ") (a spring number)");
        for (std::size_t l = 0; l < j; ++l)
          if (list[l] == list[j])
            throw InputError(obj + ": " + what + "[" + std::to_string(j) +
                             "] = " + std::to_string(list[j]) +
                             " is invalid; valid range: a spring not "
                             "already listed (numbers must be unique)");
      }
    };
    check_list(rule_.tsprings, "tsprings", true);
    check_list(rule_.msprings, "msprings", true);
    check_list(rule_.activate, "activate", false);
    if (!rule_.min && !rule_.max)
      throw InputError(obj + ": limits = (none, none) is invalid; valid range: at least one of "
                             "min, max");
    if (rule_.min) require(!std::isnan(*rule_.min), obj, "min", *rule_.min, "a number");
    if (rule_.max) require(!std::isnan(*rule_.max), obj, "max", *rule_.max, "a number");
    if (rule_.min && rule_.max)
      require(*rule_.min < *rule_.max, obj, "min", *rule_.min,
              "(-inf, max) = (-inf, " + to_text(*rule_.max) + ")");
    require(rule_.nsteps >= 1, obj, "nsteps", rule_.nsteps, "[1, inf)");
    require(rule_.nfreq >= 1, obj, "nfreq", rule_.nfreq, "[1, inf)");
    for (std::size_t j = 0; j < rule_.unload.size(); ++j) {
      const auto& [spring, curve] = rule_.unload[j];
      const std::string w = "unload[" + std::to_string(j) + "]";
      if (std::find(rule_.msprings.begin(), rule_.msprings.end(), spring) == rule_.msprings.end())
        throw InputError(obj + ": " + w + " spring = " + std::to_string(spring) +
                         " is invalid; valid range: a spring of msprings");
      for (std::size_t l = 0; l < j; ++l)
        if (rule_.unload[l].first == spring)
          throw InputError(obj + ": " + w + " spring = " + std::to_string(spring) +
                           " is invalid; valid range: a spring without another unloading curve");
      grain::detail::require_given(curve, obj, w, "the unloading curve");
      const auto& x = curve.x();
      const auto& y = curve.y();
      if (x[0] != 0.0 || y[0] != 0.0)
        throw InputError(obj + ": " + w + " " + curve.label() + " first point = (" + to_text(x[0]) +
                         ", " + to_text(y[0]) +
                         ") is invalid; valid range: (0, 0) (the curve starts at zero)");
      for (std::size_t i = 1; i < y.size(); ++i)
        if (y[i] < y[i - 1])
          throw InputError(obj + ": " + w + " " + curve.label() + " y[" + std::to_string(i) +
                           "] = " + to_text(y[i]) + " is invalid; valid range: [" +
                           to_text(y[i - 1]) + ", inf) (the curve must not decrease)");
      if (!(y.back() > 0.0))
        throw InputError(obj + ": " + w + " " + curve.label() + " y[last] = " + to_text(y.back()) +
                         " is invalid; valid range: (0, inf)");
    }
  }

  UnspringRule rule_;
  std::uint64_t calls_ = 0;
  int count_ = 0;
  bool fired_ = false;
  bool activated_ = false;
};

} // namespace grain::bodies
