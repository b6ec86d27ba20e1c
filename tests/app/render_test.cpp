// `flag-sim render` and `run --render` end to end.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "flagsim/data/output_reader.hpp"
#include "process.hpp"
#include "temp_dir.hpp"
#include "tolerances.hpp"

namespace flagsim::test {
namespace {
namespace fs = std::filesystem;

const std::vector<std::string> kSmallRun = {
    "run", "--set", "flag.fine=[17,25]", "--frames", "4", "--quiet", "-o", "r.h5"};

std::vector<char> bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<char>(std::istreambuf_iterator<char>(in), {});
}

// `render ARGS -o bad --size 160x90` is exit 2, its message holds `words`,
// and it leaves no `bad`.
void expect_render_refused(const TempDir& dir, const std::vector<std::string>& args,
                           const std::string& words) {
  std::vector<std::string> command = {"render", "-o", "bad", "--size", "160x90"};
  command.insert(command.end(), args.begin(), args.end());
  const ProcessResult result = run_flag_sim(command, dir.path());
  EXPECT_EQ(result.exit_code, 2) << words;
  EXPECT_NE(result.err.find(words), std::string::npos) << result.err;
  EXPECT_FALSE(fs::exists(dir.file("bad"))) << words;
}

TEST(Render, RunRenderWritesTheFileAndOnePngPerFrame) {
  TempDir dir;
  std::vector<std::string> args = kSmallRun;
  args.insert(args.end(), {"--render", "frames", "--size", "160x90", "--style", "wireframe"});
  const ProcessResult result = run_flag_sim(args, dir.path());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("rendered 4 frames (wireframe, 160x90)"), std::string::npos)
      << result.out;
  EXPECT_TRUE(fs::exists(dir.file("r.h5")));
  for (int t = 0; t < 4; ++t)
    EXPECT_TRUE(fs::exists(dir.file("frames/frame_0000" + std::to_string(t) + ".png"))) << t;
  EXPECT_FALSE(fs::exists(dir.file("frames/frame_00004.png")));
}

TEST(Render, TheSameFileRendersToTheSameBytes) {
  TempDir dir;
  ASSERT_EQ(run_flag_sim(kSmallRun, dir.path()).exit_code, 0);
  for (const char* out : {"a", "b"})
    ASSERT_EQ(run_flag_sim({"render", "r.h5", "-o", out, "--size", "160x90", "--style", "textured"},
                           dir.path())
                  .exit_code,
              0);
  for (int t = 0; t < 4; ++t) {
    const std::string name = "/frame_0000" + std::to_string(t) + ".png";
    EXPECT_EQ(bytes(dir.file("a" + name)), bytes(dir.file("b" + name))) << t;
  }
}

TEST(Render, Mp4ThroughFfmpeg) {
  TempDir dir;
  ASSERT_EQ(run_flag_sim(kSmallRun, dir.path()).exit_code, 0);
  const ProcessResult result =
      run_flag_sim({"render", "r.h5", "-o", "movie/flag.mp4", "--size", "160x90"}, dir.path());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const std::vector<char> mp4 = bytes(dir.file("movie/flag.mp4"));
  ASSERT_GT(mp4.size(), 100u);
  EXPECT_EQ(std::string(mp4.begin() + 4, mp4.begin() + 8), "ftyp");  // an ISO media file
}

// The containers users ask for, each what its name says (magic bytes), and a
// video's frame rate from its frames' times: a run writing every 3rd frame of
// 30 fps has frames 0.1 s apart, so its video is 10 fps (ffprobe says so).
TEST(Render, VideoContainersAndTheirFrameRate) {
  TempDir dir;
  ASSERT_EQ(run_flag_sim({"run", "--set", "flag.fine=[17,25]", "--frames", "13", "--set",
                          "output.every=3", "--quiet", "-o", "r.h5"},
                         dir.path())
                .exit_code,
            0);
  const std::vector<std::pair<std::string, std::string>> videos = {
      {"v.mp4", std::string("ftyp")},
      {"v.mkv", std::string("\x1a\x45\xdf\xa3")},
      {"v.webm", std::string("\x1a\x45\xdf\xa3")},
      {"v.gif", std::string("GIF89a")}};
  for (const auto& [name, magic] : videos) {
    const ProcessResult result =
        run_flag_sim({"render", "r.h5", "-o", name, "--size", "160x90"}, dir.path());
    ASSERT_EQ(result.exit_code, 0) << name << result.err;
    const std::vector<char> file = bytes(dir.file(name));
    ASSERT_GT(file.size(), 16u) << name;
    const std::size_t at = name == "v.mp4" ? 4 : 0;
    EXPECT_EQ(std::string(file.begin() + long(at), file.begin() + long(at + magic.size())), magic)
        << name;
    const ProcessResult probe = run_process("/usr/bin/ffprobe",
                                            {"-v", "error", "-select_streams", "v", "-show_entries",
                                             "stream=r_frame_rate", "-of", "csv=p=0", name},
                                            dir.path());
    EXPECT_EQ(probe.out, "10/1\n") << name << probe.err;
  }
  // 13 frames written every 3rd: 5 frames of a 30 fps run, 5 x 3 / 30 = 0.5 s of video.
  const ProcessResult duration = run_process(
      "/usr/bin/ffprobe",
      {"-v", "error", "-show_entries", "format=duration", "-of", "csv=p=0", "v.mp4"}, dir.path());
  EXPECT_NEAR(std::stod(duration.out.empty() ? "0" : duration.out), 0.5, test::kVideoDuration_s)
      << duration.err;
}

