// Nothing a user gave is ever lost (issue 13, data loss): no output is an
// input of the same command however the path is spelt, a scene name cannot
// place a file outside out/, a second writer of the same output is refused,
// helper programs get their paths as arguments, never through a shell.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "process.hpp"
#include "temp_dir.hpp"

namespace flagsim::test {
namespace {

namespace fs = std::filesystem;

constexpr const char* kTiny =
    "[scene]\nname = \"tiny\"\nmode = \"hybrid\"\nduration = 0.1\n"
    "[flag]\nsize = [1.5, 1.0]\nfine = [17, 25]\ncoarse = [9, 13]\n[gravity]\n";

std::string read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Runs point `point` of a one-lattice sweep of s.toml into p<point>.csv.
void write_point_csv(const TempDir& dir, const std::string& point) {
  ASSERT_EQ(run_flag_sim({"sweep", "s.toml", "--coarse", "9x13", "--point", point, "-o",
                          "p" + point + ".csv", "--quiet"},
                         dir.path())
                .exit_code,
            0);
}

// One error line, exit 2.
void expect_refused(const ProcessResult& r, const std::string& words, const std::string& what) {
  EXPECT_EQ(r.exit_code, 2) << what << "\n" << r.err;
  EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << what << "\n" << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << what << "\n" << r.err;
  EXPECT_NE(r.err.find(words), std::string::npos) << what << "\n" << r.err;
  EXPECT_TRUE(r.out.empty()) << what;
}

TEST(DataSafety, NoOutputOverwritesTheSceneHoweverItIsSpelt) {
  TempDir dir;
  const std::string scene = dir.write("s.toml", kTiny);
  fs::create_directory(dir.file("real"));
  fs::copy_file(scene, dir.file("real/s.toml"));
  fs::create_directory_symlink("real", dir.file("link"));
  const std::vector<std::vector<std::string>> attempts = {
      {"run", "s.toml", "-o", "s.toml"},
      {"run", "s.toml", "-o", "./s.toml"},
      {"run", "s.toml", "-o", scene},
      {"run", "real/s.toml", "-o", "link/s.toml"},
      {"run", "link/../s.toml", "-o", "s.toml"},
      {"run", "s.toml", "--set", "output.file=\"s.toml\""},
      {"run", "s.toml", "-o", "s.h5", "--render", "s.toml"},
      {"compare", "s.toml", "-o", "./s.toml", "--frames", "2"},
      {"sweep", "s.toml", "--coarse", "9x13", "-o", "s.toml"},
      {"sweep", "s.toml", "--coarse", "9x13", "-o", "r.csv", "--plot", scene},
  };
  for (const auto& args : attempts) {
    std::string what;
    for (const std::string& a : args) what += a + " ";
    const ProcessResult r = run_flag_sim(args, dir.path());
    EXPECT_EQ(r.exit_code, 2) << what << r.err;
    EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << what << r.err;
    EXPECT_EQ(read(scene), kTiny) << what;
    EXPECT_EQ(read(dir.file("real/s.toml")), kTiny) << what;
  }
  EXPECT_EQ(dir.entry_count(), 3);  // s.toml, real/, link: nothing else made
}

TEST(DataSafety, NoOutputOverwritesAnOutputFileItReads) {
  TempDir dir;
  dir.write("s.toml", kTiny);
  ASSERT_EQ(run_flag_sim({"run", "s.toml", "-o", "r.h5", "--quiet"}, dir.path()).exit_code, 0);
  const std::string before = read(dir.file("r.h5"));
  expect_refused(run_flag_sim({"render", "r.h5", "-o", "./r.h5"}, dir.path()), "would overwrite",
                 "render onto its input");
  expect_refused(run_flag_sim({"sweep", "--merge", "r.h5", "-o", "r.h5"}, dir.path()),
                 "would overwrite", "merge onto its input");
  EXPECT_EQ(read(dir.file("r.h5")), before);
}

TEST(DataSafety, AnOutputWhoseSidecarIsItselfIsRefused) {
  TempDir dir;
  dir.write("s.toml", kTiny);
  expect_refused(run_flag_sim({"run", "s.toml", "-o", "run.xdmf"}, dir.path()), "same file",
                 "-o run.xdmf");
  EXPECT_EQ(dir.entry_count(), 1);
}

TEST(DataSafety, ASceneNameMustBeOneFileNameInsideOut) {
  TempDir dir;
  dir.write("s.toml", kTiny);
  for (const char* name : {"\"../../escaped\"", "\"a/b\"", "\"ab\\u0000cd\"", "\"..\"", "\"\""}) {
    const ProcessResult r =
        run_flag_sim({"run", "s.toml", "--set", std::string("scene.name=") + name}, dir.path());
    expect_refused(r, "cannot name an output file", name);
  }
  EXPECT_EQ(dir.entry_count(), 1);  // no out/, nothing above it
  EXPECT_FALSE(fs::exists(fs::path(dir.path()).parent_path().parent_path() / "escaped.h5"));
}

TEST(DataSafety, ASecondWriterOfTheSameOutputIsRefusedAndTheFirstKeepsItsFrames) {
  TempDir dir;
  dir.write("s.toml", kTiny);
  // The first run is long enough (257 x 385, 400 frames: seconds) to be caught writing.
  ProcessResult first;
  std::thread writer([&] {
    first = run_flag_sim({"run", "s.toml", "-o", "c.h5", "--quiet", "--set", "flag.fine=[257,385]",
                          "--frames", "400"},
                         dir.path());
  });
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (!fs::exists(dir.file("c.h5.partial")) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  std::this_thread::sleep_for(std::chrono::milliseconds(50));  // HDF5 has created and locked it
  const ProcessResult second = run_flag_sim({"run", "s.toml", "-o", "c.h5", "--quiet"}, dir.path());
  writer.join();
  expect_refused(second, "being written by another run", "second writer");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_NE(first.out.find("400 frames"), std::string::npos) << first.out;
  EXPECT_TRUE(fs::exists(dir.file("c.h5")));
  EXPECT_FALSE(fs::exists(dir.file("c.h5.partial")));
}

TEST(DataSafety, HelperProgramsGetPathsAsArgumentsNotThroughAShell) {
  TempDir dir;
  dir.write("s.toml", kTiny);
  // Two real point CSVs (a reference and a hybrid: the plot needs an error
  // above 0), then a merge whose output paths are shell syntax.
  for (const char* point : {"0", "1"}) ASSERT_NO_FATAL_FAILURE(write_point_csv(dir, point));
  const std::string hostile = "x';touch INJECTED;'.csv";
  const ProcessResult merged = run_flag_sim({"sweep", "--merge", "p0.csv", "p1.csv", "-o", hostile,
                                             "--plot", "p'$(touch INJECTED2)'.png"},
                                            dir.path());
  EXPECT_EQ(merged.exit_code, 0) << merged.err;
  EXPECT_TRUE(fs::exists(dir.file(hostile)));
  EXPECT_TRUE(fs::exists(dir.file("p'$(touch INJECTED2)'.png")));
  EXPECT_FALSE(fs::exists(dir.file("INJECTED")));
  EXPECT_FALSE(fs::exists(dir.file("INJECTED2")));
}

TEST(DataSafety, MergeRowsThatAreNotSweepRowsAreOneErrorLine) {
  TempDir dir;
  dir.write("s.toml", kTiny);
  ASSERT_NO_FATAL_FAILURE(write_point_csv(dir, "0"));
  const std::string good = read(dir.file("p0.csv"));
  const std::string header = good.substr(0, good.find('\n') + 1);
  for (const char* row : {"abc,def", "99999999999,x", "-5,x", "7", " 3 ,x"}) {
    dir.write("bad.csv", header + row + "\n");
    const ProcessResult r =
        run_flag_sim({"sweep", "--merge", "bad.csv", "-o", "m.csv"}, dir.path());
    expect_refused(r, "bad.csv:2: not a row of a flag-sim sweep CSV", row);
    EXPECT_FALSE(fs::exists(dir.file("m.csv"))) << row;
  }
}

TEST(DataSafety, DeepNestingIsOneErrorLineNotACrash) {
  TempDir dir;
  std::string header = "[", key, array = "x = ";
  for (int i = 0; i < 50000; ++i) {
    header += i ? ".a" : "a";
    key += i ? ".a" : "a";
  }
  array += std::string(50000, '[') + std::string(50000, ']') + "\n";
  dir.write("header.toml", header + "]\n");
  dir.write("dotted.toml", key + " = 1\n");
  dir.write("array.toml", array);
  expect_refused(run_flag_sim({"validate", "header.toml"}, dir.path()), "header.toml:1: a key of",
                 "deep table header");
  expect_refused(run_flag_sim({"validate", "dotted.toml"}, dir.path()), "dotted.toml:1: a key of",
                 "deep dotted key");
  expect_refused(run_flag_sim({"validate", "array.toml"}, dir.path()),
                 "array.toml:1: nesting deeper than 64", "deep array");
  expect_refused(run_flag_sim({"run", "--set",
                               "wind.velocity=" + std::string(50000, '[') + std::string(50000, ']'),
                               "--frames", "1", "-o", "x.h5"},
                              dir.path()),
                 "nesting deeper than 64", "deep --set");
  {
    const ProcessResult r = run_flag_sim(
        {"run", "--frames", "1", "-o", "y.h5", "--set", "x=" + std::string(50000, '[')},
        dir.path());
    expect_refused(r, "nesting deeper than 64", "deep --set, quoted");
    EXPECT_LT(r.err.size(), 400u);  // the --set is quoted cut short, not 50 kB
  }
  EXPECT_EQ(dir.entry_count(), 3);
}

TEST(DataSafety, OnlyRegularFilesAreReadAsScenes) {
  TempDir dir;
  ASSERT_EQ(::mkfifo(dir.file("fifo.toml").c_str(), 0600), 0);
  const auto start = std::chrono::steady_clock::now();
  expect_refused(run_flag_sim({"validate", "fifo.toml"}, dir.path()),
                 "fifo.toml: not a regular file", "FIFO");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));  // no block
  expect_refused(run_flag_sim({"validate", "/dev/zero"}, dir.path()),
                 "/dev/zero: not a regular file", "/dev/zero");
  dir.write("huge.toml", std::string(2 << 20, '#'));
  expect_refused(run_flag_sim({"validate", "huge.toml"}, dir.path()),
                 "more than a scene file can be", "2 MiB scene");
}

TEST(DataSafety, PhysicalValuesNoRealSceneNeedsAreRefusedWithTheirRange) {
  TempDir dir;
  dir.write("s.toml", kTiny);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"wind.velocity=[1e308,0,0]", "at most 200 m/s, got 1e+308"},
      {"flag.areal_density=1e-300", "in [0.0001, 100] kg/m^2"},
      {"bending.stiffness=1e299", "in [0, 1] N m"},
      {"gravity.acceleration=[0,-1e9,0]", "at most 1000 m/s^2"},
      {"flag.stretch_modulus=1e20", "N/m"},
      {"pole.frequency=1e4", "Hz"},
  };
  for (const auto& [set, words] : cases) {
    const auto start = std::chrono::steady_clock::now();
    expect_refused(run_flag_sim({"run", "s.toml", "--set", set, "-o", "x.h5"}, dir.path()), words,
                   set);
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10)) << set;
  }
  EXPECT_EQ(dir.entry_count(), 1);
}

