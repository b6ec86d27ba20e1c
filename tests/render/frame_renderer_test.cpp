// What the renderer draws, checked on images of a known lattice: a flat flag
// 1.5 x 1.0 m in the z = 0 plane seen straight on from 4 m.
#include "flagsim/render/frame_renderer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "flagsim/core/lattice.hpp"
#include "flagsim/render/png_io.hpp"
#include "temp_dir.hpp"

namespace flagsim::render {
namespace {

constexpr int kWidth = 320, kHeight = 240;

struct Flat {
  Lattice lattice = Lattice::rectangle(9, 13, 1.5, 1.0, Vec3(0.0, 2.0, 0.0));
  std::vector<Vec3> x = lattice.rest_positions();
  FrameView view() const { return {lattice.rows, lattice.cols, x, std::nullopt, {}}; }
};

Camera straight_on(double z = 4.0) {
  Camera camera;
  camera.eye_m = Vec3(0.75, 1.5, z);
  camera.target_m = Vec3(0.75, 1.5, 0.0);
  return camera;
}

Image draw(Style style, const Camera& camera, Image texture = {}, int samples = 1) {
  const auto context = make_osmesa_context(kWidth, kHeight, samples);
  RenderOptions options;
  options.style = style;
  options.camera = camera;
  options.texture = std::move(texture);
  FrameRenderer renderer(*context, options);
  return renderer.render(Flat().view());
}

// Where the flag must land: 35 degrees of view over 240 rows, 4 m away.
struct Region {
  double left, right, top, bottom;
};
Region flag_region() {
  const double px_per_m = 0.5 * kHeight / (4.0 * std::tan(17.5 * M_PI / 180.0));
  return {0.5 * kWidth - 0.75 * px_per_m, 0.5 * kWidth + 0.75 * px_per_m,
          0.5 * kHeight - 0.5 * px_per_m, 0.5 * kHeight + 0.5 * px_per_m};
}

bool is_cloth_red(const std::uint8_t* p) {
  return p[0] > p[1] + 60 && p[0] > p[2] + 60;
}

// Pixels of `image` inside the region shrunk by `margin` px that satisfy `test`, as a fraction.
template <typename Test>
double fraction_inside(const Image& image, double margin, Test&& test) {
  const Region r = flag_region();
  int hits = 0, total = 0;
  for (int y = int(std::ceil(r.top + margin)); y <= int(r.bottom - margin); ++y)
    for (int x = int(std::ceil(r.left + margin)); x <= int(r.right - margin); ++x) {
      ++total;
      hits += test(image.pixel(x, y)) ? 1 : 0;
    }
  return double(hits) / total;
}

TEST(FrameRenderer, SupersamplingBlendsTheEdgesAndKeepsTheRest) {
  // 2 x 2 samples a pixel, averaged: the same picture at the same size, with
  // pixels on the flag's slanted edges part cloth, part background (redder
  // than the sky or ground, less red than the cloth), which one sample a
  // pixel does not make.
  Camera slanted = straight_on();
  slanted.eye_m = Vec3(3.0, 2.6, 3.2);
  const auto partly_red = [](const Image& image) {
    int count = 0;
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) {
        const std::uint8_t* p = image.pixel(x, y);
        const int redness = int(p[0]) - std::max(int(p[1]), int(p[2]));
        count += redness > 15 && redness < 45 ? 1 : 0;
      }
    return count;
  };
  const Image one = draw(Style::kShaded, slanted, {}, 1);
  const Image two = draw(Style::kShaded, slanted, {}, 2);
  ASSERT_EQ(two.width, kWidth);
  ASSERT_EQ(two.height, kHeight);
  EXPECT_EQ(fraction_inside(draw(Style::kShaded, straight_on(), {}, 2), 3.0, is_cloth_red), 1.0);
  EXPECT_EQ(partly_red(one), 0);    // measured 0
  EXPECT_GT(partly_red(two), 120);  // measured 177 (the edges are about 250 pixels long)
}

TEST(FrameRenderer, AFlatFlagFacingTheCameraCoversTheExpectedRegion) {
  const Image image = draw(Style::kShaded, straight_on());
  ASSERT_EQ(image.width, kWidth);
  EXPECT_EQ(fraction_inside(image, 2.0, is_cloth_red), 1.0);
  // Nothing red outside it (2 px of slack for the rasterizer's edge rules).
  const Region r = flag_region();
  int outside_red = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const bool near = x > r.left - 2 && x < r.right + 2 && y > r.top - 2 && y < r.bottom + 2;
      if (!near && is_cloth_red(image.pixel(x, y))) ++outside_red;
    }
  EXPECT_EQ(outside_red, 0);
}

TEST(FrameRenderer, WireframeDrawsLinesWhereShadedFillsTheFlag) {
  const Image shaded = draw(Style::kShaded, straight_on());
  const Image wire = draw(Style::kWireframe, straight_on());
  const auto dark = [](const std::uint8_t* p) { return p[0] + p[1] + p[2] < 150; };
  EXPECT_EQ(fraction_inside(shaded, 2.0, dark), 0.0);
  EXPECT_EQ(fraction_inside(wire, 2.0, is_cloth_red), 0.0);
  // 13 + 9 one-pixel lines across a ~140 x 95 px region: a tenth to a third of it.
  const double lines = fraction_inside(wire, 0.0, dark);
  EXPECT_GT(lines, 0.1);
  EXPECT_LT(lines, 0.35);
}