// A name with another extension is refused, not made into a directory of
// PNGs called run.avi; a trailing '/' makes any name a directory.
TEST(Render, AnUnknownVideoExtensionIsRefused) {
  TempDir dir;
  ASSERT_EQ(run_flag_sim(kSmallRun, dir.path()).exit_code, 0);
  const ProcessResult refused =
      run_flag_sim({"render", "r.h5", "-o", "run.avi", "--size", "160x90"}, dir.path());
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("error: -o run.avi: '.avi' is not a video flag-sim writes"),
            std::string::npos)
      << refused.err;
  EXPECT_FALSE(fs::exists(dir.file("run.avi")));
  const ProcessResult frames =
      run_flag_sim({"render", "r.h5", "-o", "frames.v2/", "--size", "160x90"}, dir.path());
  EXPECT_EQ(frames.exit_code, 0) << frames.err;
  EXPECT_TRUE(fs::exists(dir.file("frames.v2/frame_00003.png")));
}

// -o NAME.png with one frame (--frames N, -1 the last) is that frame, as the
// same frame drawn into a directory; a range of several is refused up front.
TEST(Render, ANamedStillIsOneFrame) {
  TempDir dir;
  ASSERT_EQ(run_flag_sim(kSmallRun, dir.path()).exit_code, 0);
  ASSERT_EQ(
      run_flag_sim({"render", "r.h5", "-o", "all/", "--size", "160x90"}, dir.path()).exit_code, 0);
  const ProcessResult still = run_flag_sim(
      {"render", "r.h5", "-o", "stills/hero.png", "--frames", "-1", "--size", "160x90"},
      dir.path());
  ASSERT_EQ(still.exit_code, 0) << still.err;
  EXPECT_NE(still.out.find("rendered 1 frame "), std::string::npos) << still.out;
  EXPECT_EQ(bytes(dir.file("stills/hero.png")), bytes(dir.file("all/frame_00003.png")));
  ASSERT_EQ(run_flag_sim({"render", "r.h5", "-o", "two.PNG", "--frames", "2", "--size", "160x90"},
                         dir.path())
                .exit_code,
            0);
  EXPECT_EQ(bytes(dir.file("two.PNG")), bytes(dir.file("all/frame_00002.png")));
  const ProcessResult several =
      run_flag_sim({"render", "r.h5", "-o", "many.png", "--frames", "1:3"}, dir.path());
  EXPECT_EQ(several.exit_code, 2);
  EXPECT_NE(several.err.find("-o many.png: a PNG file holds one frame, and frames 1 to 2 are 2"),
            std::string::npos)
      << several.err;
  EXPECT_FALSE(fs::exists(dir.file("many.png")));
  const ProcessResult run_render = run_flag_sim({"run", "--set", "flag.fine=[17,25]", "--frames",
                                                 "4", "--quiet", "-o", "s.h5", "--render", "s.png"},
                                                dir.path());
  EXPECT_EQ(run_render.exit_code, 2);  // before the run: four frames are no still
  EXPECT_FALSE(fs::exists(dir.file("s.h5")));
}

