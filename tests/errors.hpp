#pragma once
// Helpers for tests of input checks: the message of the InputError (or other exception) a call
// raises, and substring tests for it.
#include <grain/core/error.hpp>

#include <initializer_list>
#include <string>

namespace grain::test {

/// The message of the exception of type E (grain::InputError unless given) that f() throws (""
/// if it throws none; other exceptions pass).
template <class E = InputError, class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "";
}

/// True if `part` occurs in `s`.
inline bool has(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

/// True if `s` is not empty and each of `parts` occurs in it.
inline bool has(const std::string& s, std::initializer_list<const char*> parts) {
  for (const char* p : parts)
    if (s.find(p) == std::string::npos) return false;
  return !s.empty();
}

} // namespace grain::test
