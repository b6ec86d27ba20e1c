#pragma once
// `flag-sim plot`: an output file's statistics as an image.
// Returns the process exit code (contract: "Exit codes"); user mistakes are
// thrown as UserError and reported by main.
#include <string>

namespace flagsim::app {

/// `plot`: strain, kinetic energy and wall time per frame of an output file, as an image.
int plot_command(const std::string& h5_path, const std::string& output);

}  // namespace flagsim::app
