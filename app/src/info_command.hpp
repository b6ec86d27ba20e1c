#pragma once
// `flag-sim info`: what an output file holds.
// Returns the process exit code (contract: "Exit codes"); user mistakes are
// thrown as UserError and reported by main.
#include <string>

namespace flagsim::app {

/// `info`: the run in `path`, as text or (json) as one JSON object.
int info_command(const std::string& path, bool json);

}  // namespace flagsim::app
