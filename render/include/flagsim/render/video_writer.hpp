#pragma once
// A video made by piping raw RGB frames to ffmpeg, in the containers users
// ask for: MP4 and Matroska (H.264, yuv420p, so that common players open
// them), WebM (VP9) and GIF (a palette made from the frames).
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "flagsim/os/child_process.hpp"
#include "flagsim/render/image.hpp"

namespace flagsim::render {

/// The ffmpeg executable on PATH, or "" when there is none.
std::string find_ffmpeg();

enum class Container { kMp4, kMkv, kWebm, kGif };

/// The container a path's extension names (.mp4, .mkv, .webm, .gif, any
/// case), or nullopt.
std::optional<Container> container_of(std::string_view path);
/// "H.264 MP4", ...: for messages and the render summary.
std::string_view to_string(Container container);
/// Whether the container's encoding needs an even width and height (yuv420p).
bool needs_even_size(Container container);

class VideoWriter {
 public:
  /// Starts ffmpeg writing `path`.partial in `container`; finish() renames it
  /// onto `path`. Throws UserError when ffmpeg is not on PATH.
  VideoWriter(const std::string& path, Container container, int width, int height, double fps);
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  /// Appends a frame (same size as given to the constructor). Throws IoError
  /// when ffmpeg stopped taking frames.
  void write(const Image& frame);
  /// Waits for ffmpeg and puts the video under its name; throws IoError (with
  /// ffmpeg's last line) when it failed. A writer destroyed unfinished (a
  /// signal, an error) removes the partial video.
  void finish();

 private:
  [[noreturn]] void fail(const std::string& what);

  std::string path_, partial_;
  bool finished_ = false;
  int width_, height_;
  std::unique_ptr<ChildProcess> ffmpeg_;
  FILE* pipe_ = nullptr;  ///< ffmpeg's standard input
};

}  // namespace flagsim::render
