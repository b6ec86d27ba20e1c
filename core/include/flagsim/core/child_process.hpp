#pragma once
// A helper program (Python for plots, ffmpeg for video) started with an
// argument vector, never through a shell: no path or name a user gives can
// become a command.
#include <sys/types.h>

#include <cstdio>
#include <string>
#include <vector>

namespace flagsim {

class ChildProcess {
 public:
  /// Starts argv[0] (an absolute path, or looked up on PATH) with `argv`.
  /// @param pipe_input  its standard input is a pipe written through input()
  /// @param quiet       its standard output and error go to /dev/null
  /// valid() is false when it could not be started.
  ChildProcess(const std::vector<std::string>& argv, bool pipe_input, bool quiet);
  ~ChildProcess();  ///< closes the pipe and waits, if wait() was not called
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  bool valid() const { return pid_ > 0; }
  /// The write end of its standard input (null without pipe_input).
  std::FILE* input() { return input_; }
  /// Closes its input, waits for it; its exit code, or -1 if it did not exit normally.
  int wait();

 private:
  pid_t pid_ = -1;
  std::FILE* input_ = nullptr;
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
