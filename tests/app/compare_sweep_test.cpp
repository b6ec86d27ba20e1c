// `flag-sim compare` and `flag-sim sweep` end to end, on a small lattice.
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "process.hpp"
#include "temp_dir.hpp"
#include "tolerances.hpp"

namespace flagsim::test {
namespace {
namespace fs = std::filesystem;

const std::vector<std::string> kSmall = {"--set", "flag.fine=[17,25]", "--frames", "21"};

std::vector<std::vector<std::string>> read_csv(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream fields(line);
    std::string cell;
    while (std::getline(fields, cell, ',')) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    rows.push_back(cells);
  }
  return rows;
}

std::size_t column(const std::vector<std::vector<std::string>>& csv, const std::string& name) {
  for (std::size_t i = 0; i < csv[0].size(); ++i)
    if (csv[0][i] == name) return i;
  ADD_FAILURE() << "no column " << name;
  return 0;
}

// Every column but the wall-clock ones.
std::vector<std::vector<std::string>> without_timing(std::vector<std::vector<std::string>> csv) {
  const std::size_t ms = column(csv, "ms_per_frame"), physics = column(csv, "physics_ms"),
                    infill = column(csv, "infill_ms");
  for (auto& row : csv)
    for (std::size_t c : {ms, physics, infill}) row[c] = "";
  return csv;
}

// `sweep --coarse 5x7 --quiet` on the small lattice, then `extra`.
std::vector<std::string> small_5x7_sweep(const std::vector<std::string>& extra) {
  std::vector<std::string> args = {"sweep", "--coarse", "5x7", "--quiet"};
  args.insert(args.end(), kSmall.begin(), kSmall.end());
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

TEST(Compare, WritesTheContractColumnsForEachRun) {
  TempDir dir;
  std::vector<std::string> args = {"compare", "-o", "report.csv"};
  args.insert(args.end(), kSmall.begin(), kSmall.end());
  const ProcessResult result = run_flag_sim(args, dir.path());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("hybrid"), std::string::npos) << result.out;
  const auto csv = read_csv(dir.file("report.csv"));
  ASSERT_EQ(csv.size(), 4u);  // header, reference, hybrid, tracking
  for (const char* name : {"mode", "fine", "coarse", "substeps", "relax_iterations", "frames",
                           "ms_per_frame", "physics_ms", "infill_ms", "max_strain", "p99_strain",
                           "short_horizon_rms_m", "tracking_rms_m", "flap_hz", "mean_shape_rms_m"})
    column(csv, name);
  const std::size_t shape = column(csv, "mean_shape_rms_m"), track = column(csv, "tracking_rms_m");
  EXPECT_EQ(csv[1][column(csv, "mode")], "mass-spring");
  EXPECT_EQ(std::stod(csv[1][shape]), 0.0);  // the reference against itself
  EXPECT_EQ(csv[2][column(csv, "mode")], "hybrid");
  EXPECT_GT(std::stod(csv[2][shape]), 0.0);
  EXPECT_GT(std::stod(csv[2][track]), 0.0);
  EXPECT_EQ(csv[2][column(csv, "fine")], "17x25");
  EXPECT_EQ(csv[2][column(csv, "coarse")], "9x13");
  // The cost split by what each stage is for (StageGroup): the reference has
  // no infill, the hybrid's frame is its physics plus its infill.
  const auto number = [&](std::size_t row, const char* name) {
    return std::stod(csv[row][column(csv, name)]);
  };
  EXPECT_EQ(number(1, "infill_ms"), 0.0);
  EXPECT_GT(number(2, "infill_ms"), 0.0);
  EXPECT_GT(number(2, "physics_ms"), 0.0);
  EXPECT_NEAR(number(2, "physics_ms") + number(2, "infill_ms"), number(2, "ms_per_frame"),
              test::kCsvRelTol * number(2, "ms_per_frame") + test::kCsvAbs_ms);
}

// --reference all: every full-lattice integrator, implicit and XPBD at more
// substeps until their p99 strain is no worse than the hybrid's, and the
// hybrid's speed-up against the fastest reference run that reached it.
TEST(Compare, AllReferencesAndTheSpeedupAgainstTheBestThatMatchesTheHybridsStrain) {
  TempDir dir;
  std::vector<std::string> args = {"compare", "--reference", "all", "-o", "all.csv"};
  args.insert(args.end(), kSmall.begin(), kSmall.end());
  const ProcessResult result = run_flag_sim(args, dir.path());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const auto csv = read_csv(dir.file("all.csv"));
  const std::size_t mode = column(csv, "mode"), p99 = column(csv, "p99_strain"),
                    ms = column(csv, "ms_per_frame"), status = column(csv, "status"),
                    substeps = column(csv, "substeps"), label = column(csv, "label");
  std::size_t hybrid = 0;
  std::map<std::string, std::vector<std::size_t>> rows_of;
  for (std::size_t r = 1; r < csv.size(); ++r) {
    if (csv[r][label] == "hybrid") hybrid = r;
    if (csv[r][label].rfind("reference", 0) == 0) rows_of[csv[r][mode]].push_back(r);
  }
  ASSERT_GT(hybrid, 0u);
  EXPECT_EQ(csv[1][mode], "mass-spring");  // the first reference: errors are against it
  for (const char* m : {"mass-spring", "bullet", "implicit", "xpbd"})
    EXPECT_FALSE(rows_of[m].empty()) << m;
  EXPECT_EQ(rows_of["mass-spring"].size(), 1u);
  EXPECT_EQ(rows_of["bullet"].size(), 1u);
  const double hybrid_p99 = std::stod(csv[hybrid][p99]);
  // Each accuracy-stepped ladder doubles its substeps and stops at the first
  // run that reaches the hybrid's p99 strain.
  for (const char* m : {"implicit", "xpbd"}) {
    const std::vector<std::size_t>& ladder = rows_of[m];
    for (std::size_t i = 0; i + 1 < ladder.size(); ++i) {
      EXPECT_EQ(std::stoi(csv[ladder[i + 1]][substeps]), 2 * std::stoi(csv[ladder[i]][substeps]));
      EXPECT_TRUE(csv[ladder[i]][status] != "complete" ||
                  std::stod(csv[ladder[i]][p99]) > hybrid_p99)
          << m << " row " << ladder[i] << " already matched the hybrid";
    }
  }
  // The best reference: the fastest complete one with p99 at most the hybrid's.
  std::size_t best = 0;
  for (const auto& [m, rows] : rows_of)
    for (std::size_t r : rows)
      if (csv[r][status] == "complete" && std::stod(csv[r][p99]) <= hybrid_p99 &&
          (best == 0 || std::stod(csv[r][ms]) < std::stod(csv[best][ms])))
        best = r;
  ASSERT_GT(best, 0u) << "a 17 x 25 run: some reference reaches the hybrid's strain";
  EXPECT_EQ(csv[hybrid][column(csv, "best_reference")], csv[best][label]);
  EXPECT_NEAR(std::stod(csv[hybrid][column(csv, "speedup_vs_best_reference")]),
              std::stod(csv[best][ms]) / std::stod(csv[hybrid][ms]),
              test::kCsvRelTol * std::stod(csv[best][ms]) / std::stod(csv[hybrid][ms]));
  EXPECT_NE(result.out.find("faster than the fastest reference with p99 strain at most"),
            std::string::npos)
      << result.out;
  for (std::size_t r = 1; r < csv.size(); ++r)
    if (r != hybrid) {
      EXPECT_EQ(csv[r][column(csv, "best_reference")], "") << r;
    }
}

// The flapping is measured at the fly end, whichever edge is pinned: a flag
// pinned on the right in a wind blowing to -x flaps about as its mirror image
// pinned on the left (the seeded start and the cells' diagonals are not
// mirrored: over the last 2.5 s of 5, 3.42 / 3.74 / 3.74 Hz pinned left and
// 3.91 / 4.37 / 4.37 Hz pinned right measured on 2026-12-03; one second of
// flapping alone reads anywhere from 3.3 to 5.0 Hz); it read 0 Hz when the fly
// end was column K - 1.
TEST(Compare, FlapIsMeasuredAtTheFlyEndWhicheverEdgeIsPinned) {
  TempDir dir;
  std::map<std::string, std::vector<double>> flap;
  for (const std::string side : {"left", "right"}) {
    std::vector<std::string> args = {"compare",           "-o",    side + ".csv",
                                     "--frames",          "151",   "--set",
                                     "flag.fine=[17,25]", "--set", "flag.pin=\"" + side + "\""};
    if (side == "right") args.insert(args.end(), {"--set", "wind.velocity=[-10,0,0]"});
    const ProcessResult result = run_flag_sim(args, dir.path());
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const auto csv = read_csv(dir.file(side + ".csv"));
    for (std::size_t row = 1; row < csv.size(); ++row)
      flap[side].push_back(std::stod(csv[row][column(csv, "flap_hz")]));
  }
  ASSERT_EQ(flap["left"].size(), 3u);
  for (std::size_t run = 0; run < 3; ++run) {
    EXPECT_GT(flap["right"][run], 1.0) << run;
    EXPECT_NEAR(flap["right"][run], flap["left"][run],
                test::kMirroredFlapRelTol * flap["left"][run])
        << run;
  }
}

// The line of `text` that starts with `head`, or "".
std::string line_starting(const std::string& text, const std::string& head) {
  std::stringstream lines(text);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind(head, 0) == 0) return line;
  return "";
}

