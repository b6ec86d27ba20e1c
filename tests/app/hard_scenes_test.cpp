// The hard-case stability suite: every scene under scenes/hard/ (and, in the
// "large" binary, scenes/hard/large/) runs end to end and ends as its header
// says:
//   # expect: complete        exit 0, every frame finite, strain within limits
//   # expect: still           exit 0, and no node moves at all
//   # expect: diverged (KEY)  exit 3, status "diverged", a reason naming KEY,
//                             the good frames kept and finite
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>

#include "flagsim/data/output_reader.hpp"
#include "process.hpp"
#include "temp_dir.hpp"

#ifndef FLAGSIM_HARD_DIR
#define FLAGSIM_HARD_DIR "scenes/hard"
#endif

namespace flagsim::test {
namespace {
namespace fs = std::filesystem;

struct HardCase {
  std::string name;
  std::string path;
  std::string expect;  ///< complete / still / diverged
  std::string reason;  ///< for diverged: what the reason must name
};

void PrintTo(const HardCase& c, std::ostream* out) {
  *out << c.name;
}

std::vector<HardCase> hard_cases() {
  std::vector<HardCase> cases;
  const fs::path dir = fs::path(FLAGSIM_SOURCE_DIR) / FLAGSIM_HARD_DIR;
  static const std::regex header(R"(^# expect: (\w+)(?: \((.*)\))?)");
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".toml") continue;
    std::ifstream in(entry.path());
    std::string line;
    HardCase c{entry.path().stem().string(), entry.path().string(), "", ""};
    while (std::getline(in, line)) {
      std::smatch match;
      if (std::regex_search(line, match, header)) {
        c.expect = match[1];
        c.reason = match[2];
        break;
      }
    }
    cases.push_back(c);
  }
  std::sort(cases.begin(), cases.end(), [](auto& a, auto& b) { return a.name < b.name; });
  return cases;
}

class HardScene : public ::testing::TestWithParam<HardCase> {};

TEST_P(HardScene, EndsAsItsHeaderSays) {
  const HardCase& c = GetParam();
  ASSERT_TRUE(c.expect == "complete" || c.expect == "still" || c.expect == "diverged")
      << c.path << ": no '# expect:' header";
  TempDir dir;
  const ProcessResult result = run_flag_sim({"run", c.path, "-o", "out.h5", "--quiet"}, dir.path());
  const int expected_exit = c.expect == "diverged" ? 3 : 0;
  ASSERT_EQ(result.exit_code, expected_exit) << result.err << result.out;
  const data::OutputReader reader(dir.file("out.h5"));
  ASSERT_GE(reader.frame_count(), 1);
  for (int t = 0; t < reader.frame_count(); ++t)
    for (const Vec3& p : reader.positions(t)) ASSERT_TRUE(p.allFinite()) << "frame " << t;
  const std::vector<double> strain = reader.stat("max_strain");
  if (c.expect == "diverged") {
    EXPECT_EQ(reader.attribute("status"), "diverged");
    EXPECT_NE(reader.attribute("status_reason").find(c.reason), std::string::npos)
        << reader.attribute("status_reason");
    EXPECT_TRUE(result.err.starts_with("error: simulation diverged")) << result.err;
    return;
  }
  EXPECT_EQ(reader.attribute("status"), "complete");
  // What the header claims, a figure tighter than the divergence limit (which
  // any run that exits 0 meets): "# expect: complete (max strain 1.4%; ...)".
  static const std::regex claim(R"(max strain ([0-9.]+)%)");
  std::smatch bound;
  ASSERT_TRUE(std::regex_search(c.reason, bound, claim))
      << c.path << ": the header must say its max strain, e.g. (max strain 1.4%; measured ...)";
  const double claimed = std::stod(bound[1]) / 100.0;
  static const std::regex limit_key(R"(max_strain\s*=\s*([0-9.eE+-]+))");
  std::smatch limit;
  const std::string scene_text = reader.attribute("scene");
  const double limit_value =
      std::regex_search(scene_text, limit, limit_key) ? std::stod(limit[1]) : 0.3;
  EXPECT_LT(claimed, limit_value) << c.path << ": a bound at the divergence limit asserts nothing";
  double worst = 0.0;
  for (double s : strain) worst = std::max(worst, s);
  EXPECT_LE(worst, claimed) << c.path << ": max strain " << 100 * worst << "%";
  if (c.expect == "still") {
    const auto first = reader.positions(0);
    for (int t = 1; t < reader.frame_count(); ++t) EXPECT_EQ(reader.positions(t), first) << t;
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, HardScene, ::testing::ValuesIn(hard_cases()),
                         [](const auto& param_info) { return param_info.param.name; });

TEST(HardScenes, TheSuiteHasItsCases) {
#ifndef FLAGSIM_HARD_LARGE
  EXPECT_GE(hard_cases().size(), 40u);
#else
  EXPECT_GE(hard_cases().size(), 1u);
#endif
}

}  // namespace
}  // namespace flagsim::test
