#pragma once
// The progress line on a terminal: frame, sim time, ms/frame, ETA. The rate
// is the recent one (the frames of the last few seconds): a run whose frames
// get slower as the flag starts to flap (10 ms flat, 600 ms flapping with the
// paper infill) said "ETA 0 s" from the running mean with 6 s left.
#include <chrono>
#include <deque>
#include <string>
#include <utility>

#include "flagsim/sim/frame_runner.hpp"

namespace flagsim::app {

/// Also a sink of a run of frames (sim::run_frames): each good frame updates the line.
class Progress final : public sim::FrameSink {
 public:
  /// Shown only when `enabled` (stderr is a terminal and --quiet is not given).
  /// `label` leads the line ("reference (mass-spring)"); empty: none.
  Progress(bool enabled, int total_frames, std::string label = "");
  /// Whether a progress line belongs on stderr: a terminal, and not --quiet.
  static bool wanted(bool quiet);
  /// After frame `frame` (0-based) at simulated time t; redraws at most 5 times
  /// a second. `ms_per_frame` (the run's mean) is shown until there is a
  /// recent rate to show.
  void update(int frame, double time_s, double ms_per_frame);
  /// update() after each frame of a run, with the mean wall time of its frames
  /// so far, each counted from its start until the next frame starts.
  bool take(const sim::Simulation& simulation, const sim::CheckedFrame& frame) override;
  /// Clears the line.
  void done();

 private:
  bool enabled_;
  int total_frames_;
  std::string label_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point last_draw_{};
  /// (when, frame) of the updates of the last kWindow, oldest first.
  std::deque<std::pair<std::chrono::steady_clock::time_point, int>> recent_;
  /// take(): the first frame taken and when it started.
  int first_taken_ = -1;
  std::chrono::steady_clock::time_point first_start_{};
};

}  // namespace flagsim::app
