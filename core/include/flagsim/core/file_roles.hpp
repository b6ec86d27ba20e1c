#pragma once
// The files one command reads and writes, checked before any work: no output
// may be the same file as an input, or as another output, however the path is
// spelt (contract: "No output of a command ... may be the same file as any of
// its inputs"). Nothing a user gave is ever overwritten.
#include <string>
#include <vector>

#include "flagsim/core/message.hpp"

namespace flagsim {

class FileRoles {
 public:
  /// @param what  how the user named it, for the message ("the scene", "--render")
  void input(std::string path, std::string what);
  void output(std::string path, std::string what);

  /// Throws UserError naming both paths when an output is the same file as an
  /// input or as another output: compared by device and inode where the file
  /// exists, else by the absolute path with every existing directory (and
  /// symlink) on it resolved.
  void check() const;

 private:
  struct Role {
    std::string path, what;
  };
  std::vector<Role> inputs_, outputs_;
};

/// Whether `a` and `b` name the same file (as FileRoles::check compares them).
bool same_file(const std::string& a, const std::string& b);

/// Throws UserError unless `name` can be a single file name inside a
/// directory (the default output file out/<name>.h5): not empty, no '/', no
/// NUL or other control character, not "." or "..", at most 200 bytes.
void check_file_name_part(const std::string& name, const std::string& what);


}  // namespace flagsim
