// Fuzz target of grain::Table::from_file: any file either gives a valid table (at least two
// points, finite values, strictly increasing abscissae) or throws grain::InputError.

#include "fuzz_support.hpp"

#include <grain/core/table.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = grain_fuzz::write_input("table.txt", data, size);
  try {
    const grain::Table t = grain::Table::from_file(path);
    if (t.size() < 2 || t.x().size() != t.y().size()) grain_fuzz::fail("table of < 2 points");
    for (std::size_t i = 0; i < t.size(); ++i) {
      if (!std::isfinite(t.x()[i]) || !std::isfinite(t.y()[i]))
        grain_fuzz::fail("table with a non-finite point");
      if (i > 0 && !(t.x()[i] > t.x()[i - 1])) grain_fuzz::fail("abscissae not increasing");
    }
    // evaluation between, at and beyond the points never gives NaN
    std::size_t hint = 0;
    for (const double x : {t.x_front() - 1.0, t.x_front(), 0.5 * (t.x_front() + t.x_back()),
                           t.x_back(), t.x_back() + 1.0, -HUGE_VAL, HUGE_VAL}) {
      if (std::isnan(t(x)) || std::isnan(t(x, hint))) grain_fuzz::fail("table value NaN");
    }
  } catch (const grain::InputError&) {
  }
  return 0;
}