TEST(DataSafety, ASeedIsTakenAsTypedOrRefused) {
  TempDir dir;
  dir.write("s.toml", kTiny);
  for (const char* seed : {"18446744073709551615", "9223372036854775808", "-1", "12x"})
    expect_refused(run_flag_sim({"run", "s.toml", "--seed", seed, "-o", "x.h5"}, dir.path()),
                   "expected an integer from 0 to 9223372036854775807", seed);
  expect_refused(run_flag_sim({"run", "s.toml", "--seed", "", "-o", "x.h5"}, dir.path()),
                 "--seed '': an empty value", "an empty seed");
  EXPECT_EQ(dir.entry_count(), 1);
  const ProcessResult largest = run_flag_sim(
      {"run", "s.toml", "--seed", "9223372036854775807", "-o", "x.h5", "--quiet"}, dir.path());
  EXPECT_EQ(largest.exit_code, 0) << largest.err;
}

TEST(DataSafety, ASweepNeverTakesAPointsPathThatIsAlreadyThere) {
  TempDir dir;
  dir.write("s.toml", kTiny);
  dir.write("out.csv.points", "a user's file\n");
  expect_refused(
      run_flag_sim({"sweep", "s.toml", "--coarse", "9x13", "--jobs", "2", "-o", "out.csv"},
                   dir.path()),
      "out.csv.points: exists", "points path is a file");
  EXPECT_EQ(read(dir.file("out.csv.points")), "a user's file\n");
  EXPECT_FALSE(fs::exists(dir.file("out.csv")));
}

