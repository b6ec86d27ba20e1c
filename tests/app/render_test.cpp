// `flag-sim render` and `run --render` end to end.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "process.hpp"
#include "temp_dir.hpp"

namespace flagsim::test {
namespace {
namespace fs = std::filesystem;

const std::vector<std::string> kSmallRun = {
    "run", "--set", "flag.fine=[17,25]", "--frames", "4", "--quiet", "-o", "r.h5"};

std::vector<char> bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<char>(std::istreambuf_iterator<char>(in), {});
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

}  // namespace
}  // namespace flagsim::test