// -o in a directory that does not exist yet: made, as run makes its output's
// (issue 33); a command that fails leaves no directory behind; --quiet taken.
TEST(Compare, MakesTheReportsDirectoryAsRunDoes) {
  TempDir dir;
  std::vector<std::string> args = {"compare", "-o", "new/deeper/c.csv", "--quiet"};
  args.insert(args.end(), kSmall.begin(), kSmall.end());
  const ProcessResult made = run_flag_sim(args, dir.path());
  ASSERT_EQ(made.exit_code, 0) << made.err;
  EXPECT_TRUE(fs::exists(dir.file("new/deeper/c.csv")));
  const ProcessResult sweep = run_flag_sim(small_5x7_sweep({"-o", "s/sweep.csv"}), dir.path());
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  EXPECT_TRUE(fs::exists(dir.file("s/sweep.csv")));
  std::vector<std::string> bad = args;
  bad[2] = "other/c.csv";
  bad.insert(bad.end(), {"--set", "flag.fine=[17,26]"});
  EXPECT_EQ(run_flag_sim(bad, dir.path()).exit_code, 2);
  EXPECT_FALSE(fs::exists(dir.file("other")));
  // render takes --quiet too (issue 33: it was refused).
  ASSERT_EQ(
      run_flag_sim({"run", "--quiet", "--frames", "2", "--set", "flag.fine=[17,25]", "-o", "r.h5"},
                   dir.path())
          .exit_code,
      0);
  const ProcessResult render =
      run_flag_sim({"render", "r.h5", "--quiet", "--size", "64x48", "-o", "frames/"}, dir.path());
  EXPECT_EQ(render.exit_code, 0) << render.err;
}

