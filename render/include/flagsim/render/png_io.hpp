#pragma once
// PNG files through libpng's simplified API. Written files carry no time
// chunk: the same image gives the same bytes.
#include <string>

#include "flagsim/render/image.hpp"

namespace flagsim::render {

/// Writes `image` as an 8-bit RGB PNG. Throws IoError when the file cannot be written.
void write_png(const std::string& path, const Image& image);

/// Reads a PNG (any colour type, converted to 8-bit RGB). Throws UserError
/// naming the file when it is missing or not a PNG.
Image read_png(const std::string& path);

}  // namespace flagsim::render
