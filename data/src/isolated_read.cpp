#include "flagsim/data/isolated_read.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <thread>

#include "flagsim/core/errors.hpp"
#include "flagsim/core/message.hpp"
#include "flagsim/core/stop_request.hpp"

namespace flagsim::data {
namespace {

bool g_in_child = false;
bool g_isolated_reads = true;

// A test read reads the attributes, the first and last frame and at most
// 16 MiB of each dataset: seconds even for a large file on a slow disk. It is
// given 60 s, and 1 s more for every 10 MiB of the file (a cold network disk).
constexpr long long kTestReadSeconds = 60;

// What the child reports, first byte of its memory file: then the text.
enum Outcome : char { kReturned = 'R', kUserError = 'U', kIoError = 'I' };

void write_all(int fd, const std::string& bytes) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    done += std::size_t(n);
  }
}

std::string read_all(int fd) {
  std::string text;
  char chunk[1 << 16];
  ::lseek(fd, 0, SEEK_SET);
  for (;;) {
    const ssize_t n = ::read(fd, chunk, sizeof chunk);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    text.append(chunk, std::size_t(n));
  }
  return text;
}

}  // namespace

bool in_isolated_child() {
  return g_in_child;
}

bool isolated_reads() {
  return g_isolated_reads;
}

void set_isolated_reads(bool on) {
  g_isolated_reads = on;
}

std::string run_isolated(const std::string& path, const std::function<std::string()>& work) {
  if (g_in_child) return work();
  const int fd = ::memfd_create("flag-sim-isolated-read", MFD_CLOEXEC);
  if (fd < 0) return work();
  std::fflush(nullptr);  // nothing buffered is printed twice
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fd);
    return work();
  }
  if (pid == 0) {
    g_in_child = true;
    std::signal(SIGINT, SIG_DFL);  // the parent's handlers only raise a flag: a signal ends it
    std::signal(SIGTERM, SIG_DFL);
    // Its words come back through the report; what a crashing library prints
    // ("free(): invalid pointer") does not reach the user's terminal.
    if (const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC); null >= 0) {
      ::dup2(null, STDOUT_FILENO);
      ::dup2(null, STDERR_FILENO);
    }
    std::string report;
    try {
      report = char(kReturned) + work();
    } catch (const UserError& e) {
      report = char(kUserError) + std::string(e.what());
    } catch (const IoError& e) {
      report = char(kIoError) + std::string(e.what());
    } catch (...) {
      ::_exit(1);
    }
    write_all(fd, report);
    ::_exit(0);  // no atexit handlers, no HDF5 shutdown: the parent owns those
  }
  // Waited for at most kTestReadSeconds (a damaged global heap can also make
  // HDF5 loop for ever), and no longer than the user wants (SIGINT, SIGTERM).
  int status = 0;
  pid_t done = 0;
  struct stat st {};
  const long long limit_s =
      kTestReadSeconds + (::stat(path.c_str(), &st) == 0 ? (long long)(st.st_size >> 20) / 10 : 0);
  const auto start = std::chrono::steady_clock::now();
  auto pause = std::chrono::microseconds(200);
  bool late = false, stopped = false;
  while ((done = ::waitpid(pid, &status, WNOHANG)) == 0 || (done < 0 && errno == EINTR)) {
    stopped = stop_requested();
    late = std::chrono::steady_clock::now() - start > std::chrono::seconds(limit_s);
    if (stopped || late) {
      ::kill(pid, SIGKILL);
      do done = ::waitpid(pid, &status, 0);
      while (done < 0 && errno == EINTR);
      break;
    }
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::microseconds(20'000));
  }
  const std::string report = read_all(fd);
  ::close(fd);
  // Ctrl-C reaches the child with its parent: a child ended by SIGINT or
  // SIGTERM was stopped by the user, not by the file.
  stopped = stopped || stop_requested() ||
            (done == pid && WIFSIGNALED(status) &&
             (WTERMSIG(status) == SIGINT || WTERMSIG(status) == SIGTERM));
  if (stopped)
    throw Interrupted(fmt::format("reading {} stopped by a signal", printable(path, 200)));
  if (late)
    throw UserError(fmt::format(
        "{}: damaged (a test read of it did not finish in {} s: the HDF5 library loops on it); "
        "not read",
        printable(path, 200), limit_s));
  if (done == pid && WIFSIGNALED(status))
    throw UserError(fmt::format(
        "{}: damaged (reading it crashes the HDF5 library: {} in a test read); not read",
        printable(path, 200), strsignal(WTERMSIG(status))));
  if (done != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0 || report.empty())
    throw UserError(
        fmt::format("{}: damaged (a test read of it failed); not read", printable(path, 200)));
  std::string text = report.substr(1);
  if (report[0] == kUserError) throw UserError(text);
  if (report[0] == kIoError) throw IoError(text);
  return text;
}

}  // namespace flagsim::data
