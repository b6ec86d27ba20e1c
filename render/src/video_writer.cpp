#include "flagsim/render/video_writer.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <sstream>

#include "flagsim/core/child_process.hpp"
#include "flagsim/core/errors.hpp"

namespace flagsim::render {

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
  std::signal(SIGPIPE, SIG_IGN);  // a dead ffmpeg is reported by fwrite, not by a signal
  // An argument vector, never a shell command: the path is one argument.
  ffmpeg_ = std::make_unique<ChildProcess>(
      std::vector<std::string>{ffmpeg,      "-loglevel",
                               "error",     "-y",
                               "-f",        "rawvideo",
                               "-pix_fmt",  "rgb24",
                               "-s",        fmt::format("{}x{}", width, height),
                               "-r",        fmt::format("{}", fps),
                               "-i",        "-",
                               "-c:v",      "libx264",
                               "-preset",   "veryfast",
                               "-crf",      "20",
                               "-pix_fmt",  "yuv420p",
                               "-movflags", "+faststart",
                               path},
      true, false);
  if (!ffmpeg_->valid()) throw IoError(fmt::format("{}: cannot start ffmpeg", path));
  pipe_ = ffmpeg_->input();
}

VideoWriter::~VideoWriter() = default;

void VideoWriter::write(const Image& frame) {
  if (frame.width != width_ || frame.height != height_ ||
      std::fwrite(frame.rgb.data(), 1, frame.rgb.size(), pipe_) != frame.rgb.size())
    throw IoError(fmt::format("{}: ffmpeg stopped taking frames", path_));
}

void VideoWriter::finish() {
  const int status = ffmpeg_->wait();
  pipe_ = nullptr;
  if (status != 0) throw IoError(fmt::format("{}: ffmpeg failed to write the video", path_));
}

}  // namespace flagsim::render