TEST(Compare, SeedsGiveSpreadsAndAConvergenceVerdict) {
  TempDir dir;
  const std::vector<std::string> args = {"compare", "--frames",         "91", "--seeds", "2",
                                         "--set",   "flag.fine=[17,25]"};
  const ProcessResult first = run_flag_sim(args, dir.path());
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const std::string seeds = line_starting(first.out, "seeds 1 .. 2 (2), mean +- seed-to-seed sd");
  const std::string verdict =
      line_starting(first.out, "reference convergence (mass-spring 17 x 25 against 9 x 13");
  ASSERT_FALSE(seeds.empty()) << first.out;
  ASSERT_FALSE(verdict.empty()) << first.out;
  EXPECT_TRUE(verdict.ends_with(": converged (the lattice does not change the answer beyond the "
                                "seeds)") ||
              verdict.find(": NOT converged") != std::string::npos)
      << verdict;
  // Seeds and lattices are the only randomness: the same command says the same.
  const ProcessResult again = run_flag_sim(args, dir.path());
  EXPECT_EQ(line_starting(again.out, "seeds 1 .."), seeds);
  EXPECT_EQ(line_starting(again.out, "reference convergence"), verdict);
  // No lattice of every other node (an even side): said, not guessed.
  const ProcessResult even = run_flag_sim({"compare", "--frames", "31", "--seeds", "2", "--set",
                                           "flag.fine=[18,26]", "--set", "flag.coarse=[2,2]"},
                                          dir.path());
  ASSERT_EQ(even.exit_code, 0) << even.err;
  EXPECT_NE(even.out.find("reference convergence: not judged (18 x 26 has no lattice of every "
                          "other node"),
            std::string::npos)
      << even.out;
  const ProcessResult none = run_flag_sim({"compare", "--seeds", "0"}, dir.path());
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.err.find("--seeds 0: expected 1 to 64 seeds"), std::string::npos) << none.err;
}

