// Bad scenes and bad command lines, end to end through build/flag-sim: each
// gets exit code 2, exactly one `error:` line on stderr naming the place and
// the fix, nothing on stdout, and no output file left behind.
#include <gtest/gtest.h>

#include "process.hpp"
#include "temp_dir.hpp"

namespace flagsim::test {
namespace {

// A valid small scene; cases append to it or replace it.
constexpr const char* kBase = R"([scene]
mode = "mass-spring"
duration = 0.1
[flag]
size = [1.5, 1.0]
fine = [9, 13]
)";

struct BadInput {
  const char* name;
  std::string scene;              ///< written to scene.toml; empty: no scene file
  std::vector<std::string> args;  ///< "SCENE" is replaced by the scene's path
  std::string message;            ///< must appear in the error line
};

// Names the case in gtest's output instead of dumping its bytes.
void PrintTo(const BadInput& input, std::ostream* out) {
  *out << input.name;
}

std::string with(const std::string& extra) {
  return std::string(kBase) + extra;
}

const std::vector<BadInput>& cases() {
  static const std::vector<BadInput> list = {
      {"broken_toml", "[flag\nsize = [1, 2]\n", {"run", "SCENE"}, "scene.toml:1:6: invalid TOML"},
      {"misspelt_key",
       with("stretch_modulous = 1e4\n"),
       {"run", "SCENE"},
       "scene.toml:7:1: unknown key 'flag.stretch_modulous' (did you mean "
       "'flag.stretch_modulus'?)"},
      {"misspelt_table",
       with("[wnid]\nvelocity = [1, 0, 0]\n"),
       {"run", "SCENE"},
       "unknown key 'wnid' (did you mean 'wind'?)"},
      {"key_in_wrong_table",
       std::string("seed = 3\n") + kBase,
       {"run", "SCENE"},
       "unknown key 'seed' (did you mean 'scene.seed'?)"},
      {"wrong_type",
       std::string(kBase).replace(std::string(kBase).find("[9, 13]"), 7, "\"9x13\""),
       {"run", "SCENE"},
       "scene.toml:6:8: flag.fine: expected [J, K] nodes, two integers"},
      {"negative_density",
       with("areal_density = -0.2\n"),
       {"run", "SCENE"},
       "flag.areal_density: expected a number in [0.0001, 100] kg/m^2, got -0.2"},
      {"nan_modulus",
       with("stretch_modulus = nan\n"),
       {"run", "SCENE"},
       "flag.stretch_modulus: expected a number in (0, 1e+08] N/m, got nan"},
      {"infinite_duration",
       std::string(kBase).replace(std::string(kBase).find("0.1"), 3, "inf"),
       {"run", "SCENE"},
       "scene.duration: expected a number in (0, 1e+06] s, got inf"},
      {"zero_fps",
       with("").insert(std::string(kBase).find("[flag]"), "fps = 0\n"),
       {"run", "SCENE"},
       "scene.fps: expected a number in (0, 10000] frames per second, got 0"},
      {"lattice_1x1",
       std::string(kBase).replace(std::string(kBase).find("[9, 13]"), 7, "[1, 1]"),
       {"run", "SCENE"},
       "flag.fine: expected [J, K] nodes, two integers in [2, 8193]"},
      {"lattice_absurd",
       std::string(kBase).replace(std::string(kBase).find("[9, 13]"), 7, "[1000000, 1000000]"),
       {"run", "SCENE"},
       "two integers in [2, 8193], got [1000000, 1000000]"},
      {"too_many_nodes",
       std::string(kBase).replace(std::string(kBase).find("[9, 13]"), 7, "[8193, 8193]"),
       {"run", "SCENE"},
       "flag.fine: 8193 x 8193 = 67125249 nodes is more than"},
      {"coarse_not_dividing",
       with("coarse = [4, 13]\n"),
       {"run", "SCENE"},
       "flag.coarse: [4, 13] does not divide flag.fine = [9, 13]: 9 - 1 = 8 is not a multiple of 4 "
       "- 1; "
       "coarse rows that work: 2, 3, 5, 9"},
      {"mode_typo",
       std::string(kBase).replace(std::string(kBase).find("\"mass-spring\""), 13,
                                  "\"mass_spring\""),
       {"run", "SCENE"},
       "scene.mode: expected one of \"hybrid\", \"mass-spring\", \"bullet\", \"implicit\", "
       "\"xpbd\", \"infill\", "
       "got \"mass_spring\" (did you mean \"mass-spring\"?)"},
      {"bad_pin", with("pin = \"middle\"\n"), {"run", "SCENE"}, "flag.pin: expected one of"},
      {"pole_without_pins",
       with("pin = \"none\"\n[pole]\nmotion = \"sine\"\n"),
       {"run", "SCENE"},
       "pole: a moving pole needs pinned nodes"},
      {"wind_two_components",
       with("[wind]\nvelocity = [10, 0]\n"),
       {"run", "SCENE"},
       "wind.velocity: expected an array of 3 finite numbers"},
      {"keyframes_out_of_order",
       with("[[keyframe]]\ntime = 1.0\ncorners = [[0,0,0],[1,0,0],[0,1,0],[1,1,0]]\n"
            "[[keyframe]]\ntime = 0.5\ncorners = [[0,0,0],[1,0,0],[0,1,0],[1,1,0]]\n"),
       {"run", "SCENE"},
       "keyframe.time: keyframes must be in increasing time; 0.5 s follows 1 s"},
      {"wrinkles_without_infill",
       with("[wrinkles]\nfiber_radius = 0.001\n"),
       {"run", "SCENE"},
       "wrinkles: wrinkles are made by the infill (paper 3.5); they need scene.mode = \"hybrid\" "
       "or "
       "\"infill\""},
      {"render_size_in_scene_too_small",
       with("[render]\nsize = [8, 8]\n"),
       {"run", "SCENE"},
       "render.size: expected [w, h] pixels"},
      {"unknown_backend",
       kBase,
       {"run", "SCENE", "--set", "solver.backend=bulet"},
       "solver.backend: expected one of \"spring-damper\", \"bullet\", \"implicit\", \"xpbd\", got "
       "\"bulet\""},
      {"infill_mode_with_wind",
       "[scene]\nmode = \"infill\"\nduration = 0.1\n[flag]\nsize = [1.5, 1.0]\nfine = [9, 13]\n"
       "[wind]\nvelocity = [1, 0, 0]\n[[keyframe]]\ntime = 0.0\ncorners = "
       "[[0,2,0],[1.5,2,0],[0,1,0],[1.5,1,0]]\n",
       {"run", "SCENE"},
       "wind: infill mode has no physics"},
      {"infill_mode_with_bending_but_no_creases",
       "[scene]\nmode = \"infill\"\nduration = 0.1\n[flag]\nsize = [1.5, 1.0]\nfine = [9, 13]\n"
       "[bending]\nstiffness = 1e-4\n[[keyframe]]\ntime = 0.0\ncorners = "
       "[[0,2,0],[1.5,2,0],[0,1,0],[1.5,1,0]]\n",
       {"run", "SCENE"},
       "bending: infill mode has no physics"},
      {"self_contact_in_infill_mode",
       "[scene]\nmode = \"infill\"\nduration = 0.1\n[flag]\nsize = [1.5, 1.0]\nfine = [9, 13]\n"
       "[contact]\n[[keyframe]]\ntime = 0.0\ncorners = "
       "[[0,2,0],[1.5,2,0],[0,1,0],[1.5,1,0]]\n",
       {"run", "SCENE"},
       "contact: infill mode has no physics"},
      {"infill_mode_without_keyframes",
       kBase,
       {"run", "SCENE", "--mode", "infill"},
       "scene.mode: infill mode needs [[keyframe]] tables"},
      {"keyframes_outside_infill_mode",
       with("[[keyframe]]\ntime = 0.0\ncorners = [[0,2,0],[1.5,2,0],[0,1,0],[1.5,1,0]]\n"),
       {"run", "SCENE"},
       "keyframe: [[keyframe]] drives the corners in infill mode only"},
      {"keyframe_three_corners",
       with("[[keyframe]]\ntime = 0.0\ncorners = [[0,2,0],[1.5,2,0],[0,1,0]]\n"),
       {"run", "SCENE", "--mode", "infill"},
       "keyframe.corners: expected 4 corners"},
      {"negative_limit",
       with("[limits]\nmax_strain = -1\n"),
       {"run", "SCENE"},
       "limits.max_strain: expected a number > 0"},
      {"unknown_flag", kBase, {"run", "SCENE", "--bogus"}, "--bogus"},
      {"set_without_value",
       kBase,
       {"run", "SCENE", "--set", "flag.fine"},
       "--set flag.fine: expected KEY=VALUE"},
      {"set_out_of_range",
       kBase,
       {"run", "SCENE", "--set", "flag.fine=[0,3]"},
       "--set flag.fine=[0,3]: flag.fine: expected [J, K] nodes"},
      {"set_unknown_key",
       kBase,
       {"run", "SCENE", "--set", "flag.colour=1"},
       "unknown key 'flag.colour'"},
      {"negative_seed",
       kBase,
       {"run", "SCENE", "--seed", "-1"},
       "--seed -1: expected an integer from 0 to 9223372036854775807"},
      {"misspelt_option",
       kBase,
       {"run", "SCENE", "--frams", "3"},
       "--frams; did you mean --frames? (see flag-sim help run)"},
      {"misspelt_render_option",
       kBase,
       {"render", "SCENE", "-o", "frames/", "--colour", "strain"},
       "--colour; did you mean --color? (see flag-sim help render)"},
      {"zero_frames",
       kBase,
       {"run", "SCENE", "--frames", "0"},
       "--frames 0: expected at least 1 frame"},
      {"missing_scene_file", "", {"run", "nowhere.toml"}, "nowhere.toml: cannot open scene file"},
      {"run_render_size_too_small",
       kBase,
       {"run", "SCENE", "--render", "frames", "--size", "12x12"},
       "--size 12x12: each side must be 16 to 8192 pixels"},
      {"run_render_size_not_wxh",
       kBase,
       {"run", "SCENE", "--render", "frames", "--size", "big"},
       "--size big: expected WxH in pixels, e.g. 1280x720"},
      {"run_render_odd_mp4",
       kBase,
       {"run", "SCENE", "--render", "movie.mp4", "--size", "641x360"},
       "--size 641x360: H.264 MP4 (yuv420p) needs an even width and height"},
      {"run_render_unknown_style",
       kBase,
       {"run", "SCENE", "--render", "frames", "--style", "sketch"},
       "--style sketch: expected one of \"wireframe\", \"shaded\", \"textured\""},
      {"run_render_misspelt_style",
       kBase,
       {"run", "SCENE", "--render", "frames", "--style", "shadd"},
       "--style shadd: expected one of \"wireframe\", \"shaded\", \"textured\" (did you mean "
       "\"shaded\"?)"},
      {"run_render_missing_texture",
       kBase,
       {"run", "SCENE", "--render", "frames", "--style", "textured", "--texture", "none.png"},
       "none.png: cannot read as PNG"},
      {"run_render_texture_not_textured",
       kBase,
       {"run", "SCENE", "--render", "frames", "--texture", "SCENE"},
       "a texture needs --style textured"},
      {"run_render_under_a_file",
       kBase,
       {"run", "SCENE", "--render", "scene.toml/frames"},
       "--render scene.toml/frames: cannot write to scene.toml/frames"},
      {"misspelt_command", "", {"runn"}, "unknown command 'runn' (did you mean 'run'?)"},
      {"help_for_a_misspelt_command",
       "",
       {"help", "rnder"},
       "unknown command 'rnder' (did you mean 'render'?)"},
      {"validate_with_a_bad_set",
       kBase,
       {"validate", "SCENE", "--set", "flag.fine=[1,1]"},
       "--set flag.fine=[1,1]: flag.fine: expected [J, K] nodes"},
      {"render_unknown_container",
       kBase,
       {"run", "SCENE", "--render", "movie.avi"},
       "--render movie.avi: '.avi' is not a video flag-sim writes"},
      {"size_without_render",
       kBase,
       {"run", "SCENE", "--size", "640x360"},
       "--size, --style, --texture and --color go with --render OUT.mp4|DIR"},
      {"render_missing_file",
       "",
       {"render", "nothing.h5", "-o", "frames"},
       "nothing.h5: no such file"},
      {"render_not_hdf5",
       kBase,
       {"render", "SCENE", "-o", "frames"},
       "scene.toml: not an HDF5 file"},
      {"render_without_output", "", {"render", "nothing.h5"}, "--output is required"},
      {"output_under_a_file",
       kBase,
       {"run", "SCENE", "-o", "scene.toml/run.h5"},
       "scene.toml/run.h5: scene.toml is a file, not a directory"},
      {"info_missing_file", "", {"info", "nothing.h5"}, "nothing.h5: no such file"},
      {"info_not_hdf5", kBase, {"info", "SCENE"}, "scene.toml: not an HDF5 file"},
      {"validate_bad_scene",
       with("damping = \"lots\"\n"),
       {"validate", "SCENE"},
       "flag.damping: expected a number in [0, 1e+06] 1/s, got \"lots\""},
      {"compare_unknown_reference",
       kBase,
       {"compare", "SCENE", "--reference", "havok"},
       "--reference havok: expected mass-spring, bullet, implicit, xpbd or all"},
      {"compare_without_coarse", kBase, {"compare", "SCENE"}, "flag.coarse"},
      {"sweep_coarse_not_dividing",
       with("coarse = [3, 4]\n"),
       {"sweep", "SCENE", "--coarse", "4x4", "-o", "s.csv"},
       "coarse rows that work"},
      {"sweep_coarse_malformed",
       with("coarse = [3, 4]\n"),
       {"sweep", "SCENE", "--coarse", "5x", "-o", "s.csv"},
       "--coarse 5x: expected coarse lattices as JcxKc"},
      {"sweep_relax_zero",
       with("coarse = [3, 4]\n"),
       {"sweep", "SCENE", "--coarse", "3x4", "--relax", "0", "-o", "s.csv"},
       "--relax 0: expected counts of at least 1"},
      {"sweep_point_out_of_range",
       with("coarse = [3, 4]\n"),
       {"sweep", "SCENE", "--coarse", "3x4", "--point", "7", "-o", "s.csv"},
       "--point 7: this sweep has points 0 to 1"},
      {"sweep_without_output",
       with("coarse = [3, 4]\n"),
       {"sweep", "SCENE", "--coarse", "3x4"},
       "-o SWEEP.csv is required"},
      {"no_subcommand", "", {}, "no command given: flag-sim COMMAND, with COMMAND one of run, "},
  };
  return list;
}

class BadInputTest : public ::testing::TestWithParam<BadInput> {};

TEST_P(BadInputTest, ExitTwoOneErrorLineNoOutputFile) {
  const BadInput& input = GetParam();
  TempDir dir;
  std::vector<std::string> args;
  if (!input.scene.empty()) dir.write("scene.toml", input.scene);
  for (const std::string& a : input.args) args.push_back(a == "SCENE" ? "scene.toml" : a);
  if (!args.empty() && args[0] == "run") {
    args.push_back("--quiet");
    if (std::find(args.begin(), args.end(), "-o") == args.end()) {
      args.push_back("-o");
      args.push_back("run.h5");
    }
  }
  const ProcessResult result = run_flag_sim(args, dir.path());
  EXPECT_EQ(result.exit_code, 2) << result.err;
  EXPECT_TRUE(result.out.empty()) << result.out;
  ASSERT_TRUE(result.err.starts_with("error: ")) << result.err;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_NE(result.err.find(input.message), std::string::npos)
      << "expected: " << input.message << "\n     got: " << result.err;
  EXPECT_EQ(dir.entry_count(), input.scene.empty() ? 0 : 1) << "an output file was left behind";
}

INSTANTIATE_TEST_SUITE_P(Cases, BadInputTest, ::testing::ValuesIn(cases()),
                         [](const auto& param_info) { return std::string(param_info.param.name); });

TEST(BadInput, AtLeastTwentyCases) {
  EXPECT_GE(cases().size(), 20u);
}

// `flag-sim help` and `help COMMAND` print the usage, exit 0; validate takes --set like run.
TEST(Help, PrintsTheUsageOfTheProgramAndOfACommand) {
  const ProcessResult all = run_flag_sim({"help"});
  EXPECT_EQ(all.exit_code, 0) << all.err;
  EXPECT_NE(all.out.find("Usage: flag-sim"), std::string::npos) << all.out;
  const ProcessResult render = run_flag_sim({"help", "render"});
  EXPECT_EQ(render.exit_code, 0) << render.err;
  EXPECT_NE(render.out.find("--size"), std::string::npos) << render.out;
  TempDir dir;
  dir.write("s.toml", "[scene]\nmode = \"hybrid\"\n[flag]\nfine = [17, 25]\ncoarse = [9, 13]\n");
  const ProcessResult validated =
      run_flag_sim({"validate", "s.toml", "--set", "flag.fine=[33,49]"}, dir.path());
  EXPECT_EQ(validated.exit_code, 0) << validated.err;
  EXPECT_NE(validated.out.find("33 x 49 nodes"), std::string::npos) << validated.out;
}

}  // namespace
}  // namespace flagsim::test
