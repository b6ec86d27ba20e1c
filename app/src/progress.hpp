#pragma once
// The progress line on a terminal: frame, sim time, ms/frame, ETA.
#include <chrono>

namespace flagsim::app {

class Progress {
 public:
  /// Shown only when `enabled` (stderr is a terminal and --quiet is not given).
  Progress(bool enabled, int total_frames);
  /// After frame `frame` (0-based) at simulated time t; redraws at most 5 times a second.
  void update(int frame, double time_s, double ms_per_frame);
  /// Clears the line.
  void done();

 private:
  bool enabled_;
  int total_frames_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point last_draw_{};
};

}  // namespace flagsim::app
