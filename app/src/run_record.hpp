#pragma once
// A run kept in memory for `compare` and `sweep`: every frame's positions and
// its stage times, no file written.
#include <string>
#include <utility>
#include <vector>

#include "flagsim/analysis/metrics.hpp"
#include "flagsim/core/lattice.hpp"
#include "flagsim/core/scene.hpp"

namespace flagsim::app {

struct RunRecord {
  Lattice lattice;
  double fps = 30.0;
  analysis::Frames frames;  ///< dense positions [T][J*K], m
  analysis::Frames coarse;  ///< hybrid: the coarse nodes the infill used [T][Jc*Kc]
  std::vector<int> coarse_rows, coarse_cols;  ///< their dense rows and columns
  int substeps_per_frame = 0;
  double ms_per_frame = 0.0;        ///< every stage, mean over frames 1..T-1
  double physics_ms = 0.0;          ///< the physics' stages (force terms, integrate, bullet_step)
  double infill_ms = 0.0;           ///< coarse_slack and infill_3.x
  std::string status = "complete";  ///< or "diverged" (frames up to the last good one)
  std::string status_reason;
};

class Progress;

/// Runs `scene` as `flag-sim run` would, into memory; `progress` (may be null)
/// is updated after every frame.
RunRecord record_run(const Scene& scene, Progress* progress = nullptr);

/// The full-lattice spring-damper cloth of `scene` with the nodes on the
/// hybrid's coarse lattice driven along its coarse trajectory (linear in time
/// between frames): what the infill would have to reproduce, without chaos.
RunRecord record_tracking(const Scene& scene, const RunRecord& hybrid,
                          Progress* progress = nullptr);

}  // namespace flagsim::app
