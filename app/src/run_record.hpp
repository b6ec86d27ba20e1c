#pragma once
// A run kept in memory for `compare` and `sweep`: every frame's positions and
// its stage times, no file written.
#include <string>
#include <utility>
#include <vector>

#include "flagsim/analysis/metrics.hpp"
#include "flagsim/core/lattice.hpp"
#include "flagsim/core/run_status.hpp"
#include "flagsim/scene/scene.hpp"

namespace flagsim::app {

struct RunRecord {
  Lattice lattice;
  double fps = 30.0;
  analysis::Frames frames;  ///< dense positions [T][J*K], m
  analysis::Frames coarse;  ///< hybrid: the coarse nodes the infill used [T][Jc*Kc]
  std::vector<int> coarse_rows, coarse_cols;  ///< their dense rows and columns
  int substeps_per_frame = 0;
  double ms_per_frame = 0.0;  ///< every stage, mean over frames 1..T-1
  double physics_ms = 0.0;    ///< the physics' stages (force terms, integrate, bullet_step)
  double infill_ms = 0.0;     ///< coarse_slack and infill_3.x
  /// complete, or diverged (frames up to the last good one) with its reason
  RunStatus status;
  std::string scene_toml;  ///< the scene as run (Scene::toml_text): what a saved record is of
};

class Progress;

/// Runs `scene` as `flag-sim run` would, into memory; `progress` (may be null)
/// is updated after every frame.
RunRecord record_run(const Scene& scene, Progress* progress = nullptr);

/// A record saved for other processes (sweep's shared reference): every field,
/// float64 positions, so a point that reads it measures exactly what one that
/// ran it would. Written under PATH.partial and renamed: a reader never sees
/// half a file, and two writers of the same record leave one whole one.
/// Throws IoError when it cannot be written.
void save_record(const RunRecord& record, const std::string& path);
/// Reads a record save_record wrote; throws UserError naming `path` when it is
/// not one (or not whole).
RunRecord load_record(const std::string& path);

/// The full-lattice spring-damper cloth of `scene` with the nodes on the
/// hybrid's coarse lattice driven along its coarse trajectory (linear in time
/// between frames): what the infill would have to reproduce, without chaos.
RunRecord record_tracking(const Scene& scene, const RunRecord& hybrid,
                          Progress* progress = nullptr);

}  // namespace flagsim::app
