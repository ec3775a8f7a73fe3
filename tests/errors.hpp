#pragma once
// Helpers for tests of input checks: the message of the InputError a call raises, and a substring
// test for it.
#include <grain/core/error.hpp>

#include <string>

namespace grain::test {

/// The message of the grain::InputError that f() throws ("" if it throws none).
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

/// True if `part` occurs in `s`.
inline bool has(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

} // namespace grain::test
