#pragma once
// An 8-bit RGB image, rows top to bottom: what the renderer produces and the
// PNG and video writers consume.
#include <cstdint>
#include <vector>

namespace flagsim::render {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  ///< [height * width * 3], row 0 at the top

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgb(std::size_t(w) * std::size_t(h) * 3, 0) {}
  const std::uint8_t* pixel(int x, int y) const {
    return rgb.data() + (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3;
  }
  std::uint8_t* pixel(int x, int y) {
    return rgb.data() + (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3;
  }
};

}  // namespace flagsim::render
