#include "flagsim/render/png_io.hpp"

#include <fmt/format.h>
#include <png.h>

#include <cstring>
#include <string>

#include "flagsim/core/errors.hpp"
#include "flagsim/core/limits.hpp"
#include "flagsim/os/staged_file.hpp"

namespace flagsim::render {
namespace {

/// A PNG read as a texture: 256 MiB (an 8192 x 8192 RGBA image is 256 MiB raw).
constexpr std::size_t kMaxPngBytes = std::size_t(256) << 20;

}  // namespace

void write_png(const std::string& path, const Image& image) {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  png.width = png_uint_32(image.width);
  png.height = png_uint_32(image.height);
  png.format = PNG_FORMAT_RGB;
  // Encoded in memory, then written whole (PATH.partial, renamed): a full disk
  // leaves no cut PNG under a frame's name.
  // Encoded once, into a buffer of libpng's bound on the encoded size.
  png_alloc_size_t bytes = PNG_IMAGE_PNG_SIZE_MAX(png);
  std::string encoded(bytes, '\0');
  if (!png_image_write_to_memory(&png, encoded.data(), &bytes, 0, image.rgb.data(), 0, nullptr))
    throw IoError(fmt::format("{}: cannot encode PNG ({})", path, png.message));
  encoded.resize(bytes);
  write_file_whole(path, encoded);
}

Image read_png(const std::string& path) {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  // Read whole first: only a regular file, and only as much as a texture can be.
  std::string bytes;
  try {
    bytes = read_file_capped(path, kMaxPngBytes, "");
  } catch (const UserError& e) {
    throw UserError(fmt::format("{}: cannot read as PNG ({})", path, e.what()));
  }
  if (!png_image_begin_read_from_memory(&png, bytes.data(), bytes.size()))
    throw UserError(fmt::format("{}: cannot read as PNG ({})", path, png.message));
  if (png.width > png_uint_32(limits::kImageSideMax) ||
      png.height > png_uint_32(limits::kImageSideMax)) {
    png_image_free(&png);
    throw UserError(fmt::format("{}: {} x {} pixels, more than {} on a side", path, png.width,
                                png.height, limits::kImageSideMax));
  }
  png.format = PNG_FORMAT_RGB;
  Image image(int(png.width), int(png.height));
  if (!png_image_finish_read(&png, nullptr, image.rgb.data(), 0, nullptr)) {
    png_image_free(&png);
    throw UserError(fmt::format("{}: cannot read as PNG ({})", path, png.message));
  }
  return image;
}

}  // namespace flagsim::render
