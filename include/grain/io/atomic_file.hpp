#pragma once
/// \file atomic_file.hpp
/// How the output helpers write their files so that a run killed at any moment, or stopped by a
/// full disk, leaves only readable files:
///
/// - `AtomicFile`: a whole file (a VTK frame, a series file, a checkpoint) is written under a
///   temporary name in the same folder, `<path>.tmp`, flushed, closed and checked, and only then
///   renamed over `<path>` (an atomic replacement on POSIX file systems). Until the rename the
///   previous file at `<path>` is untouched; a failed write removes the temporary file and throws
///   io::WriteError naming the writer, both files and the reason. A process killed while writing
///   leaves at most a stray `<path>.tmp`, which the next write of the same file replaces. A path
///   that is a symbolic link is followed (the file it points to is replaced, the link kept); a
///   path that is not a regular file (a device such as /dev/null) is written directly.
/// - `LineFile`: a text file that grows by whole lines (CSV histories, io::print to a file): each
///   call hands it one or more complete lines, written with one write and flushed. A write that
///   fails (a full disk) is cut back to the lines written before it and throws io::WriteError, so
///   the file never ends with a part of a line that the writer left.
///
/// Neither calls fsync: the files survive the process being killed, not the machine losing power
/// before the operating system has written its caches.

#include <grain/io/write_error.hpp>

#include <cerrno>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <ios>
#include <string>
#include <system_error>
#include <utility>

namespace grain::io::detail {

/// A whole file written under `<path>.tmp` and renamed to `<path>` by commit(); removed unless
/// committed.
class AtomicFile {
public:
  /// Opens the temporary file of `path` for writing (binary or text); `who` names the writer in
  /// messages. Throws WriteError if it cannot be made.
  AtomicFile(std::string who, std::string path, bool binary = false)
      : who_(std::move(who)), path_(std::move(path)) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::file_status target = fs::status(path_, ec);
    if (fs::exists(target) && !fs::is_regular_file(target)) {
      direct_ = true; // a device or a pipe: it cannot be replaced, only written
      tmp_ = path_;
    } else {
      fs::path final_path(path_);
      if (fs::is_symlink(fs::symlink_status(final_path, ec))) {
        const fs::path resolved = fs::weakly_canonical(final_path, ec);
        if (!ec) final_path = resolved;
      }
      final_ = final_path.string();
      tmp_ = final_ + ".tmp";
    }
    errno = 0;
    if (!buf_.open(tmp_, binary ? std::ios::out | std::ios::trunc | std::ios::binary
                                : std::ios::out | std::ios::trunc))
      fail(errno);
  }
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile() {
    if (!done_) discard();
  }

  /// The stream to write the file's contents to.
  std::ostream& stream() { return out_; }
  /// The file asked for.
  const std::string& path() const { return path_; }

  /// Flushes and closes the temporary file and renames it over the final one; throws WriteError
  /// (after removing the temporary file) if any byte did not reach it or the rename failed.
  void commit() {
    // a write that failed earlier left the stream bad and did nothing since: its error number
    int err = out_ ? 0 : errno;
    errno = 0;
    if (out_) out_.flush();
    if (!out_ && err == 0) err = errno;
    errno = 0;
    const bool closed = buf_.close() != nullptr;
    if (!closed && err == 0) err = errno;
    if (!out_ || !closed) fail(err);
    if (!direct_) {
      std::error_code ec;
      std::filesystem::rename(tmp_, final_, ec);
      if (ec) fail(ec.value());
    }
    done_ = true;
  }

  /// Removes the temporary file and throws WriteError for the error number `err`.
  [[noreturn]] void fail(int err) {
    discard();
    if (direct_) throw write_error(who_, path_, err);
    throw WriteError(who_ + ": cannot write '" + tmp_ + "', the temporary file of '" + path_ +
                         "': " + write_reason(err) + "; it is removed and '" + path_ +
                         "' is left as it was",
                     path_, err);
  }

private:
  void discard() {
    done_ = true;
    if (buf_.is_open()) buf_.close();
    if (direct_) return;
    std::error_code ignored;
    std::filesystem::remove(tmp_, ignored);
  }

  std::string who_, path_, final_{}, tmp_{};
  bool direct_ = false, done_ = false;
  std::filebuf buf_{};
  std::ostream out_{&buf_};
};

/// A text file written by whole lines (see the file comment).
class LineFile {
public:
  /// Opens `path` for writing: anew (truncated) if `keep` is 0, else for appending after its
  /// first `keep` bytes (the caller has cut the file to that length). Throws WriteError if it
  /// cannot be opened.
  LineFile(std::string who, std::string path, std::uintmax_t keep = 0)
      : who_(std::move(who)), path_(std::move(path)), size_(keep) {
    open(keep > 0 ? std::ios::app : std::ios::trunc);
  }
  LineFile(const LineFile&) = delete;
  LineFile& operator=(const LineFile&) = delete;

  const std::string& path() const { return path_; }

  /// Writes `lines` (complete lines, each ending with '\n') with one write and flushes them.
  /// On a failure the file is cut back to its length before the call and WriteError thrown; the
  /// file stays open for appending, so that a later call may try again.
  void write(const std::string& lines) {
    if (!out_.is_open()) open(std::ios::app);
    errno = 0;
    out_.write(lines.data(), static_cast<std::streamsize>(lines.size()));
    if (out_) out_.flush();
    if (out_) {
      size_ += lines.size();
      return;
    }
    const int err = errno;
    out_.close(); // nothing is left in the buffer to be written later
    std::error_code ec;
    if (std::filesystem::is_regular_file(path_, ec))
      std::filesystem::resize_file(path_, size_, ec); // drop the part of the lines that got in
    out_.clear();
    throw write_error(who_, path_, err,
                      size_ > 0 ? "; the file keeps the whole lines written before" : "");
  }

private:
  void open(std::ios::openmode mode) {
    out_.clear();
    // unbuffered: each write() is one write to the file, nothing waits in a buffer
    out_.rdbuf()->pubsetbuf(nullptr, 0);
    errno = 0;
    out_.open(path_, std::ios::out | std::ios::binary | mode);
    if (!out_) throw write_error(who_, path_, errno, " (it cannot be opened)");
  }

  std::string who_, path_;
  std::uintmax_t size_;
  std::ofstream out_{};
};

} // namespace grain::io::detail
