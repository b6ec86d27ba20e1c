#pragma once
// `flag-sim compare`: the hybrid against the full-lattice references.
// Returns the process exit code (contract: "Exit codes"); user mistakes are
// thrown as UserError and reported by main.
#include <optional>
#include <string>
#include <vector>

namespace flagsim::app {

struct CompareOptions {
  std::string scene_path;
  std::string reference = "mass-spring";
  std::string output;  ///< -o REPORT.csv; empty: the table only
  std::vector<std::string> sets;
  std::optional<long long> frames;
  double horizon_s = 0.5;
};
int compare_command(const CompareOptions& options);

}  // namespace flagsim::app
