#pragma once
// A file written whole or not at all: the bytes go to PATH.partial, every
// write is checked, and only a file that was written, flushed and closed
// without an error is renamed onto PATH. A full disk, a file-size limit or a
// signal leaves nothing under the final name (contract: "Nothing is lost").
#include <string>
#include <string_view>

namespace flagsim {

class StagedFile {
 public:
  /// Creates PATH.partial (replacing a stale one). Throws IoError when it
  /// cannot, or when what is there is not a regular file (a FIFO is not opened
  /// for writing: that would block until someone reads it).
  explicit StagedFile(std::string path);
  ~StagedFile();  ///< removes PATH.partial unless commit() succeeded
  StagedFile(const StagedFile&) = delete;
  StagedFile& operator=(const StagedFile&) = delete;

  /// Appends `bytes`. Throws IoError (exit 4) with the system's reason.
  void write(std::string_view bytes);
  /// Writes what is buffered and closes the file (checked), not yet renamed:
  /// for files that must all be whole before any of them is renamed.
  void close();
  /// Writes what is buffered, closes the file and renames it onto PATH.
  /// Throws IoError, leaving nothing under either name, when any step fails.
  void commit();

  const std::string& path() const { return path_; }
  static std::string partial_of(const std::string& path) { return path + ".partial"; }

 private:
  void flush();
  void fail(const std::string& doing, int error);

  std::string path_, partial_, buffer_;
  int fd_ = -1;
  bool committed_ = false;
};

/// `text` to `path` through a StagedFile.
void write_file_whole(const std::string& path, std::string_view text);

/// The whole of the regular file `path`, at most `max_bytes` of it. Throws
/// UserError when it is missing, not a regular file (a FIFO would block,
/// /dev/zero never end) or larger than that; the message starts
/// "`what` `path`: " (nothing when `what` is empty: the caller says where).
std::string read_file_capped(const std::string& path, std::size_t max_bytes,
                             const std::string& what);

}  // namespace flagsim
