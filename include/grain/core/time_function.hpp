#pragma once
/// \file time_function.hpp
/// `TimeFunction`: a scalar that may change in time; `VectorTimeFunction<D>`: a D-vector that may.
///
/// Kinds (t is the simulation time [s]; the value has the unit of whatever it describes):
///
/// | kind          | value f(t)                                              |
/// |---------------|---------------------------------------------------------|
/// | `constant`    | v                                                       |
/// | `linear`      | v0 + slope (t - t0)                                     |
/// | `oscillatory` | base + amplitude sin(2 pi (t - t0) / period + phase)    |
/// | `table`       | piecewise linear in absolute time, end values held      |
/// | `callable`    | a user's function of time, `std::function<double(double)>` |
///
/// Each function has an activity interval [t_begin, t_end] (closed; by default (-inf, inf)).
/// `active(t)` tells whether t lies in it; `operator()(t)` is f(t) while active and **0 while
/// inactive**, so an additive condition (a force, a heat rate, a gravity contribution) simply
/// adds `f(t)`. A condition that replaces a value (a fixed velocity or temperature) tests
/// `active(t)` and leaves the value free while inactive; `value(t)` is f(t) regardless of the
/// interval. The interval does not shift time: t0 of `linear` / `oscillatory` is given
/// explicitly (pass t0 = t_begin for a ramp that starts when the function becomes active), and
/// tables use absolute time.
///
/// A `TimeFunction` is a small value type (a table or a callable is shared, not copied; evaluation
/// is a switch), cheap to copy and to evaluate, and safe to evaluate from several threads at once
/// (a callable: if the user's function is). A plain number converts to a constant:
/// `TimeFunction f = 9.81;`.
///
/// A `callable` is evaluated where grain evaluates the condition it describes: once or twice per
/// step, outside the parallel particle and contact loops (gravity, damping, prescribed motion,
/// wall and obstacle motion, loads, output intervals), never per contact. An exception it throws
/// propagates out of the run. Set-up checks that need a value (a non-negative damping) evaluate
/// it at the current time only.

#include <grain/core/error.hpp>
#include <grain/core/table.hpp>
#include <grain/core/vector.hpp>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <numbers>
#include <string>
#include <type_traits>
#include <utility>

namespace grain {

class TimeFunction {
public:
  enum class Kind : std::uint8_t { constant, linear, oscillatory, table, callable };

  /// The constant 0, always active.
  TimeFunction() = default;
  /// A constant (implicit, so that a plain number can be given wherever a function is expected).
  TimeFunction(double value) { *this = constant(value); }

  /// f(t) = value.
  static TimeFunction constant(double value) {
    detail::require_finite("TimeFunction::constant", "value", value);
    TimeFunction f;
    f.kind_ = Kind::constant;
    f.a_ = value;
    return f;
  }

  /// f(t) = initial + slope (t - t0); slope in [unit of the value]/s, t0 in s.
  static TimeFunction linear(double initial, double slope, double t0 = 0.0) {
    const std::string obj = "TimeFunction::linear";
    detail::require_finite(obj, "initial", initial);
    detail::require_finite(obj, "slope", slope);
    detail::require_finite(obj, "t0", t0);
    TimeFunction f;
    f.kind_ = Kind::linear;
    f.a_ = initial;
    f.b_ = slope;
    f.t0_ = t0;
    return f;
  }

  /// f(t) = base + amplitude sin(2 pi (t - t0) / period + phase); period > 0 [s], phase [rad],
  /// t0 [s]. A negative amplitude flips the sign of the oscillation.
  static TimeFunction oscillatory(double base, double amplitude, double period, double phase = 0.0,
                                  double t0 = 0.0) {
    const std::string obj = "TimeFunction::oscillatory";
    detail::require_finite(obj, "base", base);
    detail::require_finite(obj, "amplitude", amplitude);
    detail::require_positive(obj, "period", period);
    detail::require_finite(obj, "phase", phase);
    detail::require_finite(obj, "t0", t0);
    TimeFunction f;
    f.kind_ = Kind::oscillatory;
    f.a_ = base;
    f.b_ = amplitude;
    f.period_ = period;
    f.omega_ = 2.0 * std::numbers::pi / period;
    f.phase_ = phase;
    f.t0_ = t0;
    return f;
  }

