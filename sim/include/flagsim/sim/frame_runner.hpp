#pragma once
// The frame loop, written once: every driver of a Simulation (`flag-sim run`,
// the runs compare and sweep record, Python's step) advances and checks its
// frames here, and hands each good frame to its sinks (the HDF5 writer, a run
// record, the progress line). How a run of frames ended comes back as data
// (FrameRunEnd, Divergence); the command line and Python turn it into words.
#include <optional>
#include <span>

#include "flagsim/core/stage_times.hpp"
#include "flagsim/core/strain.hpp"
#include "flagsim/scene/scene.hpp"
#include "flagsim/sim/divergence.hpp"
#include "flagsim/sim/simulation.hpp"

namespace flagsim::sim {

/// A frame the runner advanced to and found good, as its sinks see it.
struct CheckedFrame {
  int index = 0;        ///< frames since t = 0 (0: the initial state)
  double time_s = 0.0;  ///< index / fps exactly, not the sum of the substeps
  StrainStats strain;   ///< of the dense lattice's row and column links
  /// Per-node strain [J*K] (the largest |strain| of the node's links), when
  /// FrameRunOptions::node_strain asked for it; empty otherwise.
  std::span<const float> node_strain;
  double wall_s = 0.0;  ///< the frame's wall time until the sinks (advance and checks), s
};

/// Takes the good frames of a run, in order.
class FrameSink {
 public:
  virtual ~FrameSink() = default;
  /// Frame `frame` of `simulation` is good. Returns false to end the run
  /// before this frame is complete (the sink keeps why; later sinks do not
  /// see the frame).
  virtual bool take(const Simulation& simulation, const CheckedFrame& frame) = 0;
};

/// How a run of frames ended.
enum class FrameRunEnd {
  kComplete,           ///< every frame asked for was taken
  kDiverged,           ///< a frame could not be trusted (FrameRunResult::divergence); not taken
  kInterruptedDuring,  ///< a stop request cut a frame short; the simulation is not at a frame
  kInterruptedAfter,   ///< a stop request arrived after a whole frame, with frames still to go
  kStoppedBySink,      ///< a sink's take() returned false
};

struct FrameRunResult {
  FrameRunEnd end = FrameRunEnd::kComplete;
  /// The frame the run ended in: the last one taken (kComplete,
  /// kInterruptedAfter), or the one diverged, cut short or refused.
  int frame = -1;
  /// kDiverged: why, as data (frame_divergence); describe() gives the words.
  std::optional<Divergence> divergence;
};

struct FrameRunOptions {
  /// The simulation's stages (Simulation::register_stages); the runner adds
  /// nothing to it but the checks' time at `checks_stage` (when >= 0). It does
  /// not reset it: a sink that writes the times does.
  StageTimes* times = nullptr;
  int checks_stage = -1;
  bool node_strain = false;  ///< fill CheckedFrame::node_strain
};

/// Frames [first, end) of `simulation` (which is at frame first - 1, or at
/// frame 0 when first is 0): each frame after 0 is advanced to, a stop request
/// (stop_request.hpp) is looked for, the dense links' strain is measured and
/// frame_divergence asked; a good frame goes to every sink in order.
FrameRunResult run_frames(Simulation& simulation, const Scene& scene, int first, int end,
                          std::span<FrameSink* const> sinks, const FrameRunOptions& options = {});

}  // namespace flagsim::sim
