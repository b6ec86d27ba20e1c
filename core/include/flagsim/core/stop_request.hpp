#pragma once
// A request to stop, raised from a signal handler (SIGINT, SIGTERM) and seen
// by the loops that can run long inside one frame: the physics' substeps, the
// infill's projection rounds and relaxation passes. They return early; the
// frame they were making is incomplete, and the run does not write it.
namespace flagsim {

/// Async-signal-safe.
void request_stop();
void clear_stop_request();
bool stop_requested();

}  // namespace flagsim
