#pragma once
// The three levels of failure (STYLE.md, 6):
//  - our own bugs: assert;
//  - the user's mistake (scene, flags, files): throw UserError, which the app
//    prints as one `error:` line and turns into exit code 2;
//  - numerical trouble: a RunStatus (run_status.hpp: diverged), never an exception.
#include <stdexcept>
#include <string>

namespace flagsim {

/// Exit codes of the flag-sim command line (contract: "Exit codes").
enum class ExitCode : int {
  kSuccess = 0,
  kInternal = 1,  ///< a bug in flag-sim (an exception nothing else handled); not in the contract
  kBadInput = 2,
  kDiverged = 3,
  kIoFailure = 4,
  kInterrupted = 130,
};

/// A mistake in the user's input. what() is the whole message after "error: ",
/// and starts with the place (file:line:column or the flag) where it can be fixed.
class UserError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A failure to read or write a file once the run has started (disk full,
/// directory removed): exit code 4, whatever was flushed stays readable.
/// The user stopped a command (SIGINT, SIGTERM) that cleans up after itself
/// and exits 130: the message says what was stopped and what is kept.
class Interrupted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace flagsim
