// [output] dense = false and `flag-sim refine` (issue 33, "resolution on
// demand"): a hybrid run keeps its coarse trajectory only, and refine
// recomputes the dense frames from it, at the run's lattice the very bytes a
// run that stored them holds; render and export take such a file directly.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "flagsim/core/errors.hpp"
#include "flagsim/data/output_reader.hpp"
#include "process.hpp"
#include "temp_dir.hpp"

namespace flagsim::test {
namespace {

namespace fs = std::filesystem;

// Every frame's positions, velocities, strain and coarse nodes, as doubles.
std::vector<double> frames_of(const std::string& path) {
  const data::OutputReader reader(path);
  std::vector<double> values;
  for (int t = 0; t < reader.frame_count(); ++t) {
    for (const auto& nodes :
         {reader.positions(t), reader.velocities(t), reader.coarse_positions(t)})
      for (const Vec3& p : nodes) values.insert(values.end(), p.data(), p.data() + 3);
    const std::vector<double> strain = reader.node_strain(t);
    values.insert(values.end(), strain.begin(), strain.end());
  }
  for (const char* stat : {"max_strain", "mean_strain", "kinetic_energy", "infill_residual"}) {
    const std::vector<double> series = reader.stat(stat);
    values.insert(values.end(), series.begin(), series.end());
  }
  return values;
}

ProcessResult run_in(const TempDir& dir, const std::vector<std::string>& args) {
  return run_flag_sim(args, dir.path());
}

TEST(Refine, GivesTheFramesOfARunThatStoredThemBitForBit) {
  // The default scene (smooth infill) with output.every = 3, and a wrinkled
  // storm (3.5 remembers each wave's side from frame to frame): both need
  // every simulated frame's coarse nodes, not only the written ones.
  const std::string wrinkles =
      fs::absolute(FLAGSIM_SOURCE_DIR "/scenes/hard/hybrid_storm_wrinkles.toml");
  // And a flag creased in four whose creases relax within the run: the dense
  // frames draw each frame's crease angles (/coarse/memory), not the start's.
  const std::string creased = fs::absolute(FLAGSIM_SOURCE_DIR "/scenes/creases/folded_15ms.toml");
  const std::vector<std::vector<std::string>> scenes = {
      {"--set", "output.every=3"},
      {wrinkles, "--set", "infill.solver=\"paper\""},
      {creased, "--set", "creases.relax_time=0.05"}};
  for (const auto& scene : scenes) {
    SCOPED_TRACE(scene.front());
    TempDir dir;
    // The scene file first: --set takes every word up to the next option.
    std::vector<std::string> common = {"run"};
    common.insert(common.end(), scene.begin(), scene.end());
    common.insert(common.end(), {"--quiet", "--frames", "10", "--set", "flag.fine=[33,49]"});
    std::vector<std::string> dense = common, coarse = common;
    dense.insert(dense.end(), {"-o", "dense.h5"});
    coarse.insert(coarse.end(), {"-o", "coarse.h5", "--set", "output.dense=false"});
    ASSERT_EQ(run_in(dir, dense).exit_code, 0);
    const ProcessResult ran = run_in(dir, coarse);
    ASSERT_EQ(ran.exit_code, 0) << ran.err;
    EXPECT_NE(ran.out.find("note: output.dense = false: coarse.h5 keeps the coarse trajectory"),
              std::string::npos)
        << ran.out;
    EXPECT_FALSE(fs::exists(dir.file("coarse.xdmf")));  // no frames for ParaView to show
    {
      const data::OutputReader reader(dir.file("coarse.h5"));
      EXPECT_FALSE(reader.dense());
      EXPECT_EQ(reader.trajectory_frames(), 10);  // every simulated frame
      EXPECT_THROW(reader.positions(0), UserError);
      // The creases' angles of every simulated frame, and only with creases.
      EXPECT_EQ(reader.coarse_memory(9).empty(), scene.front() != creased);
      if (scene.front() == creased) {
        EXPECT_NE(reader.coarse_memory(9), reader.coarse_memory(0));
      }
    }
    const ProcessResult info = run_in(dir, {"info", "coarse.h5"});
    EXPECT_EQ(info.out.find("with each one's crease angles") != std::string::npos,
              scene.front() == creased)
        << info.out;
    const ProcessResult refined = run_in(dir, {"refine", "coarse.h5", "-o", "refined.h5", "-q"});
    ASSERT_EQ(refined.exit_code, 0) << refined.err;
    EXPECT_NE(refined.out.find("refined: "), std::string::npos) << refined.out;
    EXPECT_EQ(frames_of(dir.file("refined.h5")), frames_of(dir.file("dense.h5")));
    const data::OutputReader reader(dir.file("refined.h5"));
    EXPECT_EQ(reader.attribute("status"), "complete");
    EXPECT_NE(reader.attribute("status_reason").find("refined from coarse.h5"), std::string::npos);
  }
}

TEST(Refine, AtAnotherLatticeAndWhatItRefuses) {
  TempDir dir;
  ASSERT_EQ(run_in(dir, {"run", "-q", "--frames", "6", "--set", "flag.fine=[17,25]", "--set",
                         "output.dense=false", "-o", "c.h5"})
                .exit_code,
            0);
  const ProcessResult finer =
      run_in(dir, {"refine", "c.h5", "-o", "f.h5", "--set", "flag.fine=[65,97]"});
  ASSERT_EQ(finer.exit_code, 0) << finer.err;
  {
    const data::OutputReader reader(dir.file("f.h5"));
    EXPECT_EQ(reader.rows(), 65);
    EXPECT_EQ(reader.frame_count(), 6);
    const data::OutputReader source(dir.file("c.h5"));
    EXPECT_EQ(reader.coarse_positions(5), source.coarse_positions(5));  // the same coarse run
  }
  const auto refused = [&](const std::vector<std::string>& args, const std::string& message) {
    SCOPED_TRACE(args.back());
    const int before = dir.entry_count();
    const ProcessResult result = run_in(dir, args);
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_TRUE(result.err.starts_with("error: ")) << result.err;
    EXPECT_NE(result.err.find(message), std::string::npos) << result.err;
    EXPECT_EQ(result.err.find('\n'), result.err.size() - 1) << result.err;  // one line
    EXPECT_EQ(dir.entry_count(), before);                                   // nothing left behind
  };
  refused({"refine", "c.h5", "-o", "x.h5", "--set", "wind.velocity=[3,0,0]"},
          "--set wind.velocity=[3,0,0]: refine recomputes the dense frames");
  refused({"refine", "c.h5", "-o", "x.h5", "--set", "output.dense=false"}, "output.dense");
  refused({"refine", "f.h5", "-o", "x.h5"}, "f.h5: holds no coarse trajectory to refine");
  refused({"refine", "c.h5", "-o", "./c.h5"}, "would overwrite the coarse trajectory");
  refused({"refine", "c.h5", "-o", "x.h5", "--set", "flag.fine=[18,25]"}, "flag.coarse");
  dir.write("ms.toml",
            "[scene]\nmode = \"mass-spring\"\n[flag]\nfine = [9, 13]\n"
            "[output]\ndense = false\n");
  refused({"run", "ms.toml", "-o", "x.h5"}, "ms.toml:6");
  // A mode chosen on the command line ignores it, with a note.
  const ProcessResult noted = run_in(dir, {"run", "-q", "--frames", "2", "--mode", "mass-spring",
                                           "--set", "output.dense=false", "-o", "m.h5"});
  EXPECT_EQ(noted.exit_code, 0) << noted.err;
  EXPECT_NE(noted.out.find("does not use output.dense = false: ignored"), std::string::npos)
      << noted.out;
  EXPECT_TRUE(data::OutputReader(dir.file("m.h5")).dense());
}

TEST(Refine, RenderAndExportTakeACoarseTrajectoryDirectly) {
  TempDir dir;
  const std::vector<std::string> run = {"run", "-q", "--frames", "4", "--set", "flag.fine=[17,25]"};
  std::vector<std::string> dense = run, coarse = run;
  dense.insert(dense.end(), {"-o", "d.h5"});
  coarse.insert(coarse.end(), {"-o", "c.h5", "--set", "output.dense=false"});
  ASSERT_EQ(run_in(dir, dense).exit_code, 0);
  ASSERT_EQ(run_in(dir, coarse).exit_code, 0);
  for (const char* input : {"d.h5", "c.h5"}) {
    const std::string name(input, 1);
    const ProcessResult rendered =
        run_in(dir, {"render", input, "-o", name + "_png/", "--frames", "2:4", "--size", "160x90"});
    ASSERT_EQ(rendered.exit_code, 0) << rendered.err;
    const ProcessResult exported =
        run_in(dir, {"export", input, "-o", name + "_obj/", "--frames", "3:4"});
    ASSERT_EQ(exported.exit_code, 0) << exported.err;
  }
  for (const char* file : {"_png/frame_00002.png", "_png/frame_00003.png"})
    EXPECT_TRUE(file_bytes(dir.file(std::string("c") + file)) ==
                file_bytes(dir.file(std::string("d") + file)))
        << file;
  // The OBJs differ in their first line only, which names the input.
  const std::string from_coarse = file_bytes(dir.file("c_obj/frame_00003.obj"));
  const std::string from_dense = file_bytes(dir.file("d_obj/frame_00003.obj"));
  EXPECT_TRUE(from_coarse.starts_with("# flag-sim"));
  EXPECT_TRUE(from_coarse.substr(from_coarse.find('\n')) ==
              from_dense.substr(from_dense.find('\n')));
  const ProcessResult info = run_in(dir, {"info", "c.h5"});
  EXPECT_NE(info.out.find("stored    the coarse trajectory only"), std::string::npos) << info.out;
  // The refined copy was temporary.
  for (const auto& entry : fs::directory_iterator(fs::temp_directory_path()))
    EXPECT_EQ(entry.path().filename().string().find("flag-sim-refine."), std::string::npos);
}

TEST(Refine, KeepsTheStatusOfARunThatDiverged) {
  TempDir dir;
  const ProcessResult ran = run_in(
      dir, {"run", "-q", "--set", "flag.fine=[33,49]", "--set", "output.dense=false", "--set",
            "flag.stretch_modulus=1.0", "--set", "limits.max_strain=0.05", "-o", "c.h5"});
  ASSERT_EQ(ran.exit_code, 3) << ran.err;
  const ProcessResult refined = run_in(dir, {"refine", "c.h5", "-o", "r.h5", "-q"});
  EXPECT_EQ(refined.exit_code, 0) << refined.err;
  EXPECT_NE(refined.out.find("(the run: diverged)"), std::string::npos) << refined.out;
  const data::OutputReader source(dir.file("c.h5")), reader(dir.file("r.h5"));
  EXPECT_EQ(reader.attribute("status"), "diverged");
  EXPECT_EQ(reader.frame_count(), source.frame_count());
  EXPECT_NE(reader.attribute("status_reason").find(source.attribute("status_reason")),
            std::string::npos);
}

}  // namespace
}  // namespace flagsim::test
