#pragma once
// Tables used by several tests.
#include <grain/core/table.hpp>

namespace grain::test {

/// The linear spring characteristic F = k x on [-range, range] (two points).
inline Table linear_table(double k, double range = 10.0) {
  return Table({-range, range}, {-k * range, k * range});
}

} // namespace grain::test