  /// f(t) = table(t): linear interpolation in absolute time, the end values outside the table.
  static TimeFunction table(Table t) { return table(std::make_shared<const Table>(std::move(t))); }
  /// The same with an inline list of (t, value) pairs: `TimeFunction::table({{0, 1}, {2, 3}})`.
  template <std::size_t N>
  static TimeFunction table(const double (&points)[N][2]) {
    return table(Table(points));
  }
  /// The same with a table shared by several functions.
  static TimeFunction table(std::shared_ptr<const Table> t) {
    if (!t) throw InputError("TimeFunction::table: table = null is invalid; valid range: a Table");
    detail::require_given(*t, "TimeFunction::table", "table", "the table of the function");
    TimeFunction f;
    f.kind_ = Kind::table;
    f.table_ = std::move(t);
    return f;
  }

  /// f(t) = fn(t), a user's function of the time [s] (a lambda, a function pointer, a binding to
  /// another language). It must return a finite value; grain's checks of the quantity it
  /// describes apply where it is evaluated.
  static TimeFunction callable(std::function<double(double)> fn) {
    if (!fn)
      throw InputError("TimeFunction::callable: function = empty is invalid; valid: a callable "
                       "double(double) of the time [s]");
    TimeFunction f;
    f.kind_ = Kind::callable;
    f.fn_ = std::make_shared<const std::function<double(double)>>(std::move(fn));
    return f;
  }

  /// A copy that is active only for t_begin <= t <= t_end [s]. Either end may be infinite
  /// (-inf for t_begin, +inf for t_end); t_begin <= t_end.
  [[nodiscard]] TimeFunction active(double t_begin, double t_end) const {
    const std::string obj = std::string("TimeFunction (") + kind_name(kind_) + ")::active";
    detail::require(!std::isnan(t_begin) && t_begin < std::numeric_limits<double>::infinity(), obj,
                    "t_begin", t_begin, "[-inf, inf)");
    if (std::isnan(t_end) || t_end < t_begin || t_end == -std::numeric_limits<double>::infinity())
      throw InputError(obj + ": t_end = " + detail::to_text(t_end) +
                       " is invalid; valid range: [t_begin, inf] = [" + detail::to_text(t_begin) +
                       ", inf]");
    TimeFunction f = *this;
    f.t_begin_ = t_begin;
    f.t_end_ = t_end;
    return f;
  }

  /// True if t_begin <= t <= t_end (false for a NaN t).
  bool active(double t) const noexcept { return t >= t_begin_ && t <= t_end_; }

  /// f(t) while active, 0 while inactive.
  double operator()(double t) const { return active(t) ? value(t) : 0.0; }
  /// The same with a caller-held table cursor (see `Table::operator()(x, hint)`); the hint is
  /// ignored by the other kinds.
  double operator()(double t, std::size_t& hint) const { return active(t) ? value(t, hint) : 0.0; }

  /// f(t), ignoring the activity interval.
  double value(double t) const {
    switch (kind_) {
    case Kind::constant:
      return a_;
    case Kind::linear:
      return a_ + b_ * (t - t0_);
    case Kind::oscillatory:
      return a_ + b_ * std::sin(omega_ * (t - t0_) + phase_);
    case Kind::table:
      return (*table_)(t);
    case Kind::callable:
      return (*fn_)(t);
    }
    return a_;
  }
  /// f(t) with a caller-held table cursor, ignoring the activity interval.
  double value(double t, std::size_t& hint) const {
    return kind_ == Kind::table ? (*table_)(t, hint) : value(t);
  }

  Kind kind() const noexcept { return kind_; }
  double t_begin() const noexcept { return t_begin_; }
  double t_end() const noexcept { return t_end_; }
  /// True if an activity interval narrower than (-inf, inf) was set.
  bool has_interval() const noexcept {
    return t_begin_ > -std::numeric_limits<double>::infinity() ||
           t_end_ < std::numeric_limits<double>::infinity();
  }
  /// The table of a `table` function (null for the other kinds).
  const Table* table_ptr() const noexcept { return table_.get(); }