TEST(FrameRenderer, AFineLatticeIsDrawnWithFewerLinesNotAsABlob) {
  // 129 x 193 nodes over ~140 px: every line would paint the whole flag.
  const Lattice lattice = Lattice::rectangle(129, 193, 1.5, 1.0, Vec3(0.0, 2.0, 0.0));
  const std::vector<Vec3> x = lattice.rest_positions();
  const auto context = make_osmesa_context(kWidth, kHeight);
  RenderOptions options;
  options.style = Style::kWireframe;
  options.camera = straight_on();
  FrameRenderer renderer(*context, options);
  const Image image = renderer.render({lattice.rows, lattice.cols, x, std::nullopt, {}});
  const double lines =
      fraction_inside(image, 0.0, [](const std::uint8_t* p) { return p[0] + p[1] + p[2] < 150; });
  EXPECT_GT(lines, 0.1);
  EXPECT_LT(lines, 0.5);
}

TEST(FrameRenderer, TexturedShowsTheTexturesColours) {
  Image texture(64, 64);  // quadrants: red, green / blue, yellow
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      std::uint8_t* p = texture.pixel(x, y);
      const bool right = x >= 32, low = y >= 32;
      p[0] = (!right && !low) || (right && low) ? 230 : 10;
      p[1] = (right && !low) || (right && low) ? 230 : 10;
      p[2] = !right && low ? 230 : 10;
    }
  const Image image = draw(Style::kTextured, straight_on(), texture);
  const Region r = flag_region();
  const double cx[2] = {r.left + 0.25 * (r.right - r.left), r.left + 0.75 * (r.right - r.left)};
  const double cy[2] = {r.top + 0.25 * (r.bottom - r.top), r.top + 0.75 * (r.bottom - r.top)};
  const auto at = [&](int i, int j) { return image.pixel(int(cx[i]), int(cy[j])); };
  const std::uint8_t *red = at(0, 0), *green = at(1, 0), *blue = at(0, 1), *yellow = at(1, 1);
  EXPECT_GT(red[0], 3 * red[1]);
  EXPECT_GT(green[1], 3 * green[0]);
  EXPECT_GT(blue[2], 3 * blue[0]);
  EXPECT_GT(yellow[0], 3 * yellow[2]);
  EXPECT_GT(yellow[1], 3 * yellow[2]);
}

TEST(FrameRenderer, TheBackOfTheFlagIsLitToo) {
  const Image front = draw(Style::kShaded, straight_on(4.0));
  const Image back = draw(Style::kShaded, straight_on(-4.0));
  const auto brightness = [](const Image& image) {
    double sum = 0.0;
    fraction_inside(image, 3.0, [&](const std::uint8_t* p) {
      sum += p[0];
      return true;
    });
    return sum;
  };
  EXPECT_EQ(fraction_inside(back, 3.0, is_cloth_red), 1.0);
  EXPECT_GT(brightness(back), 0.5 * brightness(front));
}

TEST(FrameRenderer, TheSameFrameRendersToTheSameBytes) {
  test::TempDir dir;
  for (Style style : {Style::kWireframe, Style::kShaded, Style::kTextured}) {
    const Image a = draw(style, straight_on()), b = draw(style, straight_on());
    EXPECT_EQ(a.rgb, b.rgb) << to_string(style);
    write_png(dir.file("a.png"), a);
    write_png(dir.file("b.png"), b);
    auto bytes = [](const std::string& path) {
      std::ifstream in(path, std::ios::binary);
      return std::vector<char>(std::istreambuf_iterator<char>(in), {});
    };
    EXPECT_EQ(bytes(dir.file("a.png")), bytes(dir.file("b.png"))) << to_string(style);
    EXPECT_EQ(read_png(dir.file("a.png")).rgb, a.rgb);  // and the PNG holds the image
  }
}

TEST(FrameRenderer, StylesParseAndPrint) {
  for (Style style : {Style::kWireframe, Style::kShaded, Style::kTextured})
    EXPECT_EQ(parse_style(to_string(style)), style);
  EXPECT_FALSE(parse_style("sketch"));
}

TEST(RampColor, DarkToBrightAndClamped) {
  // Luminance (Rec. 709) rises along the ramp: a value reads as brightness too.
  double last = -1.0;
  for (int i = 0; i <= 20; ++i) {
    const std::array<float, 3> c = ramp_color(i / 20.0);
    const double luminance = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
    EXPECT_GT(luminance, last) << i;
    last = luminance;
  }
  EXPECT_EQ(ramp_color(-3.0), ramp_color(0.0));
  EXPECT_EQ(ramp_color(7.0), ramp_color(1.0));
  EXPECT_EQ(ramp_color(std::nan("")), ramp_color(0.0));
}

}  // namespace
}  // namespace flagsim::render
