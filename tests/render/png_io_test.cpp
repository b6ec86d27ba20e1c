#include "flagsim/render/png_io.hpp"

#include <gtest/gtest.h>

#include <string>

#include "flagsim/core/errors.hpp"
#include "temp_dir.hpp"

namespace flagsim::render {
namespace {

Image gradient(int width, int height) {
  Image image(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      std::uint8_t* p = image.pixel(x, y);
      p[0] = std::uint8_t(x * 255 / (width - 1));
      p[1] = std::uint8_t(y * 255 / (height - 1));
      p[2] = std::uint8_t((x + y) % 256);
    }
  return image;
}

TEST(PngIo, ReadsBackWhatItWrote) {
  test::TempDir dir;
  const Image image = gradient(17, 9);
  write_png(dir.file("a.png"), image);
  const Image back = read_png(dir.file("a.png"));
  EXPECT_EQ(back.width, 17);
  EXPECT_EQ(back.height, 9);
  EXPECT_EQ(back.rgb, image.rgb);
}

TEST(PngIo, TheSameImageGivesTheSameBytes) {
  test::TempDir dir;
  const Image image = gradient(32, 20);
  write_png(dir.file("a.png"), image);
  write_png(dir.file("b.png"), image);
  const std::string a = test::file_bytes(dir.file("a.png"));
  EXPECT_EQ(a.substr(1, 3), "PNG");
  EXPECT_EQ(a, test::file_bytes(dir.file("b.png")));
}

TEST(PngIo, AMissingOrForeignFileIsTheUsersMistakeAndNamesTheFile) {
  test::TempDir dir;
  const std::string missing = dir.file("missing.png"), text = dir.write("text.png", "not a png");
  for (const std::string& path : {missing, text}) {
    try {
      read_png(path);
      ADD_FAILURE() << path << " was read";
    } catch (const UserError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
  }
}

TEST(PngIo, AFileThatCannotBeWrittenIsAnIoError) {
  test::TempDir dir;
  EXPECT_THROW(write_png(dir.file("no/such/dir/a.png"), gradient(4, 4)), IoError);
}

}  // namespace
}  // namespace flagsim::render
