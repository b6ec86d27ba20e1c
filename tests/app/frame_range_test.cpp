// frame_range.cpp: --frames A:B read as a Python slice, checked against the file.
#include "frame_range.hpp"

#include <gtest/gtest.h>

#include <string>
#include <utility>

#include "flagsim/core/errors.hpp"

namespace flagsim::app {
namespace {

std::string error_of(const std::string& text) {
  try {
    parse_frame_range(text);
  } catch (const UserError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no UserError for " << text;
  return "";
}

TEST(FrameRange, ASliceWithEitherEndLeftOut) {
  EXPECT_EQ(parse_frame_range("0:30"), std::make_pair(0, 30));
  EXPECT_EQ(parse_frame_range("10:"), std::make_pair(10, kToEnd));
  EXPECT_EQ(parse_frame_range(":20"), std::make_pair(0, 20));
  EXPECT_EQ(parse_frame_range(" 3 : 4 "), std::make_pair(3, 4));
  EXPECT_EQ(parse_frame_range(":"), kAllFrames);
}

TEST(FrameRange, OneFrameAndCountsFromTheEndAsPythonReadsThem) {
  EXPECT_EQ(parse_frame_range("100"), std::make_pair(100, 101));   // a[100]
  EXPECT_EQ(parse_frame_range("-1"), std::make_pair(-1, kToEnd));  // a[-1]: the last
  EXPECT_EQ(parse_frame_range("-3"), std::make_pair(-3, -2));
  EXPECT_EQ(parse_frame_range("-10:"), std::make_pair(-10, kToEnd));
  EXPECT_EQ(parse_frame_range(":-1"), std::make_pair(0, -1));   // all but the last
  EXPECT_EQ(parse_frame_range("-1:3"), std::make_pair(-1, 3));  // empty or not: the file says
}

TEST(FrameRange, AnythingElseNamesTheFlagAsTyped) {
  EXPECT_EQ(error_of("five"),
            "--frames five: expected N (one frame; -1 the last) or A:B (frames A to B - 1, e.g. "
            "0:30, 10:, :20, -10:)");
  EXPECT_TRUE(error_of("1:2:3").starts_with("--frames 1:2:3: expected")) << error_of("1:2:3");
  EXPECT_TRUE(error_of("--1").starts_with("--frames --1: expected")) << error_of("--1");
  EXPECT_EQ(error_of("7:7"), "--frames 7:7: the range is empty (B must be more than A)");
  EXPECT_TRUE(error_of("9:2").starts_with("--frames 9:2: the range is empty"));
  EXPECT_TRUE(error_of("-2:-5").starts_with("--frames -2:-5: the range is empty"));
}

std::string resolve_error(std::pair<int, int> range, int frames) {
  try {
    resolve_frame_range(range, frames, "run.h5");
  } catch (const UserError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no UserError";
  return "";
}

TEST(FrameRange, ResolvedAgainstTheFileItReads) {
  EXPECT_EQ(resolve_frame_range({10, kToEnd}, 31, "run.h5"), std::make_pair(10, 31));
  EXPECT_EQ(resolve_frame_range({0, 31}, 31, "run.h5"), std::make_pair(0, 31));
  EXPECT_EQ(resolve_frame_range(parse_frame_range("-1"), 31, "run.h5"), std::make_pair(30, 31));
  EXPECT_EQ(resolve_frame_range(parse_frame_range("-10:"), 31, "run.h5"), std::make_pair(21, 31));
  EXPECT_EQ(resolve_frame_range(parse_frame_range(":-1"), 31, "run.h5"), std::make_pair(0, 30));
  EXPECT_EQ(resolve_frame_range(parse_frame_range("-1:31"), 31, "run.h5"), std::make_pair(30, 31));
  EXPECT_EQ(resolve_error({0, 40}, 31), "--frames 0:40: run.h5 has frames 0 to 30");
  EXPECT_EQ(resolve_error({31, 32}, 31), "--frames 31: run.h5 has frames 0 to 30");
  EXPECT_EQ(resolve_error({-40, kToEnd}, 31), "--frames -40:: run.h5 has frames 0 to 30");
  EXPECT_EQ(resolve_error({-1, 3}, 31),
            "--frames -1:3: run.h5 has frames 0 to 30 (the range holds none)");
}

}  // namespace
}  // namespace flagsim::app
