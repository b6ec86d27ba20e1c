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
  EXPECT_EQ(parse_frame_range("10:"), std::make_pair(10, -1));
  EXPECT_EQ(parse_frame_range(":20"), std::make_pair(0, 20));
  EXPECT_EQ(parse_frame_range(" 3 : 4 "), std::make_pair(3, 4));
  EXPECT_EQ(parse_frame_range(":"), std::make_pair(0, -1));
}

TEST(FrameRange, AnythingElseNamesTheFlagAsTyped) {
  EXPECT_EQ(error_of("5"), "--frames 5: expected A:B (frames A to B - 1, e.g. 0:30, 10:, :20)");
  EXPECT_TRUE(error_of("-1:3").starts_with("--frames -1:3: expected A:B")) << error_of("-1:3");
  EXPECT_TRUE(error_of("1:2:3").starts_with("--frames 1:2:3: expected")) << error_of("1:2:3");
  EXPECT_EQ(error_of("7:7"), "--frames 7:7: the range is empty (B must be more than A)");
  EXPECT_TRUE(error_of("9:2").starts_with("--frames 9:2: the range is empty"));
}

TEST(FrameRange, ResolvedAgainstTheFileItReads) {
  EXPECT_EQ(resolve_frame_range({10, -1}, 31, "run.h5"), std::make_pair(10, 31));
  EXPECT_EQ(resolve_frame_range({0, 31}, 31, "run.h5"), std::make_pair(0, 31));
  try {
    resolve_frame_range({0, 40}, 31, "run.h5");
    ADD_FAILURE() << "no UserError";
  } catch (const UserError& e) {
    EXPECT_EQ(std::string(e.what()), "--frames 0:40: run.h5 has frames 0 to 30");
  }
  EXPECT_THROW(resolve_frame_range({31, -1}, 31, "run.h5"), UserError);
}

}  // namespace
}  // namespace flagsim::app
