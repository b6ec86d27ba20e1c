#pragma once
// `flag-sim sweep`: a grid of hybrid runs against one reference.
// Returns the process exit code (contract: "Exit codes"); user mistakes are
// thrown as UserError and reported by main.
#include <optional>
#include <string>
#include <vector>

namespace flagsim::app {

struct SweepOptions {
  std::string scene_path;
  std::string coarse, substeps, relax, infill, backend;  ///< comma-separated lists
  /// Comma-separated solid pole radii, m ([pole] radius); 0: the scene's own
  /// pole (contact on and off side by side: --pole-radius 0,0.04).
  std::string pole_radius;
  /// Comma-separated self-contact thicknesses, m ([contact] thickness); 0:
  /// the scene's own (self-contact on and off: --contact-thickness 0,0.005).
  std::string contact_thickness;
  /// Full-lattice modes run as reference rows, mass-spring among them (the
  /// errors are against it).
  std::string references = "mass-spring";
  std::string output, plot;
  std::vector<std::string> sets;
  std::optional<long long> frames;
  std::optional<int> point;
  int jobs = 1;
  double horizon_s = 0.5;
  std::vector<std::string> merge;  ///< CSVs to join instead of running
  /// The reference run, shared: read from this file when it is there, else
  /// run and saved there (sweep --jobs uses one in its points' directory).
  std::string reference_file;
  bool list = false;      ///< print the points and exit
  bool resume = false;    ///< with --point: nothing to do when -o already holds its row
  std::string slurm_dir;  ///< --slurm DIR: write Slurm batch jobs instead of running
  bool submit = false;    ///< --submit: and sbatch them
  std::vector<std::string> slurm_args;  ///< --slurm-arg: extra #SBATCH options
  bool quiet = false;
  /// --seeds N: every point (the references too) at seeds scene.seed .. +N-1,
  /// each measured against the reference of its own seed; a row per point and seed.
  int seeds = 1;
};
/// argv: the command line that started this sweep (children re-run it with --point).
int sweep_command(const SweepOptions& options, const std::vector<std::string>& argv);

}  // namespace flagsim::app