TEST(Sweep, PointsRunAloneAndMergedEqualTheWholeSweep) {
  TempDir dir;
  std::vector<std::string> base = {"sweep", "--coarse", "5x7,9x13", "--relax", "100", "--quiet"};
  base.insert(base.end(), kSmall.begin(), kSmall.end());
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = base;
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  };
  ASSERT_EQ(run_flag_sim(with({"-o", "whole.csv"}), dir.path()).exit_code, 0);
  ASSERT_EQ(run_flag_sim(with({"-o", "jobs.csv", "--jobs", "2"}), dir.path()).exit_code, 0);
  std::vector<std::string> merge = {"sweep", "--quiet", "-o", "merged.csv", "--merge"};
  for (int point = 2; point >= 0; --point) {  // any order
    const std::string file = "p" + std::to_string(point) + ".csv";
    ASSERT_EQ(
        run_flag_sim(with({"-o", file, "--point", std::to_string(point)}), dir.path()).exit_code,
        0);
    merge.push_back(file);
  }
  ASSERT_EQ(run_flag_sim(merge, dir.path()).exit_code, 0);
  const auto whole = without_timing(read_csv(dir.file("whole.csv")));
  ASSERT_EQ(whole.size(), 4u);  // header, the reference, 2 hybrid points
  EXPECT_EQ(without_timing(read_csv(dir.file("merged.csv"))), whole);
  EXPECT_EQ(without_timing(read_csv(dir.file("jobs.csv"))), whole);
  // Merging a point twice is refused.
  const ProcessResult twice =
      run_flag_sim({"sweep", "-o", "x.csv", "--merge", "p0.csv", "p0.csv"}, dir.path());
  EXPECT_EQ(twice.exit_code, 2);
  EXPECT_NE(twice.err.find("point 0 appears twice"), std::string::npos) << twice.err;
}

