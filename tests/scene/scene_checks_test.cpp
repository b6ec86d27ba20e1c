// scene_checks.cpp, through parse_scene (the checks run once every key has
// been read): what a check leaves in the Scene, beside the messages that
// tests/app/cli_errors_test.cpp checks end to end.
#include "scene_checks.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "flagsim/core/errors.hpp"
#include "flagsim/scene/scene_parser.hpp"

namespace flagsim::detail {
namespace {

std::string error_of(const std::string& text, const std::vector<std::string>& sets = {}) {
  try {
    parse_scene(text, "s.toml", sets);
  } catch (const UserError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no UserError for\n" << text;
  return "";
}

constexpr const char* kHybrid = R"([scene]
mode = "hybrid"
[flag]
size = [1.5, 1.0]
fine = [33, 49]
coarse = [9, 13]
)";

TEST(SceneChecks, ACoarseLatticeThatDoesNotDivideTheFineOneListsTheSizesThatDo) {
  const std::string message = error_of(kHybrid, {"flag.coarse=[9,14]"});
  EXPECT_TRUE(
      message.starts_with("--set flag.coarse=[9,14]: flag.coarse: [9, 14] does not "
                          "divide flag.fine = [33, 49]"))
      << message;
  EXPECT_NE(message.find("coarse columns that work: 2, 3, 4, 5, 7, 9, 13, 17, 25, 49"),
            std::string::npos)
      << message;
}

TEST(SceneChecks, TablesTheFileModeDoesNotUseAreAnErrorAtTheirLine) {
  const std::string text = std::string(kHybrid) +
                           "[[keyframe]]\ntime = 0.0\n"
                           "corners = [[0.0, 2.0, 0.0], [1.5, 2.0, 0.0], [0.0, 1.0, 0.0], "
                           "[1.5, 1.0, 0.0]]\n";
  const std::string message = error_of(text);
  EXPECT_TRUE(message.starts_with("s.toml:7:")) << message;
  EXPECT_NE(message.find("[[keyframe]] drives the corners in infill mode only"), std::string::npos)
      << message;
}

TEST(SceneChecks, WithTheModeFromTheCommandLineTheyAreDroppedAndNamedInOneNote) {
  const std::string text = std::string(kHybrid) + "[infill]\nsolver = \"paper\"\n" +
                           "[wrinkles]\nfiber_modulus = 1e9\nfiber_radius = 0.001\n";
  const Scene hybrid = parse_scene(text, "s.toml");
  EXPECT_TRUE(hybrid.infill.has_value());
  EXPECT_TRUE(hybrid.wrinkles.has_value());
  EXPECT_TRUE(hybrid.notes.empty());
  const Scene full = parse_scene(text, "s.toml", std::vector<std::string>{"scene.mode=\"xpbd\""});
  EXPECT_EQ(full.mode, Mode::kXpbd);
  EXPECT_FALSE(full.infill.has_value());
  EXPECT_FALSE(full.wrinkles.has_value());
  ASSERT_EQ(full.notes.size(), 1u);
  EXPECT_EQ(full.notes[0], "note: xpbd mode does not use [infill], [wrinkles]: ignored");
}

TEST(SceneChecks, InfillModeDropsThePhysicsTablesTheCommandLineBroughtIn) {
  const std::string text = std::string(kHybrid) +
                           "[wind]\nvelocity = [10.0, 0.0, 0.0]\n[gravity]\n"
                           "[[keyframe]]\ntime = 0.0\n"
                           "corners = [[0.0, 2.0, 0.0], [1.5, 2.0, 0.0], [0.0, 1.0, 0.0], "
                           "[1.5, 1.0, 0.0]]\n";
  const Scene infill = parse_scene(
      text, "s.toml", std::vector<std::string>{"scene.mode=\"infill\"", "flag.coarse=[2,2]"});
  EXPECT_FALSE(infill.wind.has_value());
  EXPECT_FALSE(infill.gravity.has_value());
  EXPECT_EQ(infill.keyframes.size(), 1u);
  ASSERT_EQ(infill.notes.size(), 1u);
  EXPECT_EQ(infill.notes[0], "note: infill mode does not use [wind], [gravity]: ignored");
}

TEST(SceneChecks, AHybridWithoutACoarseLatticeAndAPoleWithoutPinsAreRefused) {
  const std::string no_coarse =
      error_of("[scene]\nmode = \"hybrid\"\n[flag]\nsize = [1.5, 1.0]\nfine = [33, 49]\n");
  EXPECT_NE(no_coarse.find("scene.mode: hybrid mode needs flag.coarse"), std::string::npos)
      << no_coarse;
  const std::string pole =
      error_of(std::string(kHybrid) + "pin = \"none\"\n[pole]\namplitude = 0.1\n");
  EXPECT_TRUE(pole.starts_with("s.toml:8:")) << pole;
  EXPECT_NE(pole.find("pole: a moving pole needs pinned nodes"), std::string::npos) << pole;
}

TEST(SceneChecks, TheVortexAirNeedsTheSpringDamperIntegratorAndAWindAlongTheFlag) {
  const std::string wind =
      std::string(kHybrid) + "[wind]\nvelocity = [10.0, 0.0, 0.0]\nmodel = \"vortex\"\n";
  EXPECT_EQ(parse_scene(wind, "s.toml").wind->model, AirModel::kVortex);
  const std::string xpbd = error_of(wind, {"scene.mode=\"xpbd\""});
  EXPECT_TRUE(xpbd.starts_with("s.toml:9:")) << xpbd;
  EXPECT_NE(xpbd.find("wind.model: \"vortex\" needs the spring-damper integrator"),
            std::string::npos)
      << xpbd;
  EXPECT_NE(xpbd.find("xpbd mode solves without the air's added mass"), std::string::npos) << xpbd;
  const std::string bullet = error_of(wind, {"solver.backend=\"bullet\""});
  EXPECT_NE(bullet.find("hybrid mode with the bullet backend"), std::string::npos) << bullet;
  const std::string across = error_of(wind, {"wind.velocity=[0.0, 0.0, 5.0]"});
  EXPECT_NE(across.find("wind.velocity: wind.model = \"vortex\" needs a wind along the flag"),
            std::string::npos)
      << across;
  const std::string typo = error_of(wind, {"wind.model=\"vortx\""});
  EXPECT_NE(typo.find("wind.model"), std::string::npos) << typo;
}

}  // namespace
}  // namespace flagsim::detail
