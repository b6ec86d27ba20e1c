#pragma once
// A fresh directory under /tmp, removed with everything in it at scope exit.
#include <string>

namespace flagsim::test {

class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::string& path() const { return path_; }
  /// path()/name
  std::string file(const std::string& name) const { return path_ + "/" + name; }
  /// Writes `text` to path()/name and returns the full path.
  std::string write(const std::string& name, const std::string& text) const;
  /// Number of entries in the directory (to check nothing was left behind).
  int entry_count() const;

 private:
  std::string path_;
};

/// The bytes of the file at `path`; empty when it cannot be read.
std::string file_bytes(const std::string& path);

}  // namespace flagsim::test