// --seeds N: every point at N seeds, each against the reference of its own
// seed. The second seed's rows are a plain sweep's at that seed (paired, not
// pooled), and --jobs, --point + --merge give the same rows as one process.
TEST(Sweep, SeedsRunEveryPointAgainstTheReferenceOfItsSeed) {
  TempDir dir;
  const auto with = [](const std::vector<std::string>& extra) { return small_5x7_sweep(extra); };
  const ProcessResult whole = run_flag_sim(with({"--seeds", "2", "-o", "whole.csv"}), dir.path());
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  const auto csv = without_timing(read_csv(dir.file("whole.csv")));
  ASSERT_EQ(csv.size(), 5u);  // header, 2 points x 2 seeds, by point then seed
  const std::size_t seed = column(csv, "seed"), point = column(csv, "point");
  for (std::size_t r = 1; r < csv.size(); ++r) {
    EXPECT_EQ(csv[r][point], std::to_string((r - 1) / 2));
    EXPECT_EQ(csv[r][seed], std::to_string(1 + (r - 1) % 2));
  }
  EXPECT_NE(whole.out.find("hybrid 5x7 seed 2"), std::string::npos) << whole.out;
  EXPECT_NE(whole.out.find("over the seeds, mean +- seed-to-seed sd"), std::string::npos)
      << whole.out;
  EXPECT_NE(whole.out.find("  hybrid 5x7                             2 seed(s): flap "),
            std::string::npos)
      << whole.out;
  // Seed 2 of the study is the plain sweep at scene.seed = 2, row for row.
  ASSERT_EQ(run_flag_sim(with({"--set", "scene.seed=2", "-o", "two.csv"}), dir.path()).exit_code,
            0);
  const auto two = without_timing(read_csv(dir.file("two.csv")));
  ASSERT_EQ(two.size(), 3u);
  for (std::size_t r = 1; r < two.size(); ++r) EXPECT_EQ(two[r], csv[2 * r]) << "row " << r;
  // The same rows from workers, and from points run alone and merged; each
  // seed's reference saved beside the first's.
  ASSERT_EQ(
      run_flag_sim(with({"--seeds", "2", "--jobs", "2", "-o", "jobs.csv"}), dir.path()).exit_code,
      0);
  EXPECT_EQ(without_timing(read_csv(dir.file("jobs.csv"))), csv);
  std::vector<std::string> merge = {"sweep", "--quiet", "-o", "merged.csv", "--merge"};
  for (int p = 0; p < 2; ++p) {
    const std::string file = "p" + std::to_string(p) + ".csv";
    ASSERT_EQ(run_flag_sim(with({"--seeds", "2", "--point", std::to_string(p), "--reference-file",
                                 "ref.rec", "-o", file}),
                           dir.path())
                  .exit_code,
              0);
    merge.push_back(file);
  }
  EXPECT_TRUE(fs::exists(dir.file("ref.rec")));
  EXPECT_TRUE(fs::exists(dir.file("ref.rec.seed1")));
  ASSERT_EQ(run_flag_sim(merge, dir.path()).exit_code, 0);
  EXPECT_EQ(without_timing(read_csv(dir.file("merged.csv"))), csv);
  const ProcessResult none = run_flag_sim(with({"--seeds", "0", "-o", "n.csv"}), dir.path());
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.err.find("--seeds 0: expected 1 to 64 seeds"), std::string::npos) << none.err;
  EXPECT_FALSE(fs::exists(dir.file("n.csv")));
}

// The reference runs once and is shared: a point given --reference-file reads
// it (a file that is not a record is refused, so nothing was re-run), and its
// rows are those of a point that ran the reference itself.
TEST(Sweep, PointsShareOneSavedReference) {
  TempDir dir;
  const auto with = [](const std::vector<std::string>& extra) { return small_5x7_sweep(extra); };
  ASSERT_EQ(run_flag_sim(with({"-o", "alone.csv", "--point", "1"}), dir.path()).exit_code, 0);
  ASSERT_EQ(run_flag_sim(with({"-o", "ref.csv", "--point", "0", "--reference-file", "ref.rec"}),
                         dir.path())
                .exit_code,
            0);
  EXPECT_TRUE(fs::exists(dir.file("ref.rec")));
  EXPECT_FALSE(fs::exists(dir.file("ref.rec.partial")));
  ASSERT_EQ(run_flag_sim(with({"-o", "shared.csv", "--point", "1", "--reference-file", "ref.rec"}),
                         dir.path())
                .exit_code,
            0);
  EXPECT_EQ(without_timing(read_csv(dir.file("shared.csv"))),
            without_timing(read_csv(dir.file("alone.csv"))));
  // A saved reference of another sweep (here: other frames) is refused, not measured against.
  const ProcessResult other =
      run_flag_sim({"sweep", "--coarse", "5x7", "--quiet", "--set", "flag.fine=[17,25]", "--frames",
                    "11", "-o", "o.csv", "--point", "1", "--reference-file", "ref.rec"},
                   dir.path());
  EXPECT_EQ(other.exit_code, 2);
  EXPECT_NE(other.err.find("ref.rec: the reference of another scene or sweep"), std::string::npos)
      << other.err;
  dir.write("bad.rec", "not a record");
  const ProcessResult bad = run_flag_sim(
      with({"-o", "b.csv", "--point", "1", "--reference-file", "bad.rec"}), dir.path());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("bad.rec: not a whole flag-sim run record"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir.file("b.csv")));
  // --list names the points and runs nothing; the whole sweep ends with compare's table.
  const ProcessResult list = run_flag_sim(with({"--list"}), dir.path());
  ASSERT_EQ(list.exit_code, 0) << list.err;
  EXPECT_NE(list.out.find("  1  hybrid 5x7"), std::string::npos) << list.out;
  EXPECT_NE(list.out.find("flag.coarse=[5,7]"), std::string::npos) << list.out;
  const ProcessResult whole = run_flag_sim(with({"-o", "w.csv", "--jobs", "2"}), dir.path());
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  EXPECT_NE(whole.out.find("run                                       ms/frame"), std::string::npos)
      << whole.out;
  EXPECT_NE(whole.out.find("hybrid 5x7"), std::string::npos) << whole.out;
  EXPECT_FALSE(fs::exists(dir.file("w.csv.points")));  // the workers' directory is gone
}

