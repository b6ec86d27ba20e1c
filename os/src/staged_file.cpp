#include "flagsim/os/staged_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <utility>

#include "flagsim/core/errors.hpp"
#include "flagsim/core/message.hpp"

namespace flagsim {
namespace {

constexpr std::size_t kBufferBytes = 1 << 16;

std::string reason(int error) {
  return error == EFBIG ? "the file size limit is reached (no room for it)" : std::strerror(error);
}

}  // namespace

StagedFile::StagedFile(std::string path) : path_(std::move(path)), partial_(partial_of(path_)) {
  // Non-blocking open: a FIFO without a reader fails at once instead of
  // waiting; anything that is not a regular file is refused before a byte.
  // A stale NAME.partial (a file or a symlink) is unlinked, never written
  // through; what is made is a new file (O_EXCL), never one that was there.
  struct stat old {};
  if (::lstat(partial_.c_str(), &old) == 0 && !S_ISDIR(old.st_mode)) ::unlink(partial_.c_str());
  fd_ = ::open(partial_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK,
               0666);
  if (fd_ < 0) {
    const int error = errno;
    throw IoError(fmt::format("{}: cannot create {}: {}; nothing was written", printable(path_),
                              printable(partial_), reason(error)));
  }
  struct stat st {};
  if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd_);
    fd_ = -1;
    std::remove(partial_.c_str());  // a constructor that throws has no destructor run
    throw IoError(fmt::format("{}: not a regular file; nothing was written", printable(partial_)));
  }
  ::fcntl(fd_, F_SETFL, ::fcntl(fd_, F_GETFL) & ~O_NONBLOCK);
  buffer_.reserve(kBufferBytes);
}

StagedFile::~StagedFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!committed_) std::remove(partial_.c_str());
}

void StagedFile::fail(const std::string& doing, int error) {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  std::remove(partial_.c_str());
  committed_ = true;  // nothing left to remove
  throw IoError(fmt::format("{}: {}: {}; nothing was written under that name", printable(path_),
                            doing, reason(error)));
}

void StagedFile::flush() {
  std::size_t done = 0;
  while (done < buffer_.size()) {
    const ssize_t n = ::write(fd_, buffer_.data() + done, buffer_.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail("cannot write", n < 0 ? errno : ENOSPC);
    done += std::size_t(n);
  }
  buffer_.clear();
}

void StagedFile::write(std::string_view bytes) {
  if (fd_ < 0) throw IoError(fmt::format("{}: written after it was closed", printable(path_)));
  if (buffer_.size() + bytes.size() > kBufferBytes) flush();
  if (bytes.size() > kBufferBytes) {
    buffer_.assign(bytes);
    flush();
  } else {
    buffer_.append(bytes);
  }
}

void StagedFile::close() {
  if (fd_ < 0) return;
  flush();
  const int fd = std::exchange(fd_, -1);
  if (::close(fd) != 0) {  // NFS and some file systems report a full disk only here
    const int error = errno;
    fail("cannot close", error);
  }
}

void StagedFile::commit() {
  close();
  if (std::rename(partial_.c_str(), path_.c_str()) != 0) fail("cannot rename into place", errno);
  committed_ = true;
}

void write_file_whole(const std::string& path, std::string_view text) {
  StagedFile file(path);
  file.write(text);
  file.commit();
}

std::string read_file_capped(const std::string& path, std::size_t max_bytes,
                             const std::string& what) {
  const std::string where =
      what.empty() ? std::string() : fmt::format("{} {}: ", what, printable(path));
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw UserError(fmt::format("{}cannot open ({})", where, std::strerror(errno)));
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    throw UserError(fmt::format("{}not a regular file (a FIFO, device or directory)", where));
  }
  if (std::size_t(st.st_size) > max_bytes) {
    ::close(fd);
    throw UserError(fmt::format("{}{} bytes, more than flag-sim reads there (at most {})", where,
                                st.st_size, max_bytes));
  }
  std::string text;
  char chunk[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, chunk, sizeof chunk);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    text.append(chunk, std::size_t(n));
    if (text.size() > max_bytes) break;  // it grew while read
  }
  ::close(fd);
  if (text.size() > max_bytes)
    throw UserError(
        fmt::format("{}more than flag-sim reads there (at most {} bytes)", where, max_bytes));
  return text;
}

}  // namespace flagsim
