#pragma once
/// \file write_error.hpp
/// The error raised by the output helpers when a file could not be written (a full disk, a file
/// size limit, a stream closed under them): io::WriteError, a std::runtime_error that names the
/// helper, the file and the reason, e.g. "grain::io::csv: cannot write 'out/h.csv': No space left
/// on device"; and the check of an output folder before a run (`require_output_folder`), an
/// InputError.

#include <grain/core/error.hpp>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>

namespace grain::io {

/// A file that could not be written: "<writer>: cannot write '<path>': <reason>...". `path()` is
/// the file the writer was asked for, `error_number()` the errno of the failure (EFBIG for a file
/// size limit, ENOSPC for a full disk; 0 if the failed call did not set it).
class WriteError : public std::runtime_error {
public:
  WriteError(const std::string& message, std::string path, int error_number)
      : std::runtime_error(message), path_(std::move(path)), error_number_(error_number) {}
  const std::string& path() const { return path_; }
  int error_number() const { return error_number_; }

private:
  std::string path_;
  int error_number_;
};

} // namespace grain::io

namespace grain::io::detail {

/// The reason of the error number `err` (errno after the failed call; 0 if it did not set it).
inline std::string write_reason(int err) {
  return err != 0 ? std::string(std::strerror(err)) : std::string("the stream reported a failure");
}

/// WriteError("<who>: cannot write '<path>': <reason><note>").
inline WriteError write_error(const std::string& who, const std::string& path, int err,
                              const std::string& note = "") {
  return WriteError(who + ": cannot write '" + path + "': " + write_reason(err) + note, path, err);
}

/// Flushes `o` and throws write_error unless everything written to it so far reached the file.
inline void flush_or_throw(std::ostream& o, const std::string& who, const std::string& path) {
  errno = 0;
  o.flush();
  if (!o) throw write_error(who, path, errno);
}

/// Makes the folder of `path` (a file, or the prefix of a series of files; its parents too) and
/// checks that a file can be written there: `path` itself if it exists (opened for appending,
/// unchanged), else an empty file made in the folder and removed. Throws
/// InputError naming the writer `who`, the path and the reason otherwise (a file in the way of
/// the folder, no permission, a read-only file system), so that a run stops before its first
/// step rather than at its first output.
inline void require_output_folder(const std::string& who, const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path p(path);
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  auto refuse = [&](const std::string& reason) {
    throw InputError(who + ": path = '" + path + "' is invalid: the folder '" + dir.string() +
                     "' " + reason + "; valid: a path in a folder that can be made and written");
  };
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) refuse("cannot be made (" + ec.message() + ")");
  if (!fs::is_directory(dir, ec)) refuse("is not a folder");
  // a file that exists already (one to resume, a device) is opened for appending, unchanged;
  // otherwise an empty file is made in the folder and removed
  const bool exists = fs::exists(p, ec) && !fs::is_directory(p, ec);
  const fs::path probe = exists ? p : dir / ".grain_write_test";
  errno = 0;
  {
    std::ofstream o(probe, std::ios::app);
    if (!o) {
      const int err = errno;
      refuse("cannot be written (" +
             (err != 0 ? std::string(std::strerror(err)) : std::string("cannot create a file")) +
             ")");
    }
  }
  if (!exists) fs::remove(probe, ec);
}

} // namespace grain::io::detail
