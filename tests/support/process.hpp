#pragma once
// Runs build/flag-sim (or any program) as a user would, capturing its output.
#include <string>
#include <vector>

namespace flagsim::test {

struct ProcessResult {
  int exit_code = -1;  ///< the exit status, or 128 + signal number
  std::string out;     ///< stdout
  std::string err;     ///< stderr
};

/// Runs `program` with `args` in directory `cwd` (empty: current), waits for it.
ProcessResult run_process(const std::string& program, const std::vector<std::string>& args,
                          const std::string& cwd = "");

/// Runs build/flag-sim with `args` in `cwd`.
inline ProcessResult run_flag_sim(const std::vector<std::string>& args,
                                  const std::string& cwd = "") {
  return run_process(FLAGSIM_BINARY, args, cwd);
}

}  // namespace flagsim::test
