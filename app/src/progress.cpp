#include "progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>
#include <utility>

namespace flagsim::app {

Progress::Progress(bool enabled, int total_frames, std::string label)
    : enabled_(enabled), total_frames_(total_frames), label_(std::move(label)) {}

bool Progress::wanted(bool quiet) {
  return !quiet && isatty(STDERR_FILENO);
}

void Progress::update(int frame, double time_s, double ms_per_frame) {
  if (!enabled_) return;
  constexpr auto kWindow = std::chrono::seconds(3);
  const auto now = std::chrono::steady_clock::now();
  recent_.emplace_back(now, frame);
  while (recent_.size() > 2 && now - recent_[1].first > kWindow) recent_.pop_front();
  if (drawn_ && now - last_draw_ < std::chrono::milliseconds(200)) return;
  last_draw_ = now;
  drawn_ = true;
  const auto& [then, first_frame] = recent_.front();
  const double window_s = std::chrono::duration<double>(now - then).count();
  if (frame > first_frame && window_s > 0.0) ms_per_frame = 1e3 * window_s / (frame - first_frame);
  const double eta_s = (total_frames_ - 1 - frame) * ms_per_frame / 1000.0;
  fmt::print(stderr, "\r{}{}frame {}/{}  t = {:.2f} s  {:.1f} ms/frame  ETA {:.0f} s   ", label_,
             label_.empty() ? "" : ": ", frame + 1, total_frames_, time_s, ms_per_frame, eta_s);
  std::fflush(stderr);
}

bool Progress::take(const sim::Simulation& /*simulation*/, const sim::CheckedFrame& frame) {
  const auto now = std::chrono::steady_clock::now();
  if (first_taken_ < 0) {
    first_taken_ = frame.index;
    first_start_ = now - std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                             std::chrono::duration<double>(frame.wall_s));
  }
  const double wall_s = std::chrono::duration<double>(now - first_start_).count();
  update(frame.index, frame.time_s, 1e3 * wall_s / (frame.index - first_taken_ + 1));
  return true;
}

void Progress::done() {
  if (enabled_ && drawn_) fmt::print(stderr, "\r{:{}}\r", "", 72 + label_.size());
  drawn_ = false;
}

}  // namespace flagsim::app