// --frames A:B draws frames A .. B - 1 under their own numbers; --camera
// picks the view (a side view is another image of the same frame); ranges
// outside the file and unknown views are exit 2 and leave nothing.
TEST(Render, AFrameRangeAndACameraView) {
  TempDir dir;
  ASSERT_EQ(run_flag_sim(kSmallRun, dir.path()).exit_code, 0);
  const ProcessResult range = run_flag_sim(
      {"render", "r.h5", "-o", "part", "--frames", "1:3", "--size", "160x90"}, dir.path());
  ASSERT_EQ(range.exit_code, 0) << range.err;
  EXPECT_NE(range.out.find("rendered 2 frames"), std::string::npos) << range.out;
  EXPECT_FALSE(fs::exists(dir.file("part/frame_00000.png")));
  EXPECT_TRUE(fs::exists(dir.file("part/frame_00001.png")));
  EXPECT_TRUE(fs::exists(dir.file("part/frame_00002.png")));
  EXPECT_FALSE(fs::exists(dir.file("part/frame_00003.png")));
  ASSERT_EQ(run_flag_sim({"render", "r.h5", "-o", "side", "--frames", "1:2", "--camera", "side",
                          "--size", "160x90"},
                         dir.path())
                .exit_code,
            0);
  EXPECT_NE(bytes(dir.file("side/frame_00001.png")), bytes(dir.file("part/frame_00001.png")));
  // An explicit camera: from where --eye says, at --target (default: the run's centre).
  ASSERT_EQ(run_flag_sim({"render", "r.h5", "-o", "eye", "--frames", "1:2", "--eye", "3,3,3",
                          "--size", "160x90"},
                         dir.path())
                .exit_code,
            0);
  ASSERT_EQ(run_flag_sim({"render", "r.h5", "-o", "eye_target", "--frames", "1:2", "--eye", "3,3,3",
                          "--target", "0,2,0", "--size", "160x90"},
                         dir.path())
                .exit_code,
            0);
  EXPECT_NE(bytes(dir.file("eye/frame_00001.png")), bytes(dir.file("part/frame_00001.png")));
  EXPECT_NE(bytes(dir.file("eye/frame_00001.png")), bytes(dir.file("eye_target/frame_00001.png")));
  for (const auto& [args, words] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"--frames", "2:9"}, "--frames 2:9: r.h5 has frames 0 to 3"},
           {{"--frames", "3:1"}, "the range is empty"},
           {{"--frames", "a:b"}, "expected N (one frame; -1 the last) or A:B"},
           {{"--camera", "top"}, "--camera top: expected one of"},
           {{"--camera", "sid"}, "(did you mean \"side\"?)"},
           {{"--eye", "1,2"}, "--eye 1,2: expected X,Y,Z in metres"},
           {{"--eye", "1,2,3,4"}, "--eye 1,2,3,4: expected X,Y,Z"},
           {{"--eye", "1,2,2e5"}, "each coordinate within"},
           {{"--target", "1,2,3"}, "--target 1,2,3: goes with --eye"},
           {{"--eye", "1,2,3", "--camera", "side"}, "give --eye or --camera side, not both"},
           {{"--antialias", "5"}, "--antialias 5: expected 1 (none) to 4 samples"}}) {
    std::vector<std::string> command = {"r.h5"};
    command.insert(command.end(), args.begin(), args.end());
    expect_render_refused(dir, command, words);
  }
}

// --color: one scale over the drawn frames, 0 to their largest value, said in
// the summary; the field must be in the file, and colours only the shaded style.
TEST(Render, ColouredByAPerNodeField) {
  TempDir dir;
  ASSERT_EQ(run_flag_sim(kSmallRun, dir.path()).exit_code, 0);
  const ProcessResult plain = run_flag_sim(
      {"render", "r.h5", "-o", "plain", "--frames", "1:3", "--size", "160x90"}, dir.path());
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  const ProcessResult strain = run_flag_sim({"render", "r.h5", "-o", "strain", "--frames", "1:3",
                                             "--size", "160x90", "--color", "strain"},
                                            dir.path());
  ASSERT_EQ(strain.exit_code, 0) << strain.err;
  const data::OutputReader reader(dir.file("r.h5"));
  const std::vector<double> max_strain = reader.stat("max_strain");
  EXPECT_NE(strain.out.find(fmt::format("coloured by strain 0 .. {:.3g}%",
                                        100.0 * std::max(max_strain[1], max_strain[2]))),
            std::string::npos)
      << strain.out;
  EXPECT_NE(bytes(dir.file("strain/frame_00001.png")), bytes(dir.file("plain/frame_00001.png")));
  const ProcessResult speed = run_flag_sim(
      {"render", "r.h5", "-o", "speed", "--frames", "1:2", "--size", "160x90", "--color", "speed"},
      dir.path());
  EXPECT_NE(speed.out.find("coloured by speed 0 .. "), std::string::npos) << speed.out << speed.err;
  // A file written without the fields, and a style the colours do not apply to.
  ASSERT_EQ(run_flag_sim({"run", "--set", "flag.fine=[17,25]", "--frames", "2", "--quiet", "-o",
                          "bare.h5", "--set", "output.fields=[]"},
                         dir.path())
                .exit_code,
            0);
  for (const auto& [args, words] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"bare.h5", "--color", "strain"}, "bare.h5 has no /frames/strain"},
           {{"bare.h5", "--color", "speed"}, "bare.h5 has no /frames/velocity"},
           {{"r.h5", "--color", "heat"}, "--color heat: expected \"strain\" or \"speed\""},
           {{"r.h5", "--color", "strain", "--style", "wireframe"}, "colours the shaded style"}})
    expect_render_refused(dir, args, words);
}

}  // namespace
}  // namespace flagsim::test
