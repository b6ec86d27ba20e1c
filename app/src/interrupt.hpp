#pragma once
// SIGINT / SIGTERM during a run: the handler only raises the stop request
// (core/stop_request.hpp); the loops inside a frame return early, the run
// loop drops that incomplete frame, marks the file "interrupted", exits 130.

namespace flagsim::app {

class InterruptGuard {
 public:
  InterruptGuard();   ///< installs the handlers
  ~InterruptGuard();  ///< restores the previous ones
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
  /// True once SIGINT or SIGTERM has arrived.
  static bool requested();
};

}  // namespace flagsim::app
