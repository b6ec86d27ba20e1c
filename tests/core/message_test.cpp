#include "flagsim/core/message.hpp"

#include <gtest/gtest.h>

#include <string>

#include "flagsim/core/limits.hpp"

namespace flagsim {
namespace {

// "rendered 1 frames", "1 substeps/frame" (issue 33): singular only for one.
TEST(Message, CountedIsSingularForOneOnly) {
  EXPECT_EQ(counted(1, "frame"), "1 frame");
  EXPECT_EQ(counted(0, "frame"), "0 frames");
  EXPECT_EQ(counted(251, "substep"), "251 substeps");
  EXPECT_EQ(counted(-1, "frame"), "-1 frames");
}

TEST(Message, PrintableEscapesControlCharactersAndCuts) {
  EXPECT_EQ(printable("flag.fine"), "flag.fine");
  EXPECT_EQ(printable(std::string("a\tb\x1b[31m", 8)), "a\\x09b\\x1b[31m");
  EXPECT_EQ(printable(std::string(100, 'x'), 10), std::string(10, 'x') + "...");
  EXPECT_EQ(printable(std::string(10, 'x'), 10), std::string(10, 'x'));  // at the limit: whole
}

TEST(Message, OneLineJoinsLinesWithOneSpaceAndIsCutAtTheLimit) {
  EXPECT_EQ(one_line("first\n    second\r\nthird"), "first second third");
  EXPECT_EQ(one_line("bell\a"), "bell\\x07");
  const std::string cut = one_line(std::string(5000, 'y'));
  EXPECT_EQ(cut.size(), limits::kMessageBytes + 3);
  EXPECT_EQ(cut.substr(cut.size() - 3), "...");
  EXPECT_EQ(cut.find('\n'), std::string::npos);
}

}  // namespace
}  // namespace flagsim
