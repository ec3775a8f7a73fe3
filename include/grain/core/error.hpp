#pragma once
/// \file error.hpp
/// Errors raised for bad input. Every message names the object, the value and the valid range:
///
///   <object>: <name> = <value> is invalid; valid range: <range>
///
/// The checks `grain::require`, `require_positive`, `require_non_negative`, `require_finite` and
/// `require_in` throw `InputError` with that message; a model's `validate` uses them for its
/// parameters (see docs/adding_a_model.md).

#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>

namespace grain {

/// Raised for invalid user input (before the run starts wherever possible).
class InputError : public std::invalid_argument {
public:
  using std::invalid_argument::invalid_argument;
};

/// Raised when a run becomes numerically invalid: a particle quantity that is no longer finite,
/// a particle moving more than its radius per step, or one inside another (usually a time step
/// above the stable limit, or a non-finite load or property; see simulation/state_check.hpp).
class NumericalError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// The function that receives grain's warnings (a set-up that is valid but probably not meant,
/// such as a particle material that conducts no heat in a thermal run). By default each warning
/// is written to standard error as one line "grain: warning: <message>"; a program may set its
/// own (to log, collect or raise them), or an empty function to silence them.
inline std::function<void(const std::string&)>& warning_handler() {
  static std::function<void(const std::string&)> handler = [](const std::string& message) {
    std::fprintf(stderr, "grain: warning: %s\n", message.c_str());
  };
  return handler;
}

namespace detail {
/// Passes `message` to the warning handler, if there is one.
inline void warn(const std::string& message) {
  if (const auto& h = warning_handler()) h(message);
}
} // namespace detail

namespace detail {

template <class T>
std::string to_text(const T& v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

/// The components of a vector, comma-separated: "x, y, z".
template <class Vec>
std::string vector_text(const Vec& v) {
  std::string out;
  for (long k = 0; k < static_cast<long>(v.size()); ++k)
    out += (k ? ", " : "") + to_text(v[k]);
  return out;
}

} // namespace detail

/// Throws `InputError("<object>: <name> = <value> is invalid; valid range: <range>")` unless
/// `ok`. `value` is written with 10 significant digits (any type that `operator<<` writes).
template <class T>
void require(bool ok, std::string_view object, std::string_view name, const T& value,
             std::string_view range) {
  if (!ok)
    throw InputError(std::string(object) + ": " + std::string(name) + " = " +
                     detail::to_text(value) + " is invalid; valid range: " + std::string(range));
}

/// Requires a finite value strictly above zero (valid range "(0, inf)").
inline void require_positive(std::string_view object, std::string_view name, double value) {
  require(std::isfinite(value) && value > 0.0, object, name, value, "(0, inf)");
}
/// Requires a finite value at or above zero (valid range "[0, inf)").
inline void require_non_negative(std::string_view object, std::string_view name, double value) {
  require(std::isfinite(value) && value >= 0.0, object, name, value, "[0, inf)");
}
/// Requires a finite value (valid range "a finite number").
inline void require_finite(std::string_view object, std::string_view name, double value) {
  require(std::isfinite(value), object, name, value, "a finite number");
}
/// Requires lo <= value <= hi; `range` is the text of the message (e.g. "[0, 1]").
inline void require_in(std::string_view object, std::string_view name, double value, double lo,
                       double hi, std::string_view range) {
  require(std::isfinite(value) && value >= lo && value <= hi, object, name, value, range);
}
/// Requires lo <= value <= hi; the message gives the range as "[lo, hi]".
inline void require_in(std::string_view object, std::string_view name, double value, double lo,
                       double hi) {
  if (!(std::isfinite(value) && value >= lo && value <= hi))
    require_in(object, name, value, lo, hi,
               "[" + detail::to_text(lo) + ", " + detail::to_text(hi) + "]");
}

namespace detail {

// The library's own checks: the public ones above, with the object as a std::string.

/// Throws `InputError("<object>: <name> = <value> is invalid; valid range: <range>")` unless `ok`.
template <class T>
void require(bool ok, const std::string& object, const char* name, const T& value,
             const char* range) {
  grain::require(ok, object, name, value, range);
}
template <class T>
void require(bool ok, const std::string& object, const char* name, const T& value,
             const std::string& range) {
  grain::require(ok, object, name, value, range);
}

/// Requires a finite value strictly above zero.
inline void require_positive(const std::string& object, const char* name, double v) {
  grain::require_positive(object, name, v);
}
/// Requires a finite value at or above zero.
inline void require_non_negative(const std::string& object, const char* name, double v) {
  grain::require_non_negative(object, name, v);
}
/// Requires a finite value.
inline void require_finite(const std::string& object, const char* name, double v) {
  grain::require_finite(object, name, v);
}
/// Requires lo <= v <= hi.
inline void require_in(const std::string& object, const char* name, double v, double lo, double hi,
                       const char* range) {
  grain::require_in(object, name, v, lo, hi, range);
}

} // namespace detail
} // namespace grain
