// Fuzz target of the run-file reader of grain-demlab's programs
// (grain::demlab::detail::read_run_file, include/grain/demlab/driver.hpp): any file either reads
// (with a name, an analysis, a final time > 0 and an output count >= 1, finite particle and wall
// numbers) or throws grain::InputError naming the file's line.

#include "fuzz_support.hpp"

#include <grain/demlab/driver.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = grain_fuzz::write_input("project.run", data, size);
  try {
    const auto rf = grain::demlab::detail::read_run_file(path);
    if (rf.name.empty()) grain_fuzz::fail("a run file without a name");
    if (!(rf.final_time > 0.0) || !std::isfinite(rf.final_time))
      grain_fuzz::fail("a final time that is not finite and > 0");
    if (rf.output_count < 1) grain_fuzz::fail("an output count below 1");
    for (const auto& p : rf.particles)
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !(p.radius > 0.0))
        grain_fuzz::fail("a particle with a non-finite position or a radius <= 0");
  } catch (const grain::InputError&) {
  }
  return 0;
}
