#include "flagsim/os/child_process.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>

#include "flagsim/core/message.hpp"
#include "flagsim/core/stop_request.hpp"

extern char** environ;

namespace flagsim {

std::vector<char*> exec_argv(const std::vector<std::string>& argv) {
  std::vector<char*> args;
  args.reserve(argv.size() + 1);
  // exec's signature predates const; it does not write through these.
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  return args;
}

ChildProcess::ChildProcess(const std::vector<std::string>& argv, bool pipe_input,
                           ChildOutput output) {
  std::vector<char*> args = exec_argv(argv);
  int fds[2] = {-1, -1};
  if (pipe_input && ::pipe2(fds, O_CLOEXEC) != 0) return;
  if (output == ChildOutput::kCapture) capture_fd_ = ::memfd_create("flag-sim-helper", MFD_CLOEXEC);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (pipe_input)
    posix_spawn_file_actions_adddup2(&actions, fds[0], STDIN_FILENO);
  else
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  if (output == ChildOutput::kDiscard || (output == ChildOutput::kCapture && capture_fd_ < 0)) {
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  } else if (output == ChildOutput::kCapture) {
    posix_spawn_file_actions_adddup2(&actions, capture_fd_, STDOUT_FILENO);
    posix_spawn_file_actions_adddup2(&actions, capture_fd_, STDERR_FILENO);
  }
  pid_t pid = -1;
  const int failed = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (pipe_input) ::close(fds[0]);
  if (failed != 0) {
    if (pipe_input) ::close(fds[1]);
    return;
  }
  pid_ = pid;
  if (pipe_input) input_ = ::fdopen(fds[1], "w");
}

ChildProcess::~ChildProcess() {
  if (valid()) wait();
  if (capture_fd_ >= 0) ::close(capture_fd_);
}

std::string ChildProcess::captured() const {
  if (capture_fd_ < 0) return "";
  const off_t size = ::lseek(capture_fd_, 0, SEEK_END);
  if (size <= 0) return "";
  constexpr off_t kTail = 4096;
  std::string text(std::size_t(std::min(size, kTail)), '\0');
  const ssize_t n = ::pread(capture_fd_, text.data(), text.size(), size - off_t(text.size()));
  text.resize(n > 0 ? std::size_t(n) : 0);
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r' || text.back() == ' '))
    text.pop_back();
  const std::size_t line = text.rfind('\n');
  if (line != std::string::npos) text.erase(0, line + 1);
  return printable(text, 300);
}

int ChildProcess::wait() {
  if (input_) {
    std::fclose(input_);
    input_ = nullptr;
  }
  if (pid_ <= 0) return -1;
  int status = 0;
  pid_t done;
  bool passed_on = false;
  for (;;) {  // a stop that came before the wait, or interrupted it, is passed on once
    if (stop_requested() && !passed_on) {
      ::kill(pid_, SIGTERM);
      passed_on = true;
    }
    done = ::waitpid(pid_, &status, 0);
    if (done >= 0 || errno != EINTR) break;
  }
  pid_ = -1;
  return done > 0 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

int run_capturing(const std::vector<std::string>& argv, std::string& output) {
  output.clear();
  std::vector<char*> args = exec_argv(argv);
  int fds[2] = {-1, -1};
  if (::pipe2(fds, O_CLOEXEC) != 0) return -1;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, fds[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, fds[1], STDERR_FILENO);
  pid_t pid = -1;
  const int failed = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(fds[1]);
  if (failed != 0) {
    ::close(fds[0]);
    return -1;
  }
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
    if (n > 0) {
      output.append(buffer, std::size_t(n));
    } else if (n == 0 || errno != EINTR) {
      break;
    }
  }
  ::close(fds[0]);
  int status = 0;
  pid_t done;
  do done = ::waitpid(pid, &status, 0);
  while (done < 0 && errno == EINTR);
  return done > 0 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

int run_quietly(const std::vector<std::string>& argv) {
  ChildProcess child(argv, false, ChildOutput::kDiscard);
  return child.valid() ? child.wait() : -1;
}

}  // namespace flagsim