  /// A one-line description, e.g. "0.5 + 0.1 sin(2 pi (t - 0) / 0.2 + 0), active in [0, 1]".
  std::string describe() const {
    using detail::to_text;
    std::string s;
    switch (kind_) {
    case Kind::constant:
      s = to_text(a_);
      break;
    case Kind::linear:
      s = to_text(a_) + " + " + to_text(b_) + " (t - " + to_text(t0_) + ")";
      break;
    case Kind::oscillatory:
      s = to_text(a_) + " + " + to_text(b_) + " sin(2 pi (t - " + to_text(t0_) + ") / " +
          to_text(period_) + " + " + to_text(phase_) + ")";
      break;
    case Kind::table:
      s = table_->label() + " (" + std::to_string(table_->size()) + " points, t in [" +
          to_text(table_->x_front()) + ", " + to_text(table_->x_back()) + "])";
      break;
    case Kind::callable:
      s = "a function of time";
      break;
    }
    if (has_interval()) s += ", active in [" + to_text(t_begin_) + ", " + to_text(t_end_) + "]";
    return s;
  }

  static const char* kind_name(Kind k) noexcept {
    switch (k) {
    case Kind::constant:
      return "constant";
    case Kind::linear:
      return "linear";
    case Kind::oscillatory:
      return "oscillatory";
    case Kind::table:
      return "table";
    case Kind::callable:
      return "callable";
    }
    return "?";
  }

private:
  Kind kind_ = Kind::constant;
  double a_ = 0.0;      // value, initial value or base
  double b_ = 0.0;      // slope or amplitude
  double t0_ = 0.0;     // time origin [s]
  double period_ = 1.0; // [s]
  double omega_ = 0.0;  // 2 pi / period [rad/s]
  double phase_ = 0.0;  // [rad]
  double t_begin_ = -std::numeric_limits<double>::infinity();
  double t_end_ = std::numeric_limits<double>::infinity();
  std::shared_ptr<const Table> table_;
  std::shared_ptr<const std::function<double(double)>> fn_;
};

/// A D-vector that may change in time: either one `TimeFunction` per component, or a fixed unit
/// direction times one scalar function (`along`). A constant vector converts implicitly:
/// `VectorTimeFunction<3> g = Vec3(0, 0, -9.81);`.
///
/// `operator()(t)` gives, per component, its function's value while that function is active and
/// 0 while it is inactive (with `along`, the whole vector follows the magnitude function);
/// `active(t)` is true if any component is active.
template <int D>
class VectorTimeFunction {
  static_assert(D == 2 || D == 3, "VectorTimeFunction: D must be 2 or 3");

public:
  /// The zero vector, always active.
  VectorTimeFunction() = default;
  /// A constant vector.
  VectorTimeFunction(const Vec<D>& constant) {
    for (int i = 0; i < D; ++i)
      f_[i] = TimeFunction::constant(constant[i]);
  }
  /// One function per component.
  explicit VectorTimeFunction(std::array<TimeFunction, D> components) : f_(std::move(components)) {}
  VectorTimeFunction(TimeFunction x, TimeFunction y) requires(D == 2)
      : f_{std::move(x), std::move(y)} {}
  VectorTimeFunction(TimeFunction x, TimeFunction y, TimeFunction z) requires(D == 3)
      : f_{std::move(x), std::move(y), std::move(z)} {}

  /// direction / |direction| times `magnitude(t)` (a signed magnitude). The direction must be
  /// finite and non-zero.
  static VectorTimeFunction along(const Vec<D>& direction, TimeFunction magnitude) {
    const double n = direction.norm();
    detail::require(all_finite(direction) && n > 0.0, "VectorTimeFunction::along", "|direction|", n,
                    "(0, inf), finite components");
    VectorTimeFunction v;
    v.along_ = true;
    v.direction_ = direction / n;
    v.f_[0] = std::move(magnitude);
    return v;
  }

