#pragma once
// The dense frames of an output file for the commands that read them (render,
// export): the file itself, or, for a file of [output] dense = false, its
// frames refined (`flag-sim refine`) into a temporary directory that goes
// with this object.
#include <string>

namespace flagsim::app {

class DenseInput {
 public:
  /// Refines `h5_path` when it keeps the coarse trajectory only, saying so in a
  /// `note:` line. Throws what refine throws (UserError, IoError), Interrupted.
  explicit DenseInput(const std::string& h5_path);
  ~DenseInput();
  DenseInput(const DenseInput&) = delete;
  DenseInput& operator=(const DenseInput&) = delete;
  /// The file to read the dense frames from.
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::string directory_;  ///< the temporary directory; empty when none
};

}  // namespace flagsim::app