// --slurm writes batch scripts that /bin/sh runs as Slurm would (the task id
// in the environment), whatever the scene's name; merged, they give the
// --jobs sweep's rows; written again, they leave out what is done.
TEST(Sweep, SlurmScriptsRunAsTheSweep) {
  TempDir dir;
  const std::string scene = "it's a \"scene\" $HOME.toml";
  const ProcessResult printed = run_flag_sim({"scene", "--default"});
  dir.write(scene, printed.out);
  std::vector<std::string> base = {"sweep", scene, "--coarse", "5x7", "--quiet"};
  base.insert(base.end(), kSmall.begin(), kSmall.end());
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = base;
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  };
  const ProcessResult written = run_flag_sim(
      with({"-o", "slurm.csv", "--slurm", "jobs", "--slurm-arg=--time=5"}), dir.path());
  ASSERT_EQ(written.exit_code, 0) << written.err;
  EXPECT_NE(written.out.find("sweep.sbatch (points 1)"), std::string::npos) << written.out;
  const auto sh = [&](const std::string& script, const std::string& task) {
    return run_process("/usr/bin/env", {"SLURM_ARRAY_TASK_ID=" + task, "/bin/sh", script},
                       dir.path());
  };
  ASSERT_EQ(sh("jobs/reference.sbatch", "").exit_code, 0);
  const ProcessResult point = sh("jobs/sweep.sbatch", "1");
  ASSERT_EQ(point.exit_code, 0) << point.err;
  ASSERT_EQ(sh("jobs/merge.sbatch", "").exit_code, 0);
  ASSERT_EQ(run_flag_sim(with({"-o", "jobs.csv", "--jobs", "2"}), dir.path()).exit_code, 0);
  EXPECT_EQ(without_timing(read_csv(dir.file("slurm.csv"))),
            without_timing(read_csv(dir.file("jobs.csv"))));
  const ProcessResult again =
      run_flag_sim(with({"-o", "slurm.csv", "--slurm", "jobs"}), dir.path());
  EXPECT_NE(again.out.find("reference.sbatch (done, left out), sweep.sbatch (points none left)"),
            std::string::npos)
      << again.out;
  EXPECT_EQ(sh("jobs/sweep.sbatch", "1").exit_code, 0);  // a task whose row is there: done at once
  for (const auto& [args, words] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"-o", "x.csv", "--slurm", "bad dir"}, "--slurm bad dir: use a directory path of"},
           {{"-o", "x.csv", "--submit"}, "--submit: goes with --slurm DIR"},
           {{"-o", "x.csv", "--slurm", "j2", "--slurm-arg=--time 10"},
            "expected one sbatch option"},
           {{"-o", "x.csv", "--slurm", "j2", "--jobs", "2"}, "leave out --point, --jobs"},
           {{"-o", "x.csv", "--resume"}, "--resume: goes with --point I"}}) {
    const ProcessResult refused = run_flag_sim(with(args), dir.path());
    EXPECT_EQ(refused.exit_code, 2) << words;
    EXPECT_NE(refused.err.find(words), std::string::npos) << refused.err;
  }
  EXPECT_FALSE(fs::exists(dir.file("bad dir")));
  EXPECT_FALSE(fs::exists(dir.file("j2")));
}

