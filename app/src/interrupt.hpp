#pragma once
// SIGINT / SIGTERM during a run: the handler only raises a flag; the run loop
// finishes the current frame, marks the file "interrupted" and exits 130.

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
