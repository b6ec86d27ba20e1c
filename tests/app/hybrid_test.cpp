// `scene.mode = "hybrid"` end to end: spring-damper physics on flag.coarse, the
// paper's infill on flag.fine, both written out.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <utility>

#include "flagsim/core/lattice.hpp"
#include "flagsim/data/output_reader.hpp"
#include "process.hpp"
#include "temp_dir.hpp"
#include "tolerances.hpp"

namespace flagsim::test {
namespace {

const std::vector<std::string> kHybrid = {
    "run",      "--mode", "hybrid", "--set", "flag.fine=[33,49]", "--set", "flag.coarse=[9,13]",
    "--frames", "16",     "--quiet"};

std::vector<std::string> with_output(const std::string& path) {
  std::vector<std::string> args = kHybrid;
  args.push_back("-o");
  args.push_back(path);
  return args;
}

TEST(Hybrid, CoarseNodesAreWrittenAndTheDenseLatticeFollowsThem) {
  TempDir dir;
  const ProcessResult result = run_flag_sim(with_output("h.h5"), dir.path());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const data::OutputReader reader(dir.file("h.h5"));
  EXPECT_EQ(reader.attribute("mode"), "hybrid");
  EXPECT_EQ(reader.attribute("effects"), "stretch,gravity,wind,damping,infill");
  ASSERT_EQ(reader.frame_count(), 16);
  EXPECT_EQ(reader.coarse_rows(), (std::vector<int>{0, 4, 8, 12, 16, 20, 24, 28, 32}));
  EXPECT_EQ(reader.coarse_cols().size(), 13u);
  EXPECT_EQ(reader.coarse_cols().back(), 48);
  // The coarse nodes are the mean surface: each dense counterpart is within
  // the reported offset, a small part of a cell side (0.125 m) in the median
  // frame (measured 6 mm over the default scene's 10 s) and under 0.4 of it
  // where the physics folds a coarse link sharply (4.1 cm, t = 0.5 s).
  const std::vector<double> offset = reader.stat("coarse_offset");
  ASSERT_EQ(offset.size(), 16u);
  for (int t : {0, 7, 15}) {
    const auto dense = reader.positions(t);
    const auto coarse = reader.coarse_positions(t);
    ASSERT_EQ(coarse.size(), 9u * 13u);
    const NodeView dense_at(33, 49, dense), coarse_at(9, 13, coarse);
    double largest = 0.0;
    for (int j = 0; j < 9; ++j)
      for (int k = 0; k < 13; ++k)
        largest =
            std::max(largest, double((dense_at.at(4 * j, 4 * k) - coarse_at.at(j, k)).norm()));
    EXPECT_NEAR(largest, offset[std::size_t(t)], test::kFloat32) << t;
  }
  std::vector<double> sorted = offset;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_LT(sorted[sorted.size() / 2], 0.1 * 0.125);
  EXPECT_LT(sorted.back(), 0.4 * 0.125);
  EXPECT_EQ(offset[0], 0.0);  // at rest the surface is the flat flag
  for (double converged : reader.stat("infill_converged")) EXPECT_EQ(converged, 1.0);
}

TEST(Hybrid, SameSeedSameBytesWithEveryBackend) {
  // Everything but the wall-clock stage times: dense and coarse positions,
  // strain and kinetic energy, bit for bit.
  for (const char* backend : {"spring-damper", "bullet", "implicit", "xpbd"}) {
    TempDir dir;
    auto args = [&](const char* file) {
      std::vector<std::string> a = with_output(file);
      a.insert(a.end(), {"--set", std::string("solver.backend=") + backend});
      return a;
    };
    ASSERT_EQ(run_flag_sim(args("a.h5"), dir.path()).exit_code, 0) << backend;
    ASSERT_EQ(run_flag_sim(args("b.h5"), dir.path()).exit_code, 0) << backend;
    const data::OutputReader a(dir.file("a.h5")), b(dir.file("b.h5"));
    ASSERT_EQ(a.frame_count(), 16) << backend;
    auto same = [](const std::vector<Vec3>& x, const std::vector<Vec3>& y) {
      return x.size() == y.size() && 0 == std::memcmp(x.data(), y.data(), x.size() * sizeof(Vec3));
    };
    for (int t = 0; t < a.frame_count(); ++t) {
      EXPECT_TRUE(same(a.positions(t), b.positions(t))) << backend << " frame " << t;
      EXPECT_TRUE(same(a.coarse_positions(t), b.coarse_positions(t))) << backend << " frame " << t;
    }
    EXPECT_EQ(a.stat("max_strain"), b.stat("max_strain")) << backend;
    EXPECT_EQ(a.stat("kinetic_energy"), b.stat("kinetic_energy")) << backend;
  }
}

// The hybrid's physics is the full-lattice integrator run on the coarse
// lattice, bit for bit (issue 35: so its flap, and its error against a finer
// reference, are that run's; docs/results.md). Spring-damper and implicit.
TEST(Hybrid, ItsCoarseNodesAreTheFullLatticeRunOfTheCoarseLattice) {
  for (const auto& [backend, mode] :
       {std::pair{"spring-damper", "mass-spring"}, std::pair{"implicit", "implicit"}}) {
    TempDir dir;
    std::vector<std::string> hybrid = with_output("hybrid.h5");
    hybrid.insert(hybrid.end(), {"--set", std::string("solver.backend=\"") + backend + "\""});
    ASSERT_EQ(run_flag_sim(hybrid, dir.path()).exit_code, 0) << backend;
    const ProcessResult full = run_flag_sim({"run", "--mode", mode, "--set", "flag.fine=[9,13]",
                                             "--frames", "16", "--quiet", "-o", "full.h5"},
                                            dir.path());
    ASSERT_EQ(full.exit_code, 0) << full.err;
    const data::OutputReader h(dir.file("hybrid.h5")), f(dir.file("full.h5"));
    ASSERT_EQ(h.frame_count(), f.frame_count());
    for (int t = 0; t < h.frame_count(); ++t) {
      const std::vector<Vec3> coarse = h.coarse_positions(t), nodes = f.positions(t);
      ASSERT_EQ(coarse.size(), nodes.size());
      // /frames/positions is float32: the coarse nodes rounded the same way.
      for (std::size_t i = 0; i < nodes.size(); ++i)
        ASSERT_EQ(coarse[i].cast<float>(), nodes[i].cast<float>())
            << backend << " frame " << t << " node " << i;
    }
  }
}

TEST(Hybrid, BulletBackendDrivesTheSameInfill) {
  TempDir dir;
  std::vector<std::string> args = with_output("h.h5");
  args.insert(args.end(), {"--set", "solver.backend=bullet"});
  const ProcessResult result = run_flag_sim(args, dir.path());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const data::OutputReader reader(dir.file("h.h5"));
  EXPECT_EQ(reader.attribute("mode"), "hybrid");
  EXPECT_EQ(reader.attribute("effects"), "stretch,gravity,wind,damping,infill");
  const std::vector<std::string> stages = reader.stage_names();
  EXPECT_NE(std::find(stages.begin(), stages.end(), "bullet_step"), stages.end());
  for (double strain : reader.stat("max_strain")) EXPECT_LE(strain, 0.01);
}

TEST(Hybrid, NeedsACoarseLatticeThatDividesTheFineOne) {
  TempDir dir;
  dir.write("s.toml", "[scene]\nmode = \"hybrid\"\n[flag]\nsize = [1.5, 1.0]\nfine = [33, 49]\n");
  const ProcessResult missing =
      run_flag_sim({"run", "s.toml", "--quiet", "-o", "x.h5"}, dir.path());
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("hybrid mode needs flag.coarse"), std::string::npos) << missing.err;
  const ProcessResult uneven = run_flag_sim(
      {"run", "s.toml", "--set", "flag.coarse=[4,5]", "--quiet", "-o", "x.h5"}, dir.path());
  EXPECT_EQ(uneven.exit_code, 2);
  EXPECT_NE(uneven.err.find("coarse rows that work: 2, 3, 5, 9, 17, 33"), std::string::npos)
      << uneven.err;
  EXPECT_EQ(dir.entry_count(), 1);  // the scene only
}

TEST(Hybrid, TakesInfillAndWrinkleSettings) {
  TempDir dir;
  std::vector<std::string> args = with_output("w.h5");
  for (const char* set : {"infill.solver=\"paper\"", "infill.relax_iterations=50",
                          "wrinkles.fiber_radius=0.001", "wrinkles.fiber_modulus=1e9"}) {
    args.push_back("--set");
    args.push_back(set);
  }
  const ProcessResult result = run_flag_sim(args, dir.path());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const data::OutputReader reader(dir.file("w.h5"));
  EXPECT_EQ(reader.attribute("effects"), "stretch,gravity,wind,damping,infill,wrinkles");
  const auto stages = reader.stage_names();
  EXPECT_EQ(stages[stages.size() - 3], "infill_3.5");
}

// The paper solver's cap takes effect: 2 passes a frame, and with them it does
// not converge (33 x 49 from 9 x 13 needs 14-263 measured); the default cap converges.
TEST(Hybrid, TheRelaxationCapIsThePassesAFrameMakes) {
  TempDir dir;
  const std::vector<std::string> base = {"run", "--set", "flag.fine=[33,49]",       "--frames",
                                         "6",   "--set", "infill.solver=\"paper\"", "--quiet"};
  std::vector<std::string> capped = base, free = base;
  capped.insert(capped.end(), {"--set", "infill.relax_iterations=2", "-o", "capped.h5"});
  free.insert(free.end(), {"-o", "free.h5"});
  ASSERT_EQ(run_flag_sim(capped, dir.path()).exit_code, 0);
  ASSERT_EQ(run_flag_sim(free, dir.path()).exit_code, 0);
  const data::OutputReader two(dir.file("capped.h5")), plenty(dir.file("free.h5"));
  const std::vector<double> passes = two.stat("infill_iterations");
  for (std::size_t t = 1; t < passes.size(); ++t) {
    EXPECT_EQ(passes[t], 2.0) << t;
    EXPECT_EQ(two.stat("infill_converged")[t], 0.0) << t;
    EXPECT_EQ(plenty.stat("infill_converged")[t], 1.0) << t;
    EXPECT_GT(plenty.stat("infill_iterations")[t], 2.0) << t;
  }
}

TEST(Hybrid, OnlyTheStagesTheSceneCallsFor) {
  // No [wind], no [wrinkles]: no wind stage, no step 3.5, with any backend.
  TempDir dir;
  dir.write("calm.toml",
            "[scene]\nmode = \"hybrid\"\nduration = 0.1\n[flag]\nsize = [1.5, 1.0]\n"
            "fine = [17, 25]\ncoarse = [9, 13]\n[gravity]\n");
  const std::vector<std::string> infill = {"infill_3.1", "infill_3.3", "infill_3.4", "checks",
                                           "output"};
  const std::map<std::string, std::vector<std::string>> physics = {
      {"spring-damper", {"stretch", "gravity", "integrate"}},
      {"bullet", {"bullet_step"}},
      {"implicit", {"stretch", "gravity", "newton_matrix", "linear_solve"}},
      {"xpbd", {"gravity", "constraints", "integrate"}}};
  for (const auto& [backend, physics_stages] : physics) {
    ASSERT_EQ(run_flag_sim({"run", "calm.toml", "-o", "c.h5", "--quiet", "--set",
                            std::string("solver.backend=") + backend},
                           dir.path())
                  .exit_code,
              0);
    const data::OutputReader reader(dir.file("c.h5"));
    EXPECT_EQ(reader.attribute("effects"), "stretch,gravity,damping,infill") << backend;
    std::vector<std::string> stages = physics_stages;
    stages.insert(stages.end(), infill.begin(), infill.end());
    EXPECT_EQ(reader.stage_names(), stages) << backend;
  }
}

TEST(FullLattice, ImplicitAndXpbdModesRunAndRecordTheirStepping) {
  for (const char* mode : {"implicit", "xpbd"}) {
    TempDir dir;
    const ProcessResult result =
        run_flag_sim({"run", "--mode", mode, "--set", "flag.fine=[9,13]", "--set",
                      "solver.substeps=100", "--frames", "10", "--quiet", "-o", "f.h5"},
                     dir.path());
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const data::OutputReader reader(dir.file("f.h5"));
    EXPECT_EQ(reader.attribute("mode"), mode);
    EXPECT_EQ(reader.attribute("effects"), "stretch,gravity,wind,damping");
    // A floor above XPBD's own 84 (0.125 m links): taken as given.
    EXPECT_EQ(reader.number_attribute("substeps_per_frame", 0), 100.0) << mode;
    EXPECT_TRUE(reader.coarse_positions(0).empty());
    for (double strain : reader.stat("max_strain")) EXPECT_LT(strain, 0.05) << mode;
  }
}

TEST(FullLattice, XpbdPastItsStepCountDivergesSayingWhatToRaise) {
  // The default flag at 33 x 49 at the 338 XPBD substeps a frame its links
  // need (xpbd_propagation_substep_s) stretches a few links by 4% (measured
  // 4.1% over 2 s); held to 2%, it diverges and says what would stretch them less.
  TempDir dir;
  const ProcessResult result =
      run_flag_sim({"run", "--mode", "xpbd", "--set", "flag.fine=[33,49]", "--set",
                    "limits.max_strain=0.02", "--frames", "61", "-o", "x.h5"},
                   dir.path());
  EXPECT_EQ(result.exit_code, 3) << result.err;
  EXPECT_NE(result.err.find("diverged"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("raise solver.substeps (now 338 a frame)"), std::string::npos)
      << result.err;
  const data::OutputReader reader(dir.file("x.h5"));
  EXPECT_GT(reader.frame_count(), 1);  // the good frames are kept
  EXPECT_EQ(reader.attribute("status"), "diverged");
}

TEST(Bullet, FullLatticeModeRunsAndRecordsItsStepping) {
  TempDir dir;
  const ProcessResult result = run_flag_sim({"run", "--mode", "bullet", "--set", "flag.fine=[9,13]",
                                             "--frames", "10", "--quiet", "-o", "b.h5"},
                                            dir.path());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const data::OutputReader reader(dir.file("b.h5"));
  EXPECT_EQ(reader.attribute("mode"), "bullet");
  EXPECT_EQ(reader.attribute("effects"), "stretch,gravity,wind,damping");
  const double substep = reader.number_attribute("substep_seconds", 0);
  EXPECT_GT(substep, 0.0);
  EXPECT_LE(substep, 0.5 * reader.number_attribute("stable_substep_seconds", 0));
  EXPECT_TRUE(reader.coarse_positions(0).empty());  // no /coarse group on the full lattice
  for (double strain : reader.stat("max_strain")) EXPECT_LT(strain, 0.1);
}

TEST(Hybrid, SaysWhenTheWrinklesAskedForAreFinerThanTheLattice) {
  TempDir dir;
  const std::string base =
      "[scene]\nmode = \"hybrid\"\n[flag]\nsize = [1.5, 1.0]\nfine = [33, 49]\ncoarse = [9, 13]\n"
      "[wrinkles]\nfiber_modulus = 1e9\n";
  dir.write("thin.toml", base + "fiber_radius = 0.0002\n");
  dir.write("thick.toml", base + "fiber_radius = 0.002\n");
  const ProcessResult thin = run_flag_sim({"validate", "thin.toml"}, dir.path());
  ASSERT_EQ(thin.exit_code, 0) << thin.err;
  const std::size_t note = thin.out.find("note: [wrinkles] asks for waves of 0.0575 m");
  EXPECT_NE(note, std::string::npos) << thin.out;
  EXPECT_NE(thin.out.find("a lattice of 210 or more columns would carry them"), std::string::npos);
  EXPECT_EQ(thin.out.find("note:", note + 1), std::string::npos);  // one line
  const ProcessResult thick = run_flag_sim({"validate", "thick.toml"}, dir.path());
  ASSERT_EQ(thick.exit_code, 0) << thick.err;
  EXPECT_EQ(thick.out.find("note:"), std::string::npos) << thick.out;
  const ProcessResult run =
      run_flag_sim({"run", "thin.toml", "--frames", "2", "--quiet", "-o", "t.h5"}, dir.path());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("note: [wrinkles] asks for waves"), std::string::npos) << run.out;
}

}  // namespace
}  // namespace flagsim::test
