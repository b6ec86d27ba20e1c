#include "flagsim/render/png_io.hpp"

#include <fmt/format.h>
#include <png.h>

#include <cstring>

#include "flagsim/core/errors.hpp"

namespace flagsim::render {

void write_png(const std::string& path, const Image& image) {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  png.width = png_uint_32(image.width);
  png.height = png_uint_32(image.height);
  png.format = PNG_FORMAT_RGB;
  if (!png_image_write_to_file(&png, path.c_str(), 0, image.rgb.data(), 0, nullptr))
    throw IoError(fmt::format("{}: cannot write PNG ({})", path, png.message));
}

Image read_png(const std::string& path) {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str()))
    throw UserError(fmt::format("{}: cannot read as PNG ({})", path, png.message));
  png.format = PNG_FORMAT_RGB;
  Image image(int(png.width), int(png.height));
  if (!png_image_finish_read(&png, nullptr, image.rgb.data(), 0, nullptr)) {
    png_image_free(&png);
    throw UserError(fmt::format("{}: cannot read as PNG ({})", path, png.message));
  }
  return image;
}

}  // namespace flagsim::render