// Every error is one line, however the message was built: arrays laid out over
// lines by the TOML library, a --set value holding a line break, a 100 kB name.
TEST(DataSafety, EveryErrorIsOneLineOfSaneLength) {
  TempDir dir;
  dir.write("s.toml", kTiny);
  dir.write("nan.toml", "[wind]\nvelocity = [nan, 1e308, 0]\n");
  dir.write("deep.toml", "[wind]\nvelocity = " + std::string(200, '[') + std::string(200, ']'));
  dir.write("tables.toml", "[[flag]]\nfine = [3, 3]\n");
  expect_refused(run_flag_sim({"validate", "nan.toml"}, dir.path()),
                 "nan.toml:2:12: wind.velocity: expected an array of 3 finite numbers", "nan");
  expect_refused(run_flag_sim({"validate", "deep.toml"}, dir.path()), "nesting deeper than 64",
                 "200-deep array");
  expect_refused(run_flag_sim({"validate", "tables.toml"}, dir.path()),
                 "tables.toml:1:1: flag: expected a table [flag]", "[[flag]]");
  expect_refused(
      run_flag_sim({"run", "s.toml", "--set", "flag.fine=[9,9]\n[foo]", "-o", "x.h5"}, dir.path()),
      "a value must be on one line", "--set with a line break");
  const ProcessResult huge = run_flag_sim(
      {"run", "s.toml", "--set", "flag.pin=\"" + std::string(100000, 'a') + "\"", "-o", "x.h5"},
      dir.path());
  expect_refused(huge, "...", "a 100 kB value");
  EXPECT_LT(huge.err.size(), 800u);
  EXPECT_EQ(dir.entry_count(), 4);
}

