#include "flagsim/data/frame_writer.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "flagsim/core/errors.hpp"
#include "flagsim/data/output_reader.hpp"
#include "temp_dir.hpp"

namespace flagsim::data {
namespace {

namespace fs = std::filesystem;

RunInfo info() {
  RunInfo run;
  run.mode = "mass-spring";
  run.effects = {"stretch", "gravity"};
  run.scene_toml = "[scene]\nname = \"t\"\n";
  run.version = "test";
  run.seed = 42;
  run.stages = {"stretch", "gravity", "output"};
  run.output_stage = 2;
  run.numbers = {{"substep_seconds", 1e-4, "s"}, {"substeps_per_frame", 7.0, "1", true}};
  return run;
}

TEST(FrameWriter, RoundTripThroughTheCApi) {
  test::TempDir dir;
  const Lattice lattice = Lattice::rectangle(3, 4, 1.5, 1.0, Vec3(0, 2, 0));
  const std::string path = dir.file("run.h5");
  {
    FrameWriter writer(path, lattice, info(), 2);
    EXPECT_TRUE(fs::exists(path + ".partial"));
    EXPECT_FALSE(fs::exists(path));
    std::vector<Vec3> x = lattice.rest_positions();
    std::vector<Vec3> v(x.size());
    std::vector<float> strain(x.size());
    const double stages[3] = {0.25, 0.5, 0.0};
    for (int t = 0; t < 3; ++t) {
      for (std::size_t i = 0; i < x.size(); ++i) {
        x[i].z() = 0.1 * t;
        v[i] = Vec3(double(i), -0.5 * t, 3.0);
        strain[i] = 1e-3f * float(i + t);
      }
      writer.write_frame(t / 30.0, {x, v, strain},
                         FrameStats{0.01 * t, 0.001 * t, stages, 1.0, 2.0, {}});
    }
    writer.finish({RunState::kComplete, "all frames written"});
  }
  EXPECT_FALSE(fs::exists(path + ".partial"));
  ASSERT_TRUE(fs::exists(path));
  EXPECT_TRUE(fs::exists(dir.file("run.xdmf")));

  const OutputReader reader(path);
  EXPECT_EQ(reader.attribute("format"), "flag-sim/1");
  EXPECT_EQ(reader.attribute("status"), "complete");
  EXPECT_EQ(reader.attribute("mode"), "mass-spring");
  EXPECT_EQ(reader.attribute("effects"), "stretch,gravity");
  EXPECT_EQ(reader.attribute("scene"), "[scene]\nname = \"t\"\n");
  EXPECT_EQ(reader.seed(), 42);
  EXPECT_DOUBLE_EQ(reader.number_attribute("substep_seconds", 0), 1e-4);
  EXPECT_EQ(reader.attribute("substep_seconds.units"), "s");
  EXPECT_EQ(reader.number_attribute("substeps_per_frame", 0), 7.0);
  EXPECT_EQ(reader.attribute("seed.units"), "1");
  EXPECT_EQ(reader.frame_count(), 3);
  EXPECT_EQ(reader.rows(), 3);
  EXPECT_EQ(reader.cols(), 4);
  EXPECT_EQ(reader.times_s(), (std::vector<double>{0.0, 1 / 30.0, 2 / 30.0}));
  const auto frame = reader.positions(2);
  EXPECT_EQ(frame[lattice.index(2, 3)], Vec3(1.5, 1.0, double(0.2f)));
  EXPECT_EQ(reader.rest_positions()[lattice.index(0, 3)], Vec3(1.5, 2.0, 0.0));
  const std::size_t node = lattice.index(1, 2);
  EXPECT_EQ(reader.velocities(2)[node], Vec3(double(node), -1.0, 3.0));
  EXPECT_EQ(reader.node_strain(1)[node], double(1e-3f * float(node + 1)));
  EXPECT_THROW(reader.velocities(3), UserError);
  EXPECT_EQ(reader.stat("max_strain")[2], double(0.02f));
  EXPECT_EQ(reader.stage_names(), info().stages);
  const auto stages = reader.stage_seconds();
  ASSERT_EQ(stages.size(), 3u);
  EXPECT_EQ(stages[1][0], 0.25);
  EXPECT_GT(stages[1][2], 0.0);  // the writer timed itself into "output"
  EXPECT_GE(reader.stat("wall_seconds")[1], 1.0);
}

TEST(FrameWriter, FieldsOfTheWrongSizeAreRefused) {
  test::TempDir dir;
  const Lattice lattice = Lattice::rectangle(3, 4, 1.5, 1.0, Vec3(0, 2, 0));
  FrameWriter writer(dir.file("run.h5"), lattice, info(), 2);
  const std::vector<Vec3> x = lattice.rest_positions(), short_v(3);
  const std::vector<float> strain(x.size());
  const double stages[3] = {0.0, 0.0, 0.0};
  EXPECT_THROW(writer.write_frame(0.0, {x, short_v, strain}, FrameStats{0, 0, stages, 0, 0, {}}),
               std::invalid_argument);
  EXPECT_EQ(writer.frames_written(), 0);
}

TEST(FrameWriter, FieldsTheRunDidNotAskForAreNotWritten) {
  test::TempDir dir;
  const Lattice lattice = Lattice::rectangle(3, 4, 1.5, 1.0, Vec3(0, 2, 0));
  const std::string path = dir.file("run.h5");
  {
    RunInfo run = info();
    run.fields = {};
    FrameWriter writer(path, lattice, run, 2);
    const std::vector<Vec3> x = lattice.rest_positions();
    const double stages[3] = {0.0, 0.0, 0.0};
    writer.write_frame(0.0, {x, {}, {}}, FrameStats{0, 0, stages, 0, 0, {}});
    writer.finish({RunState::kComplete, "all frames written"});
  }
  const OutputReader reader(path);
  EXPECT_EQ(reader.positions(0).size(), lattice.node_count());
  EXPECT_TRUE(reader.velocities(0).empty());
  EXPECT_TRUE(reader.node_strain(0).empty());
}

TEST(FrameWriter, UncreatableOutputIsAUserErrorAndLeavesNothing) {
  test::TempDir dir;
  const Lattice lattice = Lattice::rectangle(2, 2, 1, 1, Vec3::Zero());
  const std::string blocker = dir.write("plain_file", "x");  // a file where a directory should be
  EXPECT_THROW(FrameWriter(blocker + "/run.h5", lattice, info(), 1), UserError);
  EXPECT_EQ(dir.entry_count(), 1);
}

TEST(FrameWriter, OutputPathThatIsADirectoryIsAUserError) {
  test::TempDir dir;
  const Lattice lattice = Lattice::rectangle(2, 2, 1, 1, Vec3::Zero());
  EXPECT_THROW(FrameWriter(dir.path(), lattice, info(), 1), UserError);
}

}  // namespace
}  // namespace flagsim::data
