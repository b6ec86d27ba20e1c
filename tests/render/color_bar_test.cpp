// render --color's legend: the ramp from the scale's bottom to its top, and
// the two values beside it.
#include "flagsim/render/color_bar.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "flagsim/render/frame_renderer.hpp"

namespace flagsim::render {
namespace {

int white_pixels(const Image& image, int x0, int x1) {
  int count = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = x0; x < x1; ++x) {
      const std::uint8_t* p = image.pixel(x, y);
      count += p[0] == 255 && p[1] == 255 && p[2] == 255 ? 1 : 0;
    }
  return count;
}

TEST(ColorBar, TheRampRunsUpTheRightEdgeWithItsValuesBeside) {
  Image image(1280, 720);
  draw_color_bar(image, "0.737%", "0%");
  // At 720 rows: a bar 24 px wide, 360 high, centred, 16 px from the right edge.
  const int x = 1280 - 16 - 12, top = 180, bottom = 180 + 359;
  for (const auto& [y, t] : {std::pair{top, 1.0}, std::pair{bottom, 0.0}, std::pair{360, 0.5}}) {
    const std::array<float, 3> want = ramp_color(t);
    const std::uint8_t* got = image.pixel(x, y);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(got[c], 255.0 * want[std::size_t(c)], 2.0) << "row " << y << " channel " << c;
  }
  // The labels: white strokes left of the bar, none elsewhere.
  EXPECT_GT(white_pixels(image, 1280 - 28 - 7 * 12, 1280 - 28), 100);
  EXPECT_EQ(white_pixels(image, 0, 1100), 0);
  // A character without a glyph is a blank, not an error.
  Image small(320, 180);
  draw_color_bar(small, "12 m/s?", "0 m/s");
  EXPECT_GT(white_pixels(small, 200, 320), 20);
}

}  // namespace
}  // namespace flagsim::render
