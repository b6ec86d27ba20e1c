#pragma once
// Wall time of each pipeline stage, accumulated per output frame
// (contract: /stats/stage_seconds [T, S] with attribute `stages`).
#include <chrono>
#include <span>
#include <string>
#include <vector>

namespace flagsim {

/// What a stage's time is spent on, for the summaries that split a frame's
/// cost (compare's physics_ms and infill_ms columns).
enum class StageGroup { kPhysics, kInfill, kRunLoop };

class StageTimes {
 public:
  /// Registers a stage; returns its column. Stages are listed in pipeline order.
  int add(std::string name, StageGroup group = StageGroup::kPhysics) {
    names_.push_back(std::move(name));
    groups_.push_back(group);
    seconds_.push_back(0.0);
    return int(names_.size()) - 1;
  }
  const std::vector<StageGroup>& groups() const { return groups_; }
  void add_seconds(int stage, double seconds) { seconds_[stage] += seconds; }
  const std::vector<std::string>& names() const { return names_; }
  /// Seconds per stage since the last reset.
  std::span<const double> seconds() const { return seconds_; }
  void reset() { std::fill(seconds_.begin(), seconds_.end(), 0.0); }

 private:
  std::vector<std::string> names_;
  std::vector<StageGroup> groups_;
  std::vector<double> seconds_;
};

/// Adds the lifetime of this object to one stage's time.
class ScopedStageTimer {
 public:
  ScopedStageTimer(StageTimes& times, int stage)
      : times_(times), stage_(stage), start_(std::chrono::steady_clock::now()) {}
  ~ScopedStageTimer() {
    const auto elapsed = std::chrono::steady_clock::now() - start_;
    times_.add_seconds(stage_, std::chrono::duration<double>(elapsed).count());
  }
  ScopedStageTimer(const ScopedStageTimer&) = delete;
  ScopedStageTimer& operator=(const ScopedStageTimer&) = delete;

 private:
  StageTimes& times_;
  int stage_;
  std::chrono::steady_clock::time_point start_;
};

/// Times stages that run one after another with one clock read between each
/// two (run_timed reads the clock twice a stage): each run() adds the time
/// since the previous one (or since construction) to its stage; a stage < 0
/// (not registered) counts nowhere. Timing off (times null): just runs.
class StageLaps {
 public:
  explicit StageLaps(StageTimes* times) : times_(times) {
    if (times_) last_ = std::chrono::steady_clock::now();
  }
  template <typename Work>
  void run(int stage, Work&& work) {
    work();
    if (!times_) return;
    const auto now = std::chrono::steady_clock::now();
    if (stage >= 0) times_->add_seconds(stage, std::chrono::duration<double>(now - last_).count());
    last_ = now;
  }

 private:
  StageTimes* times_;
  std::chrono::steady_clock::time_point last_;
};

/// Runs `work`, adding its wall time to `stage` when timing is on (times not
/// null and the stage registered, stage >= 0); otherwise just runs it.
template <typename Work>
void run_timed(StageTimes* times, int stage, Work&& work) {
  if (times && stage >= 0) {
    ScopedStageTimer timer(*times, stage);
    work();
  } else {
    work();
  }
}

}  // namespace flagsim
