// `flag-sim run --resume OUT.h5` (issue 30, item 4): a run continued from the
// checkpoint its file keeps holds the frames an uninterrupted run of the same
// length holds, bit for bit, in every mode and backend; what cannot be
// continued is said before anything is written, and the file stays as it was.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "flagsim/data/output_reader.hpp"
#include "process.hpp"
#include "temp_dir.hpp"

namespace flagsim::test {
namespace {

namespace fs = std::filesystem;

// Everything a run file holds of the simulation (not its wall times): every
// frame's fields, the coarse trajectory, the statistics and the checkpoint.
std::vector<double> contents_of(const std::string& path) {
  const data::OutputReader reader(path);
  std::vector<double> values = reader.times_s();
  const auto add = [&values](const std::vector<Vec3>& nodes) {
    for (const Vec3& p : nodes) values.insert(values.end(), p.data(), p.data() + 3);
  };
  for (int t = 0; t < reader.frame_count(); ++t) {
    if (reader.dense()) {
      add(reader.positions(t));
      add(reader.velocities(t));
      const std::vector<double> strain = reader.node_strain(t);
      values.insert(values.end(), strain.begin(), strain.end());
    }
    add(reader.coarse_positions(t));
  }
  for (int t = 0; t < reader.trajectory_frames(); ++t) {
    add(reader.coarse_trajectory(t));
    const std::vector<double> memory = reader.coarse_memory(t);
    values.insert(values.end(), memory.begin(), memory.end());
  }
  for (const char* stat : {"max_strain", "mean_strain", "kinetic_energy", "infill_converged",
                           "infill_residual", "infill_iterations", "coarse_offset"}) {
    const std::vector<double> series = reader.stat(stat);
    values.insert(values.end(), series.begin(), series.end());
  }
  const std::optional<data::Checkpoint> checkpoint = reader.checkpoint();
  EXPECT_TRUE(checkpoint.has_value()) << path;
  if (checkpoint) {
    values.insert(values.end(), {double(checkpoint->frame), double(checkpoint->written_frames),
                                 double(checkpoint->trajectory_frames)});
    for (const data::Checkpoint::Part& part : checkpoint->parts)
      values.insert(values.end(), part.owned.begin(), part.owned.end());
  }
  return values;
}

struct Case {
  const char* name;
  std::vector<std::string> args;  // the scene and its --set, as for `run`
};

TEST(Resume, AContinuedRunHoldsTheFramesOfAnUninterruptedOneInEveryModeAndBackend) {
  // 13 frames at once, against 5 and then --resume to 13 (flush_every 2 puts
  // checkpoints mid-run too: the one at the end must win).
  const std::vector<std::string> small = {"--set", "flag.fine=[17,25]", "--set",
                                          "output.flush_every=2"};
  const auto with = [&small](std::vector<std::string> args) {
    args.insert(args.end(), small.begin(), small.end());
    return args;
  };
  const std::vector<Case> cases = {
      {"hybrid", with({})},
      {"hybrid, bullet", with({"--set", "solver.backend=\"bullet\""})},
      {"hybrid, xpbd", with({"--set", "solver.backend=\"xpbd\""})},
      {"hybrid, implicit", with({"--set", "solver.backend=\"implicit\""})},
      {"hybrid, coarse trajectory only", with({"--set", "output.dense=false"})},
      {"hybrid, every 3rd frame", with({"--set", "output.every=3"})},
      {"hybrid, wrinkles and gusts",
       with({FLAGSIM_SOURCE_DIR "/scenes/hard/hybrid_storm_wrinkles.toml", "--set",
             "output.dense=false"})},
      {"hybrid, creased, coarse trajectory only (the creases' angles kept and copied)",
       with({std::string(FLAGSIM_SOURCE_DIR) + "/scenes/creases/folded_15ms.toml", "--set",
             "creases.relax_time=0.05", "--set", "output.dense=false"})},
      {"mass-spring", with({"--mode", "mass-spring"})},
      {"mass-spring, creased (the creases' rest angles go on)",
       with({"--mode", "mass-spring", "--set", "flag.folds=[{axis=\"col\",at=0.5,angle=2.5}]",
             "--set", "bending.stiffness=1e-4", "--set", "creases.set_time=1.0"})},
      {"bullet", with({"--mode", "bullet"})},
      {"implicit", with({"--mode", "implicit"})},
      {"xpbd", with({"--mode", "xpbd"})},
      {"infill",
       {FLAGSIM_SOURCE_DIR "/scenes/infill/twisted.toml", "--set", "output.flush_every=2"}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    TempDir dir;
    const auto run = [&](const std::string& out, const char* frames) {
      std::vector<std::string> args = {"run", "-o", out, "--frames", frames, "--quiet"};
      args.insert(args.end(), c.args.begin(), c.args.end());
      return run_flag_sim(args, dir.path());
    };
    ProcessResult result = run("whole.h5", "13");
    ASSERT_EQ(result.exit_code, 0) << result.err;
    result = run("part.h5", "5");
    ASSERT_EQ(result.exit_code, 0) << result.err;
    result = run_flag_sim({"run", "--resume", "part.h5", "--frames", "13", "--quiet"}, dir.path());
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(result.out.rfind("complete: ", 0), 0u) << result.out;
    const std::vector<double> whole = contents_of(dir.file("whole.h5")),
                              part = contents_of(dir.file("part.h5"));
    ASSERT_EQ(whole.size(), part.size());
    EXPECT_TRUE(whole == part) << "the continued run's frames differ";
    const data::OutputReader reader(dir.file("part.h5"));
    EXPECT_EQ(reader.attribute("status"), "complete");
    EXPECT_NE(reader.attribute("status_reason").find("frames 5 on by run --resume"),
              std::string::npos)
        << reader.attribute("status_reason");
    EXPECT_EQ(reader.attribute("scene"),
              data::OutputReader(dir.file("whole.h5")).attribute("scene"));
  }
}

TEST(Resume, ByDurationAndToAnotherFileTheFirstStaysAsItWas) {
  TempDir dir;
  const std::vector<std::string> scene = {"--set", "flag.fine=[17,25]", "--set",
                                          "scene.duration=0.2"};
  auto args = std::vector<std::string>{"run", "-o", "short.h5", "--quiet"};
  args.insert(args.end(), scene.begin(), scene.end());
  ASSERT_EQ(run_flag_sim(args, dir.path()).exit_code, 0);
  args[2] = "long.h5";
  args.back() = "scene.duration=0.5";
  ASSERT_EQ(run_flag_sim(args, dir.path()).exit_code, 0);
  const std::string before = file_bytes(dir.file("short.h5"));
  const ProcessResult result =
      run_flag_sim({"run", "--resume", "short.h5", "--set", "scene.duration=0.5", "-o",
                    "sub/continued.h5", "--quiet"},
                   dir.path());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(file_bytes(dir.file("short.h5")), before) << "-o elsewhere: the resumed file changed";
  EXPECT_TRUE(fs::exists(dir.file("sub/continued.xdmf")));
  EXPECT_TRUE(contents_of(dir.file("long.h5")) == contents_of(dir.file("sub/continued.h5")));
}

TEST(Resume, WhatCannotBeContinuedIsSaidAndNothingIsWritten) {
  TempDir dir;
  const auto run = [&dir](const std::vector<std::string>& args) {
    return run_flag_sim(args, dir.path());
  };
  const std::vector<std::string> small = {"--set", "flag.fine=[17,25]", "--quiet"};
  const auto make = [&](const std::string& out, const std::vector<std::string>& extra) {
    std::vector<std::string> args = {"run", "-o", out, "--frames", "4"};
    args.insert(args.end(), small.begin(), small.end());
    args.insert(args.end(), extra.begin(), extra.end());
    return run(args);
  };
  ASSERT_EQ(make("done.h5", {}).exit_code, 0);
  ASSERT_EQ(make("bare.h5", {"--set", "output.checkpoint=false"}).exit_code, 0);
  ASSERT_EQ(make("blown.h5", {"--set", "limits.max_strain=0.0001"}).exit_code, 3);
  const std::string done = file_bytes(dir.file("done.h5"));
  const std::vector<std::pair<std::vector<std::string>, std::string>> refusals = {
      {{"run", "--resume", "done.h5"},
       "error: done.h5: already holds frames 0 to 3 (t = 0 .. 0.1 s) of its 4-frame scene; give "
       "--frames or --set scene.duration=T beyond them to continue it\n"},
      {{"run", "--resume", "done.h5", "--set", "scene.duration=2"},
       "error: --set scene.duration=2: the scene in done.h5 fixes its length with scene.frames "
       "(run --frames); continue it with --frames N\n"},
      {{"run", "--resume", "done.h5", "--frames", "9", "--mode", "xpbd"},
       "error: --mode xpbd: run --resume continues the run in done.h5 with its own scene; it "
       "takes --frames, --set scene.duration=T, -o, --quiet and --render (to run another scene, "
       "leave out --resume)\n"},
      {{"run", "--resume", "done.h5", "--frames", "9", "--set", "wind.velocity=[5,0,0]"},
       "error: --set wind.velocity=[5,0,0]: run --resume continues the run in done.h5 with its "
       "own scene; it takes --frames, --set scene.duration=T, -o, --quiet and --render (to run "
       "another scene, leave out --resume)\n"},
      {{"run", "--resume", "bare.h5", "--frames", "9"},
       "error: bare.h5: holds no checkpoint to continue from (its scene has output.checkpoint = "
       "false, its run was stopped before its first flush, or an older flag-sim wrote it); run "
       "its scene again with the longer duration\n"},
      {{"run", "--resume", "done.h5.partial", "--frames", "9"},
       "error: done.h5.partial: the unfinished file of a run that was killed (or is still "
       "running); when no run writes it, rename it to done.h5 and continue that\n"},
  };
  for (const auto& [args, message] : refusals) {
    const ProcessResult result = run(args);
    EXPECT_EQ(result.exit_code, 2) << result.err;
    EXPECT_EQ(result.err, message);
    EXPECT_FALSE(fs::exists(dir.file("done.h5.partial")));
  }
  const ProcessResult blown = run({"run", "--resume", "blown.h5", "--frames", "9"});
  EXPECT_EQ(blown.exit_code, 2);
  EXPECT_EQ(blown.err.rfind("error: blown.h5: its run diverged (at t = ", 0), 0u) << blown.err;
  EXPECT_EQ(file_bytes(dir.file("done.h5")), done);
  // info says what resume can do: continue done.h5, nothing for the diverged run.
  const ProcessResult info_done = run({"info", "done.h5"});
  EXPECT_NE(info_done.out.find("resume    its state at frame 3 (t = 0.1 s): `flag-sim run "
                               "--resume done.h5 --frames N` continues the run\n"),
            std::string::npos)
      << info_done.out;
  EXPECT_EQ(run({"info", "blown.h5"}).out.find("resume"), std::string::npos);
  EXPECT_NE(run({"info", "bare.h5"}).out.find("resume    no checkpoint"), std::string::npos);
  // A file that is not a run: the reader's own message.
  std::ofstream(dir.file("scene.toml")) << "[scene]\n";
  EXPECT_EQ(run({"run", "--resume", "scene.toml", "--frames", "9"}).exit_code, 2);
}

}  // namespace
}  // namespace flagsim::test
