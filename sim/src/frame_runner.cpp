#include "flagsim/sim/frame_runner.hpp"

#include <chrono>
#include <vector>

#include "flagsim/core/stop_request.hpp"

namespace flagsim::sim {

FrameRunResult run_frames(Simulation& simulation, const Scene& scene, int first, int end,
                          std::span<FrameSink* const> sinks, const FrameRunOptions& options) {
  std::vector<float> node_strain(options.node_strain ? simulation.lattice().node_count() : 0);
  FrameRunResult result;
  for (int frame = first; frame < end; ++frame) {
    const auto start = std::chrono::steady_clock::now();
    result.frame = frame;
    if (frame > 0) {
      simulation.advance_frame(options.times);
      if (stop_requested()) {  // the frame was cut short: the simulation is not at a frame
        result.end = FrameRunEnd::kInterruptedDuring;
        return result;
      }
    }
    CheckedFrame checked;
    checked.index = frame;
    checked.time_s = frame / scene.fps;
    run_timed(options.times, options.checks_stage, [&] {
      checked.strain = link_strain(simulation.lattice(), simulation.positions(), node_strain);
      result.divergence = frame_divergence(simulation, scene, checked.strain);
      if (result.divergence) result.end = FrameRunEnd::kDiverged;
    });
    if (result.end == FrameRunEnd::kDiverged) return result;
    checked.node_strain = node_strain;
    checked.wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    for (FrameSink* sink : sinks)
      if (!sink->take(simulation, checked)) {
        result.end = FrameRunEnd::kStoppedBySink;
        return result;
      }
    if (stop_requested() && frame + 1 < end) {
      result.end = FrameRunEnd::kInterruptedAfter;
      return result;
    }
  }
  result.end = FrameRunEnd::kComplete;
  return result;
}

}  // namespace flagsim::sim
