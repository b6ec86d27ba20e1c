#include "toml_reader.hpp"

#include <gtest/gtest.h>

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "flagsim/core/errors.hpp"

namespace flagsim::detail {
namespace {

// The message of the UserError `read` throws; "" (and a test failure) when it throws none.
template <typename Read>
std::string error_of(Read&& read) {
  try {
    read();
  } catch (const UserError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no UserError";
  return "";
}

// s.toml: a [flag] table at line 1, its keys on lines 2.. .
toml::table parse(std::string_view body) {
  const std::string text = "[flag]\n" + std::string(body);
  return toml::parse(std::string_view(text), std::string_view("s.toml"));
}

TEST(TomlReader, ABoundSaysWhichEndsItIncludes) {
  EXPECT_TRUE(Bound::non_negative().contains(0.0));
  EXPECT_FALSE(Bound::positive().contains(0.0));
  EXPECT_TRUE(Bound::positive().contains(1e-300));
  EXPECT_TRUE(Bound::between(1.0, 2.0).contains(2.0));
  EXPECT_FALSE(Bound::between(1.0, 2.0).contains(2.0 + 1e-12));
  EXPECT_NE(Bound::positive().describe(), Bound::non_negative().describe());
}

TEST(TomlReader, ANumberReadsItsValueOrTheFallbackWhenAbsent) {
  const toml::table root = parse("damping = 0.25\nrows = 7\n");
  TableReader flag(*root["flag"].as_table(), "flag", "s.toml");
  EXPECT_EQ(flag.real("damping", 9.0, Bound::non_negative(), "1/s"), 0.25);
  EXPECT_EQ(flag.real("absent", 9.0, Bound::non_negative(), "1/s"), 9.0);
  EXPECT_FALSE(flag.optional_real("absent", Bound::any(), "m").has_value());
  EXPECT_EQ(flag.integer("rows", 2, 2, 100), 7);
  EXPECT_EQ(flag.key_name("damping"), "flag.damping");
}

TEST(TomlReader, AValueOutsideItsBoundNamesFileLineColumnAndDottedKey) {
  const toml::table root = parse("size = [1.5, 1.0]\ndamping = -1.0\nrows = 1\n");
  TableReader flag(*root["flag"].as_table(), "flag", "s.toml");
  const std::string damping =
      error_of([&] { flag.real("damping", 0.0, Bound::non_negative(), "1/s"); });
  EXPECT_TRUE(damping.starts_with("s.toml:3:")) << damping;
  EXPECT_NE(damping.find("flag.damping: expected"), std::string::npos) << damping;
  EXPECT_NE(damping.find("got -1"), std::string::npos) << damping;
  const std::string rows = error_of([&] { flag.integer("rows", 2, 2, 100); });
  EXPECT_TRUE(rows.starts_with("s.toml:4:")) << rows;
  EXPECT_NE(rows.find("flag.rows"), std::string::npos) << rows;
  // A number where a string belongs, a string where a number does.
  const std::string wrong_type = error_of([&] { flag.string("damping", ""); });
  EXPECT_NE(wrong_type.find("expected a string"), std::string::npos) << wrong_type;
  const std::string pair =
      error_of([&] { flag.int_pair("size", 2, 100, "[J, K] nodes"); });  // reals, not integers
  EXPECT_TRUE(pair.starts_with("s.toml:2:")) << pair;
}

TEST(TomlReader, AChoiceOutsideItsListSuggestsTheClosest) {
  const toml::table root = parse("pin = \"lefft\"\n");
  TableReader flag(*root["flag"].as_table(), "flag", "s.toml");
  const std::string message = error_of([&] {
    flag.choice("pin", "left", {"left", "right", "top"});
  });
  EXPECT_TRUE(message.starts_with("s.toml:2:")) << message;
  EXPECT_NE(message.find("\"lefft\""), std::string::npos) << message;
  EXPECT_NE(message.find("left"), std::string::npos) << message;
}

TEST(TomlReader, AVectorMustBeThreeFiniteNumbersWithinItsBound) {
  const toml::table root =
      parse("origin = [0.0, 2.0, 0.0]\nshort = [1.0, 2.0]\nhuge = [1e9, 0.0, 0.0]\n");
  TableReader flag(*root["flag"].as_table(), "flag", "s.toml");
  EXPECT_EQ(flag.vec3("origin", Vec3::Zero(), "m"), Vec3(0.0, 2.0, 0.0));
  EXPECT_EQ(flag.vec3("absent", Vec3(1.0, 2.0, 3.0), "m"), Vec3(1.0, 2.0, 3.0));
  EXPECT_TRUE(error_of([&] { flag.vec3("short", Vec3::Zero(), "m"); }).starts_with("s.toml:3:"));
  EXPECT_TRUE(
      error_of([&] { flag.vec3("huge", Vec3::Zero(), "m", 1e3); }).starts_with("s.toml:4:"));
}

TEST(TomlReader, AKeyNoReadAskedForIsUnknownWithASuggestion) {
  const toml::table root = parse("damping = 0.1\ndampin = 0.2\n");
  TableReader flag(*root["flag"].as_table(), "flag", "s.toml");
  flag.real("damping", 0.0, Bound::non_negative(), "1/s");
  const std::string message = error_of([&] { flag.finish(); });
  EXPECT_TRUE(message.starts_with("s.toml:3:")) << message;
  EXPECT_NE(message.find("unknown key 'flag.dampin'"), std::string::npos) << message;
  EXPECT_NE(message.find("flag.damping"), std::string::npos) << message;  // the suggestion
  // Allowed keys are known without being read.
  TableReader allowed(*root["flag"].as_table(), "flag", "s.toml");
  allowed.allow("damping");
  allowed.allow("dampin");
  allowed.finish();
}

TEST(TomlReader, AnOverriddenKeyIsNamedByTheOverrideAsTyped) {
  const toml::table root = parse("damping = -1.0\n");
  const OverrideLabels labels(std::vector<std::pair<std::string, std::string>>{
      {"flag.damping", "--set flag.damping=-1.0"}});
  TableReader flag(*root["flag"].as_table(), "flag", "s.toml");
  const std::string message =
      error_of([&] { flag.real("damping", 0.0, Bound::non_negative(), "1/s"); });
  EXPECT_TRUE(message.starts_with("--set flag.damping=-1.0: flag.damping")) << message;
}

}  // namespace
}  // namespace flagsim::detail
