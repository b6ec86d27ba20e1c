#pragma once
// `flag-sim export`: the dense lattice as PC2 / OBJ for Blender and others.
// Returns the process exit code (contract: "Exit codes"); user mistakes are
// thrown as UserError and reported by main.
#include <optional>
#include <string>

namespace flagsim::app {

struct ExportOptions {
  std::string output;                 ///< -o NAME.pc2 | NAME.obj | DIR/
  std::optional<std::string> frames;  ///< --frames A:B
};
/// `export`: the dense lattice of an output file as a PC2 point cache and its
/// OBJ (NAME.pc2), one OBJ (NAME.obj) or an OBJ per frame (DIR/).
int export_command(const std::string& h5_path, const ExportOptions& options);

}  // namespace flagsim::app
