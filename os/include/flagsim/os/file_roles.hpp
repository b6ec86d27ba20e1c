#pragma once
// The files one command reads and writes, checked before any work: no output
// may be the same file as an input, or as another output, however the path is
// spelt (contract: "No output of a command ... may be the same file as any of
// its inputs"). Nothing a user gave is ever overwritten.
#include <string>
#include <system_error>
#include <vector>

#include "flagsim/core/message.hpp"

namespace flagsim {

class FileRoles {
 public:
  /// @param what  how the user named it, for the message ("the scene", "--render")
  void input(std::string path, std::string what);
  void output(std::string path, std::string what);
  /// A directory output: every file `names` the command will write in `dir`
  /// (PNG or OBJ frames and their .partial names) is an output, however the
  /// names fall among the inputs.
  void outputs_in(const std::string& dir, const std::vector<std::string>& names,
                  const std::string& what);

  /// Throws UserError naming the path, before any work, when
  ///  - an output is the same file as an input or as another output: compared
  ///    by device and inode where the file exists, else by the absolute path
  ///    with every existing directory (and symlink) on it resolved;
  ///  - an input or output exists but is not a regular file (a FIFO would block,
  ///    a directory or device cannot be replaced);
  ///  - a path is longer than the system takes (PATH_MAX, or one name over NAME_MAX);
  ///  - an output's existing directory cannot be written.
  void check() const;

 private:
  struct Role {
    std::string path, what;
  };
  std::vector<Role> inputs_, outputs_;
};

/// Throws UserError when `path` exists and is not a regular file, or is
/// longer than the system takes; `what` is how the user gave it.
void check_regular_file(const std::string& path, const std::string& what);

/// The directories a command creates to hold its outputs. Each one that is
/// still empty when this goes away is removed again, deepest first: a command
/// that fails before it writes leaves nothing behind (not even newdir/sub of
/// `-o newdir/sub/run.h5`), one that wrote a file keeps the directories it is in.
class CreatedDirectories {
 public:
  CreatedDirectories() = default;
  CreatedDirectories(CreatedDirectories&& other) noexcept;
  CreatedDirectories& operator=(CreatedDirectories&& other) noexcept;
  CreatedDirectories(const CreatedDirectories&) = delete;
  CreatedDirectories& operator=(const CreatedDirectories&) = delete;
  ~CreatedDirectories();

  /// Creates `dir` and whichever of its parents are missing; false (with
  /// `error` set) when that fails. An existing `dir` is not ours to remove.
  bool create(const std::string& dir, std::error_code& error);

 private:
  void remove_empty() noexcept;
  std::vector<std::string> created_;  ///< outermost first
};

/// Whether `a` and `b` name the same file (as FileRoles::check compares them).
bool same_file(const std::string& a, const std::string& b);

/// Throws UserError unless `name` can be a single file name inside a
/// directory (the default output file out/<name>.h5): not empty, no '/', no
/// NUL or other control character, not "." or "..", at most 200 bytes.
void check_file_name_part(const std::string& name, const std::string& what);

}  // namespace flagsim
