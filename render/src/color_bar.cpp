#include "flagsim/render/color_bar.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "flagsim/render/frame_renderer.hpp"

namespace flagsim::render {
namespace {

// 5 x 7 glyphs, one row a byte, the low five bits left to right.
struct Glyph {
  char c;
  std::array<std::uint8_t, 7> rows;
};
constexpr Glyph kFont[] = {
    {'0', {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}},
    {'1', {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'2', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}},
    {'3', {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}},
    {'4', {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}},
    {'5', {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}},
    {'6', {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}},
    {'7', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}},
    {'9', {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}},
    {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}},
    {'%', {0x18, 0x19, 0x02, 0x04, 0x08, 0x13, 0x03}},
    {'/', {0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x00}},
    {'m', {0x00, 0x00, 0x1A, 0x15, 0x15, 0x11, 0x11}},
    {'s', {0x00, 0x00, 0x0E, 0x10, 0x0E, 0x01, 0x1E}},
    {'-', {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00}},
};

const Glyph* glyph_of(char c) {
  for (const Glyph& g : kFont)
    if (g.c == c) return &g;
  return nullptr;
}

void fill(Image& image, int x0, int y0, int w, int h, std::array<std::uint8_t, 3> rgb) {
  for (int y = std::max(0, y0); y < std::min(image.height, y0 + h); ++y)
    for (int x = std::max(0, x0); x < std::min(image.width, x0 + w); ++x)
      std::copy(rgb.begin(), rgb.end(), image.pixel(x, y));
}

// `text` with its right end at x_right, top at y_top, each font pixel `scale` pixels.
void draw_text(Image& image, std::string_view text, int x_right, int y_top, int scale) {
  const int advance = 6 * scale;
  int x = x_right - int(text.size()) * advance;
  for (const char c : text) {
    if (const Glyph* g = glyph_of(c))
      for (int row = 0; row < 7; ++row)
        for (int col = 0; col < 5; ++col)
          if (g->rows[std::size_t(row)] & (0x10 >> col))
            fill(image, x + col * scale, y_top + row * scale, scale, scale, {255, 255, 255});
    x += advance;
  }
}

}  // namespace

void draw_color_bar(Image& image, std::string_view top_label, std::string_view bottom_label) {
  const int scale = std::max(1, image.height / 360);  // 2 at 720 rows
  const int bar_w = 12 * scale, bar_h = image.height / 2;
  const int x0 = image.width - bar_w - 8 * scale, y0 = (image.height - bar_h) / 2;
  const int label_w = 6 * scale * int(std::max(top_label.size(), bottom_label.size()));
  // A dark backing for the bar and its labels, readable over sky and ground.
  fill(image, x0 - label_w - 6 * scale, y0 - 4 * scale, bar_w + label_w + 10 * scale,
       bar_h + 8 * scale, {40, 40, 40});
  for (int y = 0; y < bar_h; ++y) {
    const std::array<float, 3> c = ramp_color(1.0 - double(y) / std::max(1, bar_h - 1));
    const auto byte = [](float v) { return std::uint8_t(std::lround(255.0f * v)); };
    fill(image, x0, y0 + y, bar_w, 1, {byte(c[0]), byte(c[1]), byte(c[2])});
  }
  draw_text(image, top_label, x0 - 3 * scale, y0, scale);
  draw_text(image, bottom_label, x0 - 3 * scale, y0 + bar_h - 7 * scale, scale);
}

}  // namespace flagsim::render
