#pragma once
// An H.264 MP4 made by piping raw RGB frames to ffmpeg (libx264, yuv420p, so
// that common players open it).
#include <cstdio>
#include <memory>
#include <string>

#include "flagsim/core/child_process.hpp"
#include "flagsim/render/image.hpp"

namespace flagsim::render {

/// The ffmpeg executable on PATH, or "" when there is none.
std::string find_ffmpeg();

class VideoWriter {
 public:
  /// Starts ffmpeg writing `path`. Throws UserError when ffmpeg is not on PATH.
  VideoWriter(const std::string& path, int width, int height, double fps);
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  /// Appends a frame (same size as given to the constructor). Throws IoError
  /// when ffmpeg stopped taking frames.
  void write(const Image& frame);
  /// Waits for ffmpeg; throws IoError when it failed.
  void finish();

 private:
  std::string path_;
  int width_, height_;
  std::unique_ptr<ChildProcess> ffmpeg_;
  FILE* pipe_ = nullptr;  ///< ffmpeg's standard input
};

}  // namespace flagsim::render
