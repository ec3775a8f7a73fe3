// Fuzz target of grain::io::detail::resumable_bytes, which reads an existing CSV file to resume
// a history: any file gives a number of bytes to keep (at most the file's size, a whole number
// of lines) or throws grain::InputError.
//
// The first byte of the input chooses the step the writer resumes at (0 .. 63) and the header
// (two choices); the rest is the file.

#include "fuzz_support.hpp"

#include <grain/io/csv.hpp>

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const long step = data[0] & 63;
  const std::string header = (data[0] & 64) ? "\"time [s]\",step,particles\n" : "time [s],step\n";
  const std::string path = grain_fuzz::write_input("history.csv", data + 1, size - 1);
  const std::string file(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    const std::uintmax_t keep = grain::io::detail::resumable_bytes(path, header, step);
    if (keep > file.size()) grain_fuzz::fail("keeps more bytes than the file has");
    if (keep > 0) {
      if (file.compare(0, header.size(), header) != 0)
        grain_fuzz::fail("keeps a file with another header");
      if (file[keep - 1] != '\n') grain_fuzz::fail("keeps a part of a line");
    }
  } catch (const grain::InputError&) {
  }
  return 0;
}
