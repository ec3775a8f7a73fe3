#pragma once
/// \file error.hpp
/// Errors raised for bad input. Every message names the object, the value and the valid range.

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

namespace grain {

/// Raised for invalid user input (before the run starts wherever possible).
class InputError : public std::invalid_argument {
public:
  using std::invalid_argument::invalid_argument;
};

/// Raised when a run becomes numerically invalid: a particle position or temperature that is no
/// longer finite (usually a time step above the stable limit, or a non-finite load or property).
class NumericalError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

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

/// Throws `InputError("<object>: <name> = <value> is invalid; valid range: <range>")` unless `ok`.
template <class T>
void require(bool ok, const std::string& object, const char* name, const T& value,
             const char* range) {
  if (!ok)
    throw InputError(object + ": " + name + " = " + to_text(value) +
                     " is invalid; valid range: " + range);
}
template <class T>
void require(bool ok, const std::string& object, const char* name, const T& value,
             const std::string& range) {
  require(ok, object, name, value, range.c_str());
}

/// Requires a finite value strictly above zero.
inline void require_positive(const std::string& object, const char* name, double v) {
  require(std::isfinite(v) && v > 0.0, object, name, v, "(0, inf)");
}
/// Requires a finite value at or above zero.
inline void require_non_negative(const std::string& object, const char* name, double v) {
  require(std::isfinite(v) && v >= 0.0, object, name, v, "[0, inf)");
}
/// Requires a finite value.
inline void require_finite(const std::string& object, const char* name, double v) {
  require(std::isfinite(v), object, name, v, "a finite number");
}
/// Requires lo <= v <= hi.
inline void require_in(const std::string& object, const char* name, double v, double lo, double hi,
                       const char* range) {
  require(std::isfinite(v) && v >= lo && v <= hi, object, name, v, range);
}

} // namespace detail
} // namespace grain
