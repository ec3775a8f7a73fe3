#pragma once
/// \file fuzz_support.hpp
/// Helpers shared by the libFuzzer targets of fuzz/: a private scratch folder per process and
/// the writing of an input to a file in it (grain's readers take paths).

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace grain_fuzz {

/// A folder of its own for this process, made on first use under $TMPDIR (or the system's
/// temporary folder). libFuzzer ends a run without the handlers of atexit, so the folder stays:
/// scripts/fuzz.sh sets TMPDIR to a folder below its build folder.
inline const std::filesystem::path& scratch() {
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() /
             ("grain_fuzz_" + std::to_string(static_cast<long>(::getpid())));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

/// Writes `size` bytes at `data` to the file `name` of the scratch folder; returns its path.
inline std::string write_input(const std::string& name, const std::uint8_t* data,
                               std::size_t size) {
  const std::string path = (scratch() / name).string();
  std::ofstream o(path, std::ios::binary | std::ios::trunc);
  o.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  o.close();
  if (!o) {
    std::fprintf(stderr, "fuzz: cannot write %s\n", path.c_str());
    std::abort();
  }
  return path;
}

/// Stops the run with a message: a reader broke one of its own promises.
[[noreturn]] inline void fail(const char* what) {
  std::fprintf(stderr, "fuzz: %s\n", what);
  std::abort();
}

} // namespace grain_fuzz
