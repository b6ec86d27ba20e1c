#include "flagsim/render/video_writer.hpp"

#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <sstream>

#include "flagsim/core/errors.hpp"

namespace flagsim::render {
namespace {

// Single-quoted for /bin/sh.
std::string shell_quote(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

}  // namespace

std::string find_ffmpeg() {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    const std::string candidate = (dir.empty() ? "." : dir) + "/ffmpeg";
    if (access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return "";
}

VideoWriter::VideoWriter(const std::string& path, int width, int height, double fps)
    : path_(path), width_(width), height_(height) {
  const std::string ffmpeg = find_ffmpeg();
  if (ffmpeg.empty())
    throw UserError(fmt::format(
        "{}: MP4 needs ffmpeg, which is not on PATH (apt-get install ffmpeg), or give -o a "
        "directory for PNG frames",
        path));
  const std::string command = fmt::format(
      "{} -loglevel error -y -f rawvideo -pix_fmt rgb24 -s {}x{} -r {} -i - -c:v libx264 "
      "-preset veryfast -crf 20 -pix_fmt yuv420p -movflags +faststart {}",
      shell_quote(ffmpeg), width, height, fps, shell_quote(path));
  std::signal(SIGPIPE, SIG_IGN);  // a dead ffmpeg is reported by fwrite, not by a signal
  pipe_ = popen(command.c_str(), "w");
  if (!pipe_) throw IoError(fmt::format("{}: cannot start ffmpeg", path));
}

VideoWriter::~VideoWriter() {
  if (pipe_) pclose(pipe_);
}

void VideoWriter::write(const Image& frame) {
  if (frame.width != width_ || frame.height != height_ ||
      std::fwrite(frame.rgb.data(), 1, frame.rgb.size(), pipe_) != frame.rgb.size())
    throw IoError(fmt::format("{}: ffmpeg stopped taking frames", path_));
}

void VideoWriter::finish() {
  const int status = pclose(pipe_);
  pipe_ = nullptr;
  if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw IoError(fmt::format("{}: ffmpeg failed to write the video", path_));
}

}  // namespace flagsim::render
