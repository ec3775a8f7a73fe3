#pragma once
/// \file example_support.hpp
/// What the example programs share: a portable random-number sequence, the command line
/// "[end_time_s] [output_dir]" and calls of the plotting script (scripts/grain_plot.py, installed
/// as grain-plot).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace example {

/// Deterministic pseudo-random numbers in [0, 1) (splitmix64): the same sequence on every
/// platform and compiler.
struct Random {
  std::uint64_t state;
  double uniform() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-53;
  }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
};

/// Reads the optional arguments [end_time_s > 0] [output_dir] into `end_time` and `out_dir`
/// (which hold the defaults). Prints the usage of program `name` and returns false on bad input.
inline bool parse_arguments(int argc, char** argv, const char* name, double& end_time,
                            std::filesystem::path& out_dir) {
  bool ok = argc <= 3;
  if (ok && argc > 1) {
    char* rest = nullptr;
    end_time = std::strtod(argv[1], &rest);
    ok = rest != argv[1] && *rest == '\0' && end_time > 0.0 && std::isfinite(end_time);
  }
  if (ok && argc > 2) out_dir = argv[2];
  if (!ok) std::fprintf(stderr, "usage: %s [end_time_s > 0] [output_dir]\n", name);
  return ok;
}

/// The file `name` in the first directory of the PATH environment variable that holds one; empty
/// if none does.
inline std::filesystem::path find_on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  const std::string dirs = path ? path : "";
  for (std::size_t begin = 0; begin < dirs.size();) {
    const std::size_t end = std::min(dirs.find(':', begin), dirs.size());
    const std::filesystem::path candidate =
        std::filesystem::path(dirs.substr(begin, end - begin)) / name;
    std::error_code error;
    if (end > begin && std::filesystem::is_regular_file(candidate, error)) return candidate;
    begin = end + 1;
  }
  return {};
}

/// Runs the plotting script with these arguments, quietly: scripts/grain_plot.py of grain's
/// source tree when the examples are built there (GRAIN_PLOT_SCRIPT, set by
/// examples/CMakeLists.txt), else the installed grain-plot found on PATH (a copy of an example
/// built elsewhere). False if it fails, if there is no script, or if Python with matplotlib is
/// missing.
inline bool plot(const std::string& args) {
#ifdef GRAIN_PLOT_SCRIPT
  const std::filesystem::path script = GRAIN_PLOT_SCRIPT;
#else
  const std::filesystem::path script = find_on_path("grain-plot");
  if (script.empty()) return false;
#endif
  const std::string python =
      std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  const std::string cmd = python + " '" + script.string() + "' " + args + " > /dev/null 2>&1";
  return std::system(cmd.c_str()) == 0;
}

/// The last (in name order) file of `dir` whose name starts with `prefix`; empty if none.
inline std::string last_file(const std::filesystem::path& dir, const std::string& prefix) {
  std::string last;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(prefix, 0) == 0 && name > last) last = name;
  }
  return last;
}

} // namespace example
