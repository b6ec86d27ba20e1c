#pragma once
// How a run ended (contract: root attribute `status`, exit codes): a value
// with its reason, not a string compared in each place that needs it.
#include <string>
#include <string_view>

#include "flagsim/core/enum_names.hpp"
#include "flagsim/core/errors.hpp"

namespace flagsim {

enum class RunState {
  kRunning,      ///< being written (the .partial file's status)
  kComplete,     ///< every frame simulated
  kDiverged,     ///< stopped at a frame that cannot be trusted; the frames before it kept
  kInterrupted,  ///< SIGINT / SIGTERM, or no room left for more frames
};

/// The contract's words for them (root attribute `status`, the reports' column).
inline constexpr NameTable<RunState, 4> kRunStateNames = {
    {{RunState::kRunning, "running"},
     {RunState::kComplete, "complete"},
     {RunState::kDiverged, "diverged"},
     {RunState::kInterrupted, "interrupted"}}};

constexpr std::string_view to_string(RunState state) {
  return name_in(kRunStateNames, state);
}

struct RunStatus {
  RunState state = RunState::kComplete;
  std::string reason;  ///< why it ended (root attribute `status_reason`)

  bool complete() const { return state == RunState::kComplete; }
  bool diverged() const { return state == RunState::kDiverged; }
  bool interrupted() const { return state == RunState::kInterrupted; }
  /// The process's exit code for a run that ended so (contract: "Exit codes").
  ExitCode exit_code() const {
    return diverged()      ? ExitCode::kDiverged
           : interrupted() ? ExitCode::kInterrupted
                           : ExitCode::kSuccess;
  }
};

}  // namespace flagsim
