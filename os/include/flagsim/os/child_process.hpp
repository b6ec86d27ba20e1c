#pragma once
// A helper program (Python for plots, ffmpeg for video) started with an
// argument vector, never through a shell: no path or name a user gives can
// become a command.
#include <sys/types.h>

#include <cstdio>
#include <string>
#include <vector>

namespace flagsim {

/// Where a helper's standard output and error go.
enum class ChildOutput {
  kInherit,  ///< flag-sim's own
  kDiscard,  ///< /dev/null
  kCapture,  ///< an anonymous file, read back by captured(): for its error message
};

class ChildProcess {
 public:
  /// Starts argv[0] (an absolute path, or looked up on PATH) with `argv`.
  /// @param pipe_input  its standard input is a pipe written through input()
  /// valid() is false when it could not be started.
  ChildProcess(const std::vector<std::string>& argv, bool pipe_input, ChildOutput output);
  ~ChildProcess();  ///< closes the pipe and waits, if wait() was not called
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  bool valid() const { return pid_ > 0; }
  /// The write end of its standard input (null without pipe_input).
  std::FILE* input() { return input_; }
  /// Closes its input, waits for it; its exit code, or -1 if it did not exit
  /// normally. A stop request (SIGINT, SIGTERM to flag-sim) while it waits is
  /// passed on to it as SIGTERM: a helper never outlives a stopped command.
  int wait();
  /// With ChildOutput::kCapture: the last line it wrote (at most 300 bytes), else "".
  std::string captured() const;

 private:
  pid_t pid_ = -1;
  std::FILE* input_ = nullptr;
  int capture_fd_ = -1;
};

/// argv as exec and posix_spawn take it: a pointer to each string's
/// characters, then a null pointer. Valid while `argv` lives unchanged.
std::vector<char*> exec_argv(const std::vector<std::string>& argv);

/// Runs argv to the end with no input and no output; its exit code (-1: could not start).
int run_quietly(const std::vector<std::string>& argv);

/// Runs argv to the end with no input; `output` receives what it wrote to its
/// standard output and error, interleaved. Its exit code (-1: could not start).
int run_capturing(const std::vector<std::string>& argv, std::string& output);

}  // namespace flagsim