TEST(Sweep, PoleRadiiAndContactThicknessesSideBySideEachInItsColumn) {
  // --pole-radius 0,0.04: the scene's own pole (here none: a line) and a solid of 4 cm;
  // --contact-thickness 0,0.005: the scene's own [contact] (here none) and 5 mm. The columns
  // say which row is which, empty where the pole is not a solid or there is no self-contact.
  TempDir dir;
  std::vector<std::string> args = {
      "sweep",   "--coarse", "9x13",  "--pole-radius", "0,0.04", "--contact-thickness",
      "0,0.005", "-o",       "p.csv", "--quiet"};
  args.insert(args.end(), kSmall.begin(), kSmall.end());
  const ProcessResult result = run_flag_sim(args, dir.path());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const auto csv = read_csv(dir.file("p.csv"));
  ASSERT_EQ(csv.size(), 6u);  // header, the reference, the four points
  const std::size_t radius = column(csv, "pole_radius_m");
  const std::size_t thickness = column(csv, "contact_thickness_m");
  const std::size_t label = column(csv, "label");
  // The reference runs the scene as it is; then radius by thickness.
  const std::vector<std::array<std::string, 2>> expected = {
      {"", ""}, {"", ""}, {"", "0.005"}, {"0.04", ""}, {"0.04", "0.005"}};
  for (std::size_t row = 1; row < 6; ++row) {
    SCOPED_TRACE(csv[row][label]);
    EXPECT_EQ(csv[row][radius], expected[row - 1][0]);
    EXPECT_EQ(csv[row][thickness], expected[row - 1][1]);
    EXPECT_EQ(csv[row][column(csv, "status")], "complete");
  }
  EXPECT_NE(csv[3][label].find("contact 0.005 m"), std::string::npos);
  EXPECT_NE(csv[5][label].find("pole 0.04 m contact 0.005 m"), std::string::npos);
}

TEST(Sweep, BackendsSideBySide) {
  TempDir dir;
  std::vector<std::string> args = {"sweep",
                                   "--coarse",
                                   "9x13",
                                   "--backend",
                                   "spring-damper,implicit,xpbd",
                                   "--references",
                                   "mass-spring,implicit",
                                   "-o",
                                   "b.csv",
                                   "--quiet"};
  args.insert(args.end(), kSmall.begin(), kSmall.end());
  const ProcessResult result = run_flag_sim(args, dir.path());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const auto csv = read_csv(dir.file("b.csv"));
  ASSERT_EQ(csv.size(), 6u);  // header, 2 references, 3 backends
  const std::size_t backend = column(csv, "backend"), label = column(csv, "label");
  EXPECT_EQ(csv[2][column(csv, "mode")], "implicit");
  const std::vector<std::string> expected = {"spring-damper", "implicit", "xpbd"};
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(csv[3 + i][backend], expected[i]);
    EXPECT_NE(csv[3 + i][label].find(expected[i]), std::string::npos) << csv[3 + i][label];
    EXPECT_EQ(csv[3 + i][column(csv, "status")], "complete");
  }
  const ProcessResult bad =
      run_flag_sim({"sweep", "--coarse", "9x13", "--backend", "havok", "-o", "x.csv"}, dir.path());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--backend havok: expected backends"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("x.csv")));
}

TEST(Sweep, PlotsErrorAgainstCost) {
  TempDir dir;
  // With the Bullet reference (sweep --references), drawn as its own marker.
  std::vector<std::string> args = {
      "sweep", "--coarse", "5x7",    "--references", "mass-spring,bullet",
      "-o",    "s.csv",    "--plot", "s.png",        "--quiet"};
  args.insert(args.end(), kSmall.begin(), kSmall.end());
  const ProcessResult result = run_flag_sim(args, dir.path());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  std::ifstream png(dir.file("s.png"), std::ios::binary);
  char magic[4] = {};
  png.read(magic, 4);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG");
}

}  // namespace
}  // namespace flagsim::test