// An error names what the user wrote: the flag as typed, the --set argument
// that reached into a key, the file, line and column of a keyframe's corner.
TEST(DataSafety, ErrorsQuoteWhatTheUserTyped) {
  TempDir dir;
  dir.write("s.toml", kTiny);
  expect_refused(run_flag_sim({"run", "s.toml", "--mode", "foo", "-o", "x.h5"}, dir.path()),
                 "error: --mode foo: scene.mode: expected one of", "--mode foo");
  expect_refused(
      run_flag_sim({"run", "s.toml", "--set", "flag.fine.x=1", "-o", "x.h5"}, dir.path()),
      "error: --set flag.fine.x=1: flag.fine: expected [J, K] nodes", "--set into a pair");
  dir.write("corner.toml",
            "[scene]\nmode = \"infill\"\nduration = 0.1\n[flag]\nfine = [9, 9]\n[[keyframe]]\n"
            "time = 0.0\ncorners = [[0, 2, 0], [1.5, 2, 0], [0, 1, 0], [1.5, 1, \"x\"]]\n");
  expect_refused(run_flag_sim({"validate", "corner.toml"}, dir.path()),
                 "error: corner.toml:8:47: keyframe.corners: expected an array of 3 numbers",
                 "a corner that is not a point");
  EXPECT_EQ(dir.entry_count(), 2);
}

// Infill corners a million metres apart: refused with the range, at once; a
// flag carried 5 km in one frame is bounded work (64 cut steps), not a hang.
TEST(DataSafety, InfillCornersTheFlagCannotSpanAreRefusedAndBigJumpsAreBounded) {
  TempDir dir;
  const std::string head =
      "[scene]\nmode = \"infill\"\nduration = 0.2\n[flag]\nsize = [1.5, 1.0]\nfine = [17, 25]\n"
      "[limits]\nmax_speed = 1e6\n"
      "[[keyframe]]\ntime = 0.0\ncorners = [[0, 2, 0], [1.5, 2, 0], [0, 1, 0], [1.5, 1, 0]]\n"
      "[[keyframe]]\ntime = 0.034\n";
  dir.write("far.toml", head + "corners = [[0, 2, 0], [1e6, 2, 0], [0, 1, 0], [1e6, 1, 0]]\n");
  dir.write("apart.toml", head + "corners = [[0, 2, 0], [5000, 2, 0], [0, 1, 0], [5000, 1, 0]]\n");
  dir.write("jump.toml", head +
                             "corners = [[5000, 2, 0], [5001.5, 2, 0], [5000, 1, 0], "
                             "[5001.5, 1, 0]]\n");
  expect_refused(run_flag_sim({"run", "far.toml", "-o", "x.h5"}, dir.path()),
                 "each in [-10000, 10000], got [1000000, 2, 0]", "a million metres");
  expect_refused(run_flag_sim({"run", "apart.toml", "-o", "x.h5"}, dir.path()),
                 "corners (0,0) and (0,K-1) are 5000 m apart, but the 1.5 x 1 m flag spans only "
                 "1.5 m",
                 "farther apart than the flag");
  const auto start = std::chrono::steady_clock::now();
  const ProcessResult jump =
      run_flag_sim({"run", "jump.toml", "-o", "jump.h5", "--quiet"}, dir.path());
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(60));
  EXPECT_EQ(jump.exit_code, 0) << jump.err;
  EXPECT_NE((jump.out + jump.err).find("note: the infill did not reach its tolerance"),
            std::string::npos)
      << jump.out << jump.err;
}

