#include "progress.hpp"

#include <fmt/format.h>

#include <cstdio>

namespace flagsim::app {

Progress::Progress(bool enabled, int total_frames)
    : enabled_(enabled), total_frames_(total_frames) {}

void Progress::update(int frame, double time_s, double ms_per_frame) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (drawn_ && now - last_draw_ < std::chrono::milliseconds(200)) return;
  last_draw_ = now;
  drawn_ = true;
  const double eta_s = (total_frames_ - 1 - frame) * ms_per_frame / 1000.0;
  fmt::print(stderr, "\rframe {}/{}  t = {:.2f} s  {:.1f} ms/frame  ETA {:.0f} s   ", frame + 1,
             total_frames_, time_s, ms_per_frame, eta_s);
  std::fflush(stderr);
}

void Progress::done() {
  if (enabled_ && drawn_) fmt::print(stderr, "\r{:70}\r", "");
}

}  // namespace flagsim::app
