#include "flagsim/render/video_writer.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cctype>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <vector>

#include "flagsim/core/errors.hpp"
#include "flagsim/os/child_process.hpp"

namespace flagsim::render {

std::string find_ffmpeg() {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    std::string candidate = (dir.empty() ? "." : dir) + "/ffmpeg";
    if (access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return "";
}

std::optional<Container> container_of(std::string_view path) {
  const auto dot = path.rfind('.');
  const auto slash = path.rfind('/');
  if (dot == std::string_view::npos || (slash != std::string_view::npos && dot < slash))
    return std::nullopt;
  std::string extension;
  for (const char c : path.substr(dot + 1)) extension += char(std::tolower((unsigned char)c));
  if (extension == "mp4") return Container::kMp4;
  if (extension == "mkv") return Container::kMkv;
  if (extension == "webm") return Container::kWebm;
  if (extension == "gif") return Container::kGif;
  return std::nullopt;
}

std::string_view to_string(Container container) {
  switch (container) {
    case Container::kMp4:
      return "H.264 MP4";
    case Container::kMkv:
      return "H.264 Matroska";
    case Container::kWebm:
      return "VP9 WebM";
    case Container::kGif:
      return "GIF";
  }
  return "";
}

bool needs_even_size(Container container) {
  return container != Container::kGif;
}

VideoWriter::VideoWriter(const std::string& path, Container container, int width, int height,
                         double fps)
    : path_(path), width_(width), height_(height) {
  const std::string ffmpeg = find_ffmpeg();
  if (ffmpeg.empty())
    throw UserError(fmt::format(
        "{}: a video needs ffmpeg, which is not on PATH (apt-get install ffmpeg), or give -o a "
        "directory for PNG frames",
        path));
  std::signal(SIGPIPE, SIG_IGN);  // a dead ffmpeg is reported by fwrite, not by a signal
  // An argument vector, never a shell command: the path is one argument.
  std::vector<std::string> args{ffmpeg,     "-loglevel",
                                "error",    "-y",
                                "-f",       "rawvideo",
                                "-pix_fmt", "rgb24",
                                "-s",       fmt::format("{}x{}", width, height),
                                "-r",       fmt::format("{}", fps),
                                "-i",       "-"};
  const auto add = [&args](std::initializer_list<const char*> more) {
    args.insert(args.end(), more.begin(), more.end());
  };
  // The muxer is named, since the file ffmpeg writes is PATH.partial.
  switch (container) {
    case Container::kMp4:
      add({"-f", "mp4", "-c:v", "libx264", "-preset", "veryfast", "-crf", "20", "-pix_fmt",
           "yuv420p", "-movflags", "+faststart"});
      break;
    case Container::kMkv:
      add({"-f", "matroska", "-c:v", "libx264", "-preset", "veryfast", "-crf", "20", "-pix_fmt",
           "yuv420p"});
      break;
    case Container::kWebm:
      add({"-f", "webm", "-c:v", "libvpx-vp9", "-b:v", "0", "-crf", "32", "-deadline", "realtime",
           "-cpu-used", "8", "-row-mt", "1", "-pix_fmt", "yuv420p"});
      break;
    case Container::kGif:  // one palette for the whole clip, made from its frames
      add({"-f", "gif", "-filter_complex", "[0:v]split[a][b];[a]palettegen[p];[b][p]paletteuse",
           "-loop", "0"});
      break;
  }
  // As a file: URL with an absolute path, so no name is read as an option
  // ("-y.gif") or as another protocol ("http:x.mp4").
  partial_ = path + ".partial";
  std::error_code ec;
  const std::filesystem::path absolute = std::filesystem::absolute(partial_, ec);
  args.push_back("file:" + (ec ? partial_ : absolute.string()));
  ffmpeg_ = std::make_unique<ChildProcess>(std::move(args), true, ChildOutput::kCapture);
  if (!ffmpeg_->valid()) throw IoError(fmt::format("{}: cannot start ffmpeg", path));
  pipe_ = ffmpeg_->input();
}

VideoWriter::~VideoWriter() {
  if (!ffmpeg_) return;
  ffmpeg_.reset();  // closes its input, waits: nothing keeps writing the file below
  if (!finished_) std::remove(partial_.c_str());
}

void VideoWriter::fail(const std::string& what) {
  ffmpeg_->wait();
  pipe_ = nullptr;
  std::remove(partial_.c_str());
  const std::string said = ffmpeg_->captured();
  finished_ = true;
  throw IoError(fmt::format("{}: {}{}; no video was written", path_, what,
                            said.empty() ? "" : fmt::format(" (ffmpeg: {})", said)));
}

void VideoWriter::write(const Image& frame) {
  if (frame.width != width_ || frame.height != height_ ||
      std::fwrite(frame.rgb.data(), 1, frame.rgb.size(), pipe_) != frame.rgb.size())
    fail("ffmpeg stopped taking frames");
}

void VideoWriter::finish() {
  const int status = ffmpeg_->wait();
  pipe_ = nullptr;
  // ffmpeg exits 0 after "Error writing trailer ...: No space left on device";
  // at -loglevel error it says nothing at all when it succeeds.
  if (status != 0 || !ffmpeg_->captured().empty()) fail("ffmpeg failed to write the video");
  if (std::rename(partial_.c_str(), path_.c_str()) != 0) fail("cannot rename into place");
  finished_ = true;
}

}  // namespace flagsim::render
