#pragma once
/// \file write_error.hpp
/// The error raised by the output helpers when a file could not be written (a full disk, a file
/// size limit, a stream closed under them): a std::runtime_error that names the helper, the file
/// and the reason, e.g. "grain::io::csv: cannot write 'out/h.csv': No space left on device".

#include <cerrno>
#include <cstring>
#include <ostream>
#include <stdexcept>
#include <string>

namespace grain::io::detail {

/// std::runtime_error("<who>: cannot write '<path>': <reason><note>"), the reason that of the
/// error number `err` (errno after the failed call; 0 if the call did not set it).
inline std::runtime_error write_error(const std::string& who, const std::string& path, int err,
                                      const std::string& note = "") {
  const std::string reason =
      err != 0 ? std::string(std::strerror(err)) : std::string("the stream reported a failure");
  return std::runtime_error(who + ": cannot write '" + path + "': " + reason + note);
}

/// Flushes `o` and throws write_error unless everything written to it so far reached the file.
inline void flush_or_throw(std::ostream& o, const std::string& who, const std::string& path) {
  errno = 0;
  o.flush();
  if (!o) throw write_error(who, path, errno);
}

} // namespace grain::io::detail
