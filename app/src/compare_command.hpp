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
  /// --seeds N: the flap and mean shape over N seeds (scene.seed, +1, ...), with
  /// their seed-to-seed spread, and whether the reference is converged (against
  /// the same reference on the lattice of every other node, same seeds).
  std::optional<long long> seeds;
  bool quiet = false;  ///< --quiet: no progress lines
};
int compare_command(const CompareOptions& options);

}  // namespace flagsim::app