// Exit 2 leaves nothing behind: not the directories made for an output that
// was never written (-o newdir/sub/, a video whose frame rate is unusable),
// nor a render directory of a run that diverged before its first frame.
TEST(DataSafety, AFailedCommandLeavesNoDirectoriesBehind) {
  TempDir dir;
  dir.write("s.toml", kTiny);
  expect_refused(run_flag_sim({"run", "s.toml", "-o", "newdir/sub/", "--quiet"}, dir.path()),
                 "newdir/sub/: is a directory; give an output file name such as newdir/sub/run.h5",
                 "-o a directory");
  EXPECT_EQ(dir.entry_count(), 1);
  const ProcessResult diverged =
      run_flag_sim({"run", "s.toml", "-o", "out/r.h5", "--render", "frames/a", "--set",
                    "limits.max_strain=1e-9", "--set", "flag.initial_perturbation=0.01", "--quiet"},
                   dir.path());
  EXPECT_EQ(diverged.exit_code, 3) << diverged.err;
  EXPECT_NE(diverged.err.find("at t = 0 s (frame 0)"), std::string::npos) << diverged.err;
  EXPECT_TRUE(fs::exists(dir.file("out/r.h5")));  // the good frames are kept
  EXPECT_FALSE(fs::exists(dir.file("frames")));   // but no empty render directory
}

// One limit for an image side, whether it comes from the scene or --size.
TEST(DataSafety, ImageSizesHaveOneLimit) {
  TempDir dir;
  dir.write("s.toml", kTiny);
  expect_refused(
      run_flag_sim({"run", "s.toml", "--set", "render.size=[16384,16]", "-o", "x.h5"}, dir.path()),
      "render.size: expected [w, h] pixels, two integers in [16, 8192]", "[render] size");
  expect_refused(
      run_flag_sim({"run", "s.toml", "-o", "x.h5", "--render", "f", "--size", "16384x16"},
                   dir.path()),
      "--size 16384x16: each side must be 16 to 8192 pixels", "--size");
  EXPECT_EQ(dir.entry_count(), 1);
}

// A 1024-link cell from two coarse nodes: the smooth infill fills it; the
// paper's, given too few sweeps, overstretches it, and the message says that
// the infill failed, not the cloth (it used to advise a stiffer fabric).
TEST(DataSafety, AnInfillFailureIsNotReportedAsTheClothDiverging) {
  TempDir dir;
  dir.write("s.toml", kTiny);
  const std::vector<std::string> base = {
      "run",      "s.toml", "--set",  "flag.fine=[2,1025]", "--set", "flag.coarse=[2,2]",
      "--frames", "3",      "--quiet"};
  std::vector<std::string> smooth = base, paper = base;
  smooth.insert(smooth.end(), {"-o", "smooth.h5"});
  paper.insert(paper.end(), {"-o", "paper.h5", "--set", "infill.solver=\"paper\"", "--set",
                             "infill.relax_iterations=10"});
  const ProcessResult filled = run_flag_sim(smooth, dir.path());
  EXPECT_EQ(filled.exit_code, 0) << filled.err;
  const ProcessResult failed = run_flag_sim(paper, dir.path());
  EXPECT_EQ(failed.exit_code, 3) << failed.err;
  EXPECT_NE(failed.err.find("the infill failed, not the cloth; raise infill.relax_iterations"),
            std::string::npos)
      << failed.err;
  EXPECT_EQ(failed.err.find("raise flag.stretch_modulus"), std::string::npos) << failed.err;
}

}  // namespace
}  // namespace flagsim::test
