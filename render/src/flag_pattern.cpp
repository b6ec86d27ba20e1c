#include "flagsim/render/flag_pattern.hpp"

namespace flagsim::render {

Image flag_pattern() {
  Image image(192, 128);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      std::uint8_t* p = image.pixel(x, y);
      const bool canton = x < 80 && y < 64;
      const bool red = (y * 7 / image.height) % 2 == 0;
      const std::uint8_t colour[3] = {std::uint8_t(canton ? 30
                                                   : red  ? 200
                                                          : 245),
                                      std::uint8_t(canton ? 50
                                                   : red  ? 30
                                                          : 245),
                                      std::uint8_t(canton ? 140
                                                   : red  ? 40
                                                          : 245)};
      p[0] = colour[0];
      p[1] = colour[1];
      p[2] = colour[2];
    }
  return image;
}

}  // namespace flagsim::render
