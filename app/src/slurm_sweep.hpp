#pragma once
// `flag-sim sweep ... --slurm DIR [--submit]`: the sweep as three Slurm batch
// jobs in DIR, each a `flag-sim sweep` command line:
//   reference.sbatch  point 0, the mass-spring reference, saved as
//                     DIR/reference.rec for every other point to read;
//   sweep.sbatch      an array job, one task per point not yet done
//                     (`--point $SLURM_ARRAY_TASK_ID`), after the reference;
//   merge.sbatch      `sweep --merge` of DIR/point_*.csv into the sweep's CSV
//                     (and its plot), after the array.
// Resumable: a point whose DIR/point_I.csv already holds its row is left out
// of the array (and a task finds its own row and stops, --resume), the
// reference job is left out once DIR/reference.rec is there.
#include <string>
#include <vector>

namespace flagsim::app {

struct SlurmSweep {
  std::string dir;                       ///< --slurm DIR
  bool submit = false;                   ///< --submit: sbatch the jobs, print their ids
  std::vector<std::string> sbatch_args;  ///< --slurm-arg: extra #SBATCH options
  int seeds = 1;                         ///< --seeds: rows a point's CSV holds when done
};

/// Writes the three scripts for a sweep of `points` points (0 is the
/// reference) whose points run as `point_command` (flag-sim's absolute path,
/// "sweep", and the sweep's own arguments, without -o or --point), merging
/// into `csv` (and `plot`, may be empty). With `slurm.submit`, submits them.
/// Returns what to print. Throws UserError (bad DIR or --slurm-arg) before
/// anything is written, IoError when sbatch fails.
std::string write_slurm_sweep(const SlurmSweep& slurm,
                              const std::vector<std::string>& point_command, int points,
                              const std::string& csv, const std::string& plot);

/// Whether `csv` holds point `point`'s `seeds` rows, whole (what sweep --point wrote).
bool sweep_point_done(const std::string& csv, int point, int seeds = 1);

/// The command line as /bin/sh reads it: each argument in single quotes.
std::string shell_quoted(const std::vector<std::string>& argv);

}  // namespace flagsim::app