  /// fn(t), a user's function of the time [s] returning the whole vector: each component is a
  /// `TimeFunction::callable` that takes its part of fn(t); fn is called once per time at which
  /// the vector is evaluated (the last value is kept for the other components; thread-safe).
  static VectorTimeFunction callable(std::function<Vec<D>(double)> fn) {
    if (!fn)
      throw InputError("VectorTimeFunction::callable: function = empty is invalid; valid: a "
                       "callable returning the vector at a time [s]");
    struct Last {
      std::function<Vec<D>(double)> fn;
      std::mutex mutex;
      bool has = false;
      double t = 0.0;
      Vec<D> v = Vec<D>::Zero();
    };
    auto last = std::make_shared<Last>();
    last->fn = std::move(fn);
    std::array<TimeFunction, D> c;
    for (int k = 0; k < D; ++k)
      c[static_cast<std::size_t>(k)] = TimeFunction::callable([last, k](double t) {
        std::lock_guard<std::mutex> lock(last->mutex);
        if (!last->has || last->t != t) {
          last->has = false;
          last->v = last->fn(t);
          last->t = t;
          last->has = true;
        }
        return last->v[k];
      });
    return VectorTimeFunction(std::move(c));
  }

  /// A copy whose functions are all active only for t_begin <= t <= t_end [s].
  [[nodiscard]] VectorTimeFunction active(double t_begin, double t_end) const {
    VectorTimeFunction v = *this;
    for (auto& f : v.f_)
      f = f.active(t_begin, t_end);
    return v;
  }

  /// True if any component (with `along`: the magnitude) is active at t.
  bool active(double t) const noexcept {
    if (along_) return f_[0].active(t);
    for (const auto& f : f_)
      if (f.active(t)) return true;
    return false;
  }

  /// True if component i (with `along`: every component, by the magnitude) is active at t.
  bool component_active(int i, double t) const noexcept {
    return f_[along_ ? 0 : static_cast<std::size_t>(i)].active(t);
  }

  /// The vector at t, each component 0 while its function is inactive.
  Vec<D> operator()(double t) const {
    if (along_) return direction_ * f_[0](t);
    Vec<D> v;
    for (int i = 0; i < D; ++i)
      v[i] = f_[i](t);
    return v;
  }

  /// The vector at t, ignoring the activity intervals.
  Vec<D> value(double t) const {
    if (along_) return direction_ * f_[0].value(t);
    Vec<D> v;
    for (int i = 0; i < D; ++i)
      v[i] = f_[i].value(t);
    return v;
  }

  /// True if made by `along`; then `component(0)` is the magnitude and `direction()` the unit
  /// direction.
  bool is_along() const noexcept { return along_; }
  const Vec<D>& direction() const noexcept { return direction_; }
  /// The function of component i (with `along`: i = 0 is the magnitude).
  const TimeFunction& component(int i) const { return f_[static_cast<std::size_t>(i)]; }

private:
  std::array<TimeFunction, D> f_{};
  Vec<D> direction_ = Vec<D>::Zero();
  bool along_ = false;
};

/// An angular quantity that may change in time: a `TimeFunction` (the z component) in 2D, a
/// `VectorTimeFunction<3>` in 3D (the counterpart of `Angular<D>`).
template <int D>
using AngularTimeFunction = std::conditional_t<D == 2, TimeFunction, VectorTimeFunction<3>>;

namespace detail {
/// Requires a function that must not be negative (a damping, a temperature): its value at time t
/// finite and >= 0, and so every value of a table (the values a run will meet; a ramp or an
/// oscillation is checked where it is evaluated). `range` is the valid range with its unit.
inline void require_non_negative(const std::string& object, const char* name, const TimeFunction& f,
                                 double t, const std::string& range = "[0, inf)") {
  const double v = f.value(t);
  require(std::isfinite(v) && v >= 0.0, object, name, v, range);
  if (f.kind() == TimeFunction::Kind::table)
    for (double y : f.table_ptr()->y())
      require(std::isfinite(y) && y >= 0.0, object, name, y, range + " (table value)");
}
} // namespace detail

} // namespace grain
