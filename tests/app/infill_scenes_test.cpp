// The corner-mode example scenes (scenes/infill/, paper Figs. 9-10) end to end:
// property 1 of the paper, fiber lengths kept, on every frame.
#include <gtest/gtest.h>

#include "flagsim/data/output_reader.hpp"
#include "process.hpp"
#include "temp_dir.hpp"

namespace flagsim::test {
namespace {

class InfillScene : public ::testing::TestWithParam<const char*> {};

TEST_P(InfillScene, EveryLinkWithinOnePercentOnEveryFrame) {
  TempDir dir;
  const std::string scene =
      std::string(FLAGSIM_SOURCE_DIR) + "/scenes/infill/" + GetParam() + ".toml";
  const ProcessResult result = run_flag_sim({"run", scene, "-o", dir.file("run.h5"), "--quiet"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const data::OutputReader reader(dir.file("run.h5"));
  EXPECT_EQ(reader.attribute("mode"), "infill");
  EXPECT_EQ(reader.attribute("effects"), "keyframes,infill,wrinkles");
  ASSERT_EQ(reader.frame_count(), 61);
  const std::vector<double> strain = reader.stat("max_strain");
  for (std::size_t t = 0; t < strain.size(); ++t) EXPECT_LE(strain[t], 0.01) << "frame " << t;
  // Every example moves the bottom fly corner (J-1, K-1) away from its rest place.
  const auto last = reader.positions(reader.frame_count() - 1);
  const auto first = reader.positions(0);
  EXPECT_GT((last.back() - first.back()).norm(), 0.1);
}

INSTANTIATE_TEST_SUITE_P(Scenes, InfillScene,
                         ::testing::Values("pushed", "sheared", "twisted", "lifted"));

}  // namespace
}  // namespace flagsim::test
