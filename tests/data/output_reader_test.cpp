#include "flagsim/data/output_reader.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "flagsim/core/errors.hpp"
#include "flagsim/data/frame_writer.hpp"
#include "temp_dir.hpp"

namespace flagsim::data {
namespace {

// A complete two-frame run of a 5 x 7 lattice; with `coarse`, its coarse
// nodes are dense rows {0, 2, 4} and columns {0, 3, 6}, written as the hybrid writes them.
std::string write_run(const test::TempDir& dir, const std::string& name, bool coarse) {
  const Lattice lattice = Lattice::rectangle(5, 7, 1.5, 1.0, Vec3(0, 2, 0));
  RunInfo run;
  run.mode = coarse ? "hybrid" : "mass-spring";
  run.scene_toml = "[scene]\n";
  run.version = "test";
  run.stages = {"output"};
  run.output_stage = 0;
  if (coarse) {
    run.coarse_rows = {0, 2, 4};
    run.coarse_cols = {0, 3, 6};
  }
  std::string path = dir.file(name);  // returned: not const, moved
  FrameWriter writer(path, lattice, run, 1);
  std::vector<Vec3> x = lattice.rest_positions();
  const std::vector<Vec3> v(x.size(), Vec3::Zero());
  const std::vector<float> strain(x.size(), 0.0f);
  std::vector<Vec3> c(9);
  const double stages[1] = {0.0};
  for (int t = 0; t < 2; ++t) {
    for (Vec3& p : x) p.z() = 0.25 * t;
    for (int jc = 0; jc < 3; ++jc)
      for (int kc = 0; kc < 3; ++kc)
        c[std::size_t(jc) * 3 + std::size_t(kc)] = x[lattice.index(2 * jc, 3 * kc)];
    FrameFields fields{x, v, strain};
    if (coarse) fields.coarse_m = c;
    writer.write_frame(t / 30.0, fields, FrameStats{0, 0, stages, 0, 0, {}});
  }
  writer.finish({RunState::kComplete, "all frames written"});
  return path;
}

std::string error_of(const std::string& path) {
  try {
    const OutputReader reader(path);
  } catch (const UserError& e) {
    return e.what();
  }
  return "no error";
}

TEST(OutputReader, ForeignAndMissingFilesAreUserErrorsNamingTheFile) {
  test::TempDir dir;
  const std::string missing = dir.file("missing.h5"), text = dir.write("text.h5", "not hdf5");
  EXPECT_NE(error_of(missing).find(missing), std::string::npos) << error_of(missing);
  EXPECT_NE(error_of(text).find(text), std::string::npos) << error_of(text);
}

TEST(OutputReader, ReadsTheCoarseNodesOfAHybridRunAndNoneOtherwise) {
  test::TempDir dir;
  const OutputReader hybrid(write_run(dir, "h.h5", true));
  EXPECT_EQ(hybrid.coarse_rows(), (std::vector<int>{0, 2, 4}));
  EXPECT_EQ(hybrid.coarse_cols(), (std::vector<int>{0, 3, 6}));
  const std::vector<Vec3> coarse = hybrid.coarse_positions(1), dense = hybrid.positions(1);
  ASSERT_EQ(coarse.size(), 9u);
  EXPECT_EQ(coarse[4], dense[std::size_t(2 * 7 + 3)]);  // coarse (1, 1) is dense (2, 3)
  EXPECT_EQ(coarse[4].z(), 0.25);
  const OutputReader plain(write_run(dir, "m.h5", false));
  EXPECT_TRUE(plain.coarse_rows().empty());
  EXPECT_TRUE(plain.coarse_positions(0).empty());
}

TEST(OutputReader, AFrameOutsideTheFileIsAUserError) {
  test::TempDir dir;
  const OutputReader reader(write_run(dir, "m.h5", false));
  ASSERT_EQ(reader.frame_count(), 2);
  EXPECT_NO_THROW(reader.positions(1));
  EXPECT_THROW(reader.positions(2), UserError);
  EXPECT_THROW(reader.positions(-1), UserError);
}

}  // namespace
}  // namespace flagsim::data
