#include "flagsim/scene/scene_parser.hpp"

#include <gtest/gtest.h>

#include "flagsim/core/errors.hpp"

namespace flagsim {
namespace {

// The message of the UserError that parsing `text` throws ("" if none).
std::string error_of(const std::string& text, std::vector<std::string> overrides = {}) {
  try {
    parse_scene(text, "s.toml", overrides);
  } catch (const UserError& e) {
    return e.what();
  }
  return "";
}

constexpr const char* kMinimal = R"(
[scene]
mode = "mass-spring"
[flag]
size = [1.5, 1.0]
fine = [9, 13]
)";

TEST(SceneParser, DefaultSceneIsValidAndMeansWhatItSays) {
  const Scene scene = parse_scene(default_scene_toml(), kDefaultSceneName);
  EXPECT_EQ(scene.name, "default");
  EXPECT_EQ(scene.mode, Mode::kHybrid);
  EXPECT_EQ(scene.flag.fine_rows, 129);
  EXPECT_EQ(scene.flag.fine_cols, 193);
  EXPECT_EQ(*scene.flag.coarse, (std::array<int, 2>{9, 13}));
  EXPECT_DOUBLE_EQ(scene.flag.width_m, 1.5);
  EXPECT_DOUBLE_EQ(scene.flag.height_m, 1.0);
  EXPECT_EQ(scene.flag.pin, PinSet::kLeft);
  ASSERT_TRUE(scene.wind && scene.gravity);
  EXPECT_DOUBLE_EQ(scene.wind->velocity_m_s.x(), 10.0);
  ASSERT_TRUE(scene.flag.coarse.has_value());
  EXPECT_EQ(scene.output.file, "out/default.h5");
  // Contract: a 1.5 m flag in 10 m/s wind pulls ~90 N/m; the default cloth
  // must stretch under 1% at that load.
  EXPECT_GE(scene.flag.stretch_modulus_n_m, 1.0e4);
}

TEST(SceneParser, DefaultsAndOptionalEffects) {
  const Scene scene = parse_scene(kMinimal, "s.toml");
  EXPECT_EQ(scene.name, "s");  // file stem
  EXPECT_FALSE(scene.wind.has_value());
  EXPECT_FALSE(scene.gravity.has_value());
  EXPECT_FALSE(scene.bending.has_value());
  EXPECT_EQ(scene.simulated_frames(), 301);  // 10 s at 30 fps, plus t = 0
}

TEST(SceneParser, LiftAtThePoleIsOffUnlessSaidAndABoolean) {
  const std::string wind = std::string(kMinimal) + "[wind]\nvelocity = [10, 0, 0]\n";
  EXPECT_FALSE(parse_scene(wind, "s.toml").wind->lift_at_pole);
  EXPECT_TRUE(parse_scene(wind + "lift_at_pole = true\n", "s.toml").wind->lift_at_pole);
  EXPECT_TRUE(parse_scene(wind, "s.toml", std::vector<std::string>{"wind.lift_at_pole=true"})
                  .wind->lift_at_pole);
  EXPECT_NE(error_of(wind + "lift_at_pole = 1\n").find("wind.lift_at_pole"), std::string::npos);
}

TEST(SceneParser, ATableWithoutKeysIsItsStructsDefaults) {
  // Every key's default lives in scene.hpp's initializers; the parser reads
  // them there. (Before, [pole] gave 0.1 m at 1 Hz while PoleMotion{} said 0
  // at 0 Hz, and the same for the gusts, turbulence, bending and wrinkles.)
  const Scene scene = parse_scene(
      "[scene]\nmode = \"hybrid\"\n[flag]\nfine = [9, 13]\ncoarse = [5, 7]\n[pole]\n"
      "[bending]\n[wind]\n[wind.gusts]\n[wind.turbulence]\n[wrinkles]\n[solver]\n[output]\n"
      "[render]\n",
      "s.toml");
  const Scene defaults;
  EXPECT_EQ(scene.fps, defaults.fps);
  EXPECT_EQ(scene.duration_s, defaults.duration_s);
  EXPECT_EQ(scene.seed, defaults.seed);
  EXPECT_EQ(scene.flag.pin, defaults.flag.pin);
  EXPECT_EQ(scene.flag.initial_perturbation_m, defaults.flag.initial_perturbation_m);
  EXPECT_EQ(scene.flag.shear_modulus_n_m, defaults.flag.shear_modulus_n_m);  // stretch / 10
  ASSERT_TRUE(scene.pole && scene.bending && scene.wind && scene.wrinkles && scene.render);
  const PoleMotion pole;
  EXPECT_EQ(scene.pole->axis_unit, pole.axis_unit);
  EXPECT_EQ(scene.pole->amplitude_m, pole.amplitude_m);
  EXPECT_EQ(scene.pole->frequency_hz, pole.frequency_hz);
  EXPECT_EQ(scene.bending->rigidity_j, Bending{}.rigidity_j);
  ASSERT_TRUE(scene.wind->gusts && scene.wind->turbulence);
  EXPECT_EQ(scene.wind->gusts->amplitude, Gusts{}.amplitude);
  EXPECT_EQ(scene.wind->gusts->period_s, Gusts{}.period_s);
  EXPECT_EQ(scene.wind->turbulence->intensity, Turbulence{}.intensity);
  EXPECT_EQ(scene.wind->turbulence->length_scale_m, Turbulence{}.length_scale_m);
  EXPECT_EQ(scene.wind->drag, Wind{}.drag);
  // No yarn stated: [wrinkles] takes the paper's (material_test.cpp).
  EXPECT_FALSE(scene.wrinkles->fiber_radius_m || scene.wrinkles->fiber_modulus_pa);
  EXPECT_EQ(scene.solver.backend, defaults.solver.backend);
  EXPECT_EQ(scene.solver.substeps, defaults.solver.substeps);
  EXPECT_EQ(scene.output.every, defaults.output.every);
  EXPECT_EQ(scene.output.flush_every, defaults.output.flush_every);
  EXPECT_EQ(scene.output.fields, defaults.output.fields);
  EXPECT_EQ(scene.render->style, Render{}.style);
  EXPECT_EQ(scene.render->size_px, Render{}.size_px);
}

TEST(SceneParser, ZeroGravityIsNoGravity) {
  const Scene scene =
      parse_scene(std::string(kMinimal) + "[gravity]\nacceleration = [0, 0, 0]\n", "s.toml");
  EXPECT_FALSE(scene.gravity.has_value());
}

TEST(SceneParser, OverridesAreCheckedLikeTheFile) {
  const std::vector<std::string> sets = {"flag.fine=[17, 25]", "wind.velocity=[5,0,0]",
                                         "scene.name=windy"};
  const Scene scene = parse_scene(kMinimal, "s.toml", sets);
  EXPECT_EQ(scene.flag.fine_rows, 17);
  EXPECT_EQ(scene.flag.fine_cols, 25);
  ASSERT_TRUE(scene.wind.has_value());  // --set can add an effect table
  EXPECT_EQ(scene.name, "windy");       // a bare word is taken as a string
  EXPECT_NE(scene.toml_text.find("fine = [ 17, 25 ]"), std::string::npos) << scene.toml_text;
  EXPECT_EQ(error_of(kMinimal, {"flag.fine=[1, 25]"}),
            "--set flag.fine=[1, 25]: flag.fine: expected [J, K] nodes, two integers in [2, 8193], "
            "got [1, 25]");
  EXPECT_NE(error_of(kMinimal, {"flag.fine"}).find("expected KEY=VALUE"), std::string::npos);
}

TEST(SceneParser, FramesKeyFixesTheDuration) {
  const Scene scene = parse_scene(kMinimal, "s.toml", std::vector<std::string>{"scene.frames=7"});
  EXPECT_EQ(scene.simulated_frames(), 7);
}

TEST(SceneParser, ErrorsNameFileLineColumnAndKey) {
  EXPECT_EQ(error_of(std::string(kMinimal) + "[wind]\nvelocity = [10, 0]\n"),
            "s.toml:8:12: wind.velocity: expected an array of 3 finite numbers [x, y, z] in m/s, "
            "got [10, 0]");
  EXPECT_EQ(error_of(std::string(kMinimal) + "areal_densty = 0.2\n"),
            "s.toml:7:1: unknown key 'flag.areal_densty' (did you mean 'flag.areal_density'?)");
}

TEST(SceneParser, TheDirectSolveIsRefusedWhereTheWindCouplesFartherThanItProbes) {
  // Cholesky probes the step's matrix over two-link neighbourhoods; on a
  // cloth finer than the air's panels the wind couples farther than that.
  std::string implicit_scene = kMinimal;
  implicit_scene.replace(implicit_scene.find("mass-spring"), 11, "implicit");
  const std::string cholesky = "[solver]\nlinear = \"cholesky\"\n";
  const std::string wind = "[wind]\nvelocity = [10, 0, 0]\n";
  // 9 x 13 on 1.5 x 1.0 m: 0.125 m cells, finer than the default 0.25 m panels.
  EXPECT_EQ(error_of(implicit_scene + cholesky + wind),
            "s.toml:8:10: solver.linear: \"cholesky\" assembles the step's matrix from each "
            "node's two-link neighbourhood, and the wind seen on panels of wind.panel = 0.25 m "
            "couples the 9 x 13 cloth's nodes farther apart than that; use \"cg\", or a "
            "wind.panel no larger than the cloth's cells (0.125 m)");
  EXPECT_EQ(error_of(implicit_scene + cholesky + wind + "panel = 0.125\n"), "");
  EXPECT_EQ(error_of(implicit_scene + wind), "");  // the conjugate gradient
}

TEST(SceneParser, LinearSolverOnlyWithTheImplicitBackend) {
  const std::string cholesky = "[solver]\nlinear = \"cholesky\"\n";
  const std::string message = error_of(std::string(kMinimal) + cholesky);
  EXPECT_NE(message.find("s.toml:8:10: solver.linear: the spring-damper backend has no linear "
                         "solve"),
            std::string::npos)
      << message;
  std::string implicit_scene = kMinimal;
  implicit_scene.replace(implicit_scene.find("mass-spring"), 11, "implicit");
  EXPECT_EQ(error_of(implicit_scene + cholesky), "");
  EXPECT_EQ(parse_scene(implicit_scene + cholesky, "s.toml").solver.linear,
            LinearSolver::kCholesky);
  // The mode chosen on the command line: named in a note, not refused.
  const Scene scene = parse_scene(implicit_scene + cholesky, "s.toml",
                                  std::vector<std::string>{"scene.mode=\"xpbd\""});
  ASSERT_EQ(scene.notes.size(), 1u);
  EXPECT_EQ(scene.notes[0], "note: xpbd mode does not use solver.linear: ignored");
}

TEST(SceneParser, StepStrainChangeOnlyWithTheImplicitBackendAndPositive) {
  const std::string key = "[solver]\nmax_step_strain_change = 0.02\n";
  const std::string message = error_of(std::string(kMinimal) + key);
  EXPECT_NE(message.find("s.toml:8:26: solver.max_step_strain_change: the spring-damper backend "
                         "does not halve its steps"),
            std::string::npos)
      << message;
  std::string implicit_scene = kMinimal;
  implicit_scene.replace(implicit_scene.find("mass-spring"), 11, "implicit");
  EXPECT_EQ(parse_scene(implicit_scene, "s.toml").solver.max_step_strain_change, 0.05);
  EXPECT_EQ(parse_scene(implicit_scene + key, "s.toml").solver.max_step_strain_change, 0.02);
  const std::string zero = error_of(implicit_scene + "[solver]\nmax_step_strain_change = 0\n");
  EXPECT_NE(zero.find("s.toml:8:26: solver.max_step_strain_change:"), std::string::npos) << zero;
}

TEST(SceneParser, WindHoldOnlyWithTheSpringDamperAndWithinItsRange) {
  EXPECT_EQ(parse_scene(kMinimal, "s.toml").solver.wind_hold, 0.1);
  EXPECT_EQ(
      parse_scene(std::string(kMinimal) + "[solver]\nwind_hold = 0\n", "s.toml").solver.wind_hold,
      0.0);
  const std::string large = error_of(std::string(kMinimal) + "[solver]\nwind_hold = 0.6\n");
  EXPECT_NE(large.find("s.toml:8:13: solver.wind_hold:"), std::string::npos) << large;
  std::string xpbd_scene = kMinimal;
  xpbd_scene.replace(xpbd_scene.find("mass-spring"), 11, "xpbd");
  const std::string message = error_of(xpbd_scene + "[solver]\nwind_hold = 0.05\n");
  EXPECT_NE(message.find("s.toml:8:13: solver.wind_hold: the xpbd backend evaluates the wind at "
                         "every step"),
            std::string::npos)
      << message;
}

TEST(SceneParser, CoarseMustDivideFineAndSaysWhatWould) {
  const std::string message = error_of(std::string(kMinimal) + "coarse = [4, 5]\n");
  EXPECT_NE(message.find("s.toml:7:10: flag.coarse"), std::string::npos) << message;
  EXPECT_NE(message.find("coarse rows that work: 2, 3, 5, 9"), std::string::npos) << message;
}

TEST(SceneParser, RenderTableIsReadAndChecked) {
  const Scene scene = parse_scene(
      std::string(kMinimal) + "[render]\nstyle = \"wireframe\"\nsize = [640, 360]\n", "s.toml");
  ASSERT_TRUE(scene.render.has_value());
  EXPECT_EQ(scene.render->style, RenderStyle::kWireframe);
  EXPECT_EQ(scene.render->size_px, (std::array<int, 2>{640, 360}));
  EXPECT_NE(error_of(std::string(kMinimal) + "[render]\nstyle = \"sketch\"\n")
                .find("render.style: expected one of \"wireframe\", \"shaded\", \"textured\""),
            std::string::npos);
}

TEST(SceneParser, OutputFieldsAreNamesFromTheirList) {
  EXPECT_EQ(parse_scene(kMinimal, "s.toml").output.fields,
            (std::vector<std::string>{"strain", "velocity"}));
  const Scene none = parse_scene(std::string(kMinimal) + "[output]\nfields = []\n", "s.toml");
  EXPECT_TRUE(none.output.fields.empty());
  EXPECT_FALSE(none.output.has_field("strain"));
  EXPECT_EQ(parse_scene(kMinimal, "s.toml", std::vector<std::string>{"output.fields=[\"strain\"]"})
                .output.fields,
            std::vector<std::string>{"strain"});
  EXPECT_NE(error_of(std::string(kMinimal) + "[output]\nfields = [\"strian\"]\n")
                .find("output.fields: expected an array of distinct names, each one of \"strain\", "
                      "\"velocity\", got \"strian\" (did you mean \"strain\"?)"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "[output]\nfields = [\"strain\", \"strain\"]\n")
                .find("\"strain\" is listed twice"),
            std::string::npos);
  EXPECT_NE(
      error_of(std::string(kMinimal) + "[output]\nfields = \"strain\"\n").find("expected an array"),
      std::string::npos);
}

// Issue 33, item 8: of two unknown keys, the one that comes first in the
// file is reported (the table keeps its keys in alphabetical order).
TEST(SceneParser, OfTwoUnknownKeysTheFirstInTheFileIsReported) {
  try {
    parse_scene("[flag]\nzebra = 1\nsize = [1.5, 1.0]\nalpha = 2\n", "s.toml");
    ADD_FAILURE() << "no error";
  } catch (const UserError& e) {
    EXPECT_TRUE(std::string(e.what()).starts_with("s.toml:2:1: unknown key 'flag.zebra'"))
        << e.what();
  }
}

TEST(SceneParser, KeyInTheWrongTableIsPointedToItsHome) {
  EXPECT_NE(error_of(std::string("pin = \"left\"\n") + kMinimal).find("did you mean 'flag.pin'?"),
            std::string::npos);
}

// Issue 32: fold lines and [creases], each mistake named with its line and key.
TEST(SceneParser, FoldLinesAndCreasesAreReadAndChecked) {
  const std::string folded = std::string(kMinimal) +
                             "folds = [{ axis = \"row\", at = 0.25, angle = 3.0 }, "
                             "{ at = 0.5, angle = 1.5 }]\n";
  const std::string creases = "[bending]\nstiffness = 1e-4\n[creases]\nset_time = 2.0\n";
  const Scene scene = parse_scene(folded + creases, "s.toml");
  ASSERT_EQ(scene.flag.folds.size(), 2u);
  EXPECT_EQ(scene.flag.folds[0].axis, FoldAxis::kRow);
  EXPECT_EQ(scene.flag.folds[0].at, 0.25);
  EXPECT_EQ(scene.flag.folds[0].angle_rad, 3.0);
  EXPECT_EQ(scene.flag.folds[1].axis, FoldAxis::kCol);  // the default axis
  ASSERT_TRUE(scene.creases);
  EXPECT_EQ(scene.creases->set_time_s, 2.0);
  EXPECT_EQ(scene.creases->yield_angle_rad, Creases{}.yield_angle_rad);
  EXPECT_EQ(error_of(folded),
            "s.toml:7:9: flag.folds: fold lines are creases: they need [creases] (how a crease "
            "sets and relaxes; an empty table takes the defaults)");
  EXPECT_EQ(error_of(std::string(kMinimal) + "[creases]\n"),
            "s.toml:7:1: creases: a crease is a rest angle of the cloth's bending: add [bending] "
            "(its stiffness is the crease's)");
  // Every backend has them (XPBD and Bullet with the crease as a force).
  for (const char* mode : {"xpbd", "bullet", "implicit"})
    EXPECT_EQ(error_of(folded + creases, {std::string("scene.mode=\"") + mode + "\""}), "") << mode;
  EXPECT_EQ(
      error_of(std::string(kMinimal) + "folds = [{ axis = \"row\", at = 1.0, angle = 1 }]\n"),
      "s.toml:7:31: flag.folds.at: 1 is the flag's edge: a fold line lies inside, 0 < at < 1");
  EXPECT_NE(error_of(std::string(kMinimal) + "folds = [{ axis = \"row\", at = 0.5 }]\n")
                .find("flag.folds.angle: a fold line needs where it lies (at) and its angle"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "folds = [{ axis = \"diagonal\", at = 0.5 }]\n")
                .find("flag.folds.axis"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "folds = [{ axis = \"row\", at = 0.5, angle = 4 }]\n")
                .find("flag.folds.angle"),
            std::string::npos);
  // A signed angle: toward the back is negative; none is no fold.
  EXPECT_EQ(parse_scene(std::string(kMinimal) +
                            "folds = [{ axis = \"row\", at = 0.5, angle = -2.5 }]\n" + creases,
                        "s.toml")
                .flag.folds[0]
                .angle_rad,
            -2.5);
  EXPECT_NE(error_of(std::string(kMinimal) + "folds = [{ axis = \"row\", at = 0.5, angle = 0 }]\n")
                .find("flag.folds.angle: a fold of 0 rad leaves nothing"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "folds = [{ axis = \"row\", at = 0.5, angle = -4 }]\n")
                .find("flag.folds.angle"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "folds = 3\n").find("flag.folds: expected a list"),
            std::string::npos);
  EXPECT_NE(error_of(folded + creases + "width = 0\n").find("creases.width"), std::string::npos);
  // The hybrid draws its crease lines with the smooth infill.
  const std::vector<std::string> hybrid = {"scene.mode=\"hybrid\"", "flag.coarse=[5,7]"};
  std::vector<std::string> paper = hybrid, coarse_only = hybrid;
  paper.emplace_back("infill.solver=\"paper\"");
  coarse_only.emplace_back("output.dense=false");
  EXPECT_EQ(parse_scene(folded + creases, "s.toml", hybrid).mode, Mode::kHybrid);
  EXPECT_NE(error_of(folded + creases, paper).find("creases: the hybrid draws its crease lines"),
            std::string::npos);
  // A coarse-only file keeps the creases' angles beside the trajectory (refine_test.cpp).
  EXPECT_EQ(error_of(folded + creases, coarse_only), "");
}

}  // namespace
}  // namespace flagsim
