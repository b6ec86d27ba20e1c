// `flag-sim run`, `validate`, `info` and `scene` end to end.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "flagsim/data/output_reader.hpp"
#include "process.hpp"
#include "temp_dir.hpp"

namespace flagsim::test {
namespace {

namespace fs = std::filesystem;

constexpr const char* kWindy = R"([scene]
name = "windy"
mode = "mass-spring"
fps = 30
duration = 0.2
seed = 3
[flag]
size = [1.5, 1.0]
fine = [9, 13]
initial_perturbation = 0.01
[gravity]
acceleration = [0, -9.81, 0]
[wind]
velocity = [10, 0, 0]
[output]
flush_every = 2
)";

std::vector<float> all_positions(const std::string& path) {
  const data::OutputReader reader(path);
  std::vector<float> values;
  for (int t = 0; t < reader.frame_count(); ++t)
    for (const Vec3& p : reader.positions(t))
      for (int c = 0; c < 3; ++c) values.push_back(float(p[c]));
  return values;
}

TEST(Run, DefaultSceneWritesTheContractFile) {
  TempDir dir;
  const ProcessResult result = run_flag_sim({"run", "--frames", "3", "--quiet"}, dir.path());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_TRUE(result.err.empty()) << result.err;
  EXPECT_NE(result.out.find("complete: 3 frames"), std::string::npos) << result.out;
  const std::string path = dir.file("out/default.h5");  // output.file of the default scene
  ASSERT_TRUE(fs::exists(path));
  EXPECT_TRUE(fs::exists(dir.file("out/default.xdmf")));
  const data::OutputReader reader(path);
  EXPECT_EQ(reader.attribute("status"), "complete");
  EXPECT_EQ(reader.attribute("mode"), "hybrid");
  EXPECT_EQ(reader.attribute("effects"), "stretch,gravity,wind,damping,infill");
  EXPECT_EQ(reader.frame_count(), 3);
  EXPECT_EQ(reader.seed(), 1);
  EXPECT_NE(reader.attribute("scene").find("frames = 3"), std::string::npos);
  EXPECT_GT(reader.number_attribute("substeps_per_frame", 0), 1);
}

// Issue 33, item 9: run's summary and info give one ms/frame for one file
// (the mean wall time of a written frame after the initial one).
TEST(Run, ItsMsPerFrameIsTheOneInfoReads) {
  TempDir dir;
  const ProcessResult run = run_flag_sim(
      {"run", "--set", "flag.fine=[17,25]", "--frames", "8", "-o", "r.h5", "--quiet"}, dir.path());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const ProcessResult info = run_flag_sim({"info", "r.h5"}, dir.path());
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const std::size_t at = info.out.find("timing    ");
  ASSERT_NE(at, std::string::npos) << info.out;
  const std::string figure =
      info.out.substr(at + 10, info.out.find(" ms/frame", at) - at - 10);  // "2.54"
  EXPECT_NE(run.out.find(", " + figure + " ms/frame,"), std::string::npos)
      << run.out << " against info's " << figure;
}

TEST(Run, SameSceneAndSeedGiveIdenticalPositions) {
  TempDir dir;
  dir.write("windy.toml", kWindy);
  for (const char* out : {"a.h5", "b.h5"})
    ASSERT_EQ(run_flag_sim({"run", "windy.toml", "-o", out, "--quiet"}, dir.path()).exit_code, 0);
  ASSERT_EQ(run_flag_sim({"run", "windy.toml", "-o", "c.h5", "--seed", "4", "--quiet"}, dir.path())
                .exit_code,
            0);
  const auto a = all_positions(dir.file("a.h5")), b = all_positions(dir.file("b.h5")),
             c = all_positions(dir.file("c.h5"));
  ASSERT_EQ(a.size(), 7u * 9 * 13 * 3);
  EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(float)));
  EXPECT_NE(0, std::memcmp(a.data(), c.data(), a.size() * sizeof(float)));  // the seed matters
}

TEST(Run, GustyTurbulentWindIsSeeded) {
  TempDir dir;
  dir.write("windy.toml", kWindy);
  const std::vector<std::string> wind = {"--set", "wind.gusts.amplitude=0.3", "--set",
                                         "wind.turbulence.intensity=0.2", "--quiet"};
  auto run = [&](const char* out, const char* seed) {
    std::vector<std::string> args = {"run", "windy.toml", "-o", out, "--seed", seed};
    args.insert(args.end(), wind.begin(), wind.end());
    return run_flag_sim(args, dir.path());
  };
  ASSERT_EQ(run("a.h5", "3").exit_code, 0);
  ASSERT_EQ(run("b.h5", "3").exit_code, 0);
  ASSERT_EQ(run("c.h5", "4").exit_code, 0);
  EXPECT_EQ(data::OutputReader(dir.file("a.h5")).attribute("effects"),
            "stretch,gravity,wind,gusts,turbulence,damping");
  const auto a = all_positions(dir.file("a.h5")), b = all_positions(dir.file("b.h5")),
             c = all_positions(dir.file("c.h5"));
  EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(float)));
  EXPECT_NE(0, std::memcmp(a.data(), c.data(), a.size() * sizeof(float)));
}

TEST(Run, NoWindNoWindStage) {
  // An effect the scene does not call for is not constructed: no stage, no time.
  TempDir dir;
  dir.write("calm.toml",
            "[scene]\nmode = \"mass-spring\"\nduration = 0.1\n[flag]\nsize = [1.5, 1.0]\n"
            "fine = [9, 13]\n[gravity]\nacceleration = [0, -9.81, 0]\n");
  ASSERT_EQ(run_flag_sim({"run", "calm.toml", "-o", "c.h5", "--quiet"}, dir.path()).exit_code, 0);
  const data::OutputReader reader(dir.file("c.h5"));
  EXPECT_EQ(reader.attribute("effects"), "stretch,gravity,damping");
  const std::vector<std::string> stages = {"stretch", "gravity", "integrate", "checks", "output"};
  EXPECT_EQ(reader.stage_names(), stages);
}

TEST(Run, SetOverridesAreRecordedInTheFile) {
  TempDir dir;
  dir.write("windy.toml", kWindy);
  const ProcessResult result =
      run_flag_sim({"run", "windy.toml", "-o", "r.h5", "--set", "flag.fine=[5,7]", "--set",
                    "wind.velocity=[4,0,0]", "--quiet"},
                   dir.path());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const data::OutputReader reader(dir.file("r.h5"));
  EXPECT_EQ(reader.rows(), 5);
  EXPECT_EQ(reader.cols(), 7);
  EXPECT_NE(reader.attribute("scene").find("velocity = [ 4, 0, 0 ]"), std::string::npos)
      << reader.attribute("scene");
}

TEST(Run, DivergedRunKeepsItsGoodFramesAndExitsThree) {
  TempDir dir;
  dir.write("windy.toml", kWindy);
  // 0.1% strain is exceeded once gravity and wind have stretched the cloth.
  const ProcessResult result =
      run_flag_sim({"run", "windy.toml", "-o", "d.h5", "--set", "limits.max_strain=0.001", "--set",
                    "scene.duration=2", "--quiet"},
                   dir.path());
  EXPECT_EQ(result.exit_code, 3) << result.err;
  EXPECT_TRUE(result.err.starts_with("error: simulation diverged at t = ")) << result.err;
  EXPECT_NE(result.err.find("limits.max_strain"), std::string::npos);
  const data::OutputReader reader(dir.file("d.h5"));
  EXPECT_EQ(reader.attribute("status"), "diverged");
  EXPECT_NE(reader.attribute("status_reason").find("max link strain"), std::string::npos);
  ASSERT_GE(reader.frame_count(), 1);
  EXPECT_LT(reader.frame_count(), 61);
  for (double strain : reader.stat("max_strain")) EXPECT_LE(strain, 0.001);  // only good frames
}

TEST(Run, XpbdCompletesTheDefaultSceneAtTheSubstepsItChooses) {
  // At the scene's 13 substeps a frame XPBD's links stretched 37% by frame 2
  // at 129 x 193 (diverged); it now takes the 1350 its links need
  // (xpbd_propagation_substep_s). Half a second: the blow-up came in the first tenth.
  TempDir dir;
  const ProcessResult result = run_flag_sim(
      {"run", "--mode", "xpbd", "--frames", "16", "-o", "x.h5", "--quiet"}, dir.path());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const data::OutputReader reader(dir.file("x.h5"));
  EXPECT_EQ(reader.attribute("status"), "complete");
  EXPECT_EQ(reader.frame_count(), 16);
  EXPECT_EQ(reader.number_attribute("substeps_per_frame", 0), 1350.0);
}

TEST(Run, OutputEveryKeepsEveryNthFrame) {
  TempDir dir;
  dir.write("windy.toml", kWindy);
  ASSERT_EQ(run_flag_sim({"run", "windy.toml", "-o", "e.h5", "--set", "output.every=3", "--quiet"},
                         dir.path())
                .exit_code,
            0);
  const data::OutputReader reader(dir.file("e.h5"));
  EXPECT_EQ(reader.times_s(), (std::vector<double>{0.0, 0.1, 0.2}));
}

TEST(Run, CompressionKeepsEveryValueAndTakesLessRoom) {
  // [output] compression: HDF5's shuffle + deflate on the per-node datasets,
  // lossless; the readers take it as they take the plain file.
  TempDir dir;
  for (const char* level : {"0", "4"})
    ASSERT_EQ(run_flag_sim({"run", "--quiet", "--frames", "4", "--set", "flag.fine=[33,49]",
                            "--set", std::string("output.compression=") + level, "-o",
                            std::string("c") + level + ".h5"},
                           dir.path())
                  .exit_code,
              0);
  EXPECT_EQ(all_positions(dir.file("c4.h5")), all_positions(dir.file("c0.h5")));
  const data::OutputReader plain(dir.file("c0.h5")), packed(dir.file("c4.h5"));
  EXPECT_EQ(packed.velocities(3), plain.velocities(3));
  EXPECT_EQ(packed.node_strain(3), plain.node_strain(3));
  // 79% of the plain file's size measured here (76% on the default 129 x 193, README).
  EXPECT_LT(fs::file_size(dir.file("c4.h5")), fs::file_size(dir.file("c0.h5")) * 85 / 100);
  const ProcessResult bad =
      run_flag_sim({"run", "--quiet", "--set", "output.compression=10", "-o", "x.h5"}, dir.path());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("output.compression"), std::string::npos) << bad.err;
}

TEST(Validate, PrintsWhatWouldRun) {
  TempDir dir;
  dir.write("windy.toml", kWindy);
  const ProcessResult result = run_flag_sim({"validate", "windy.toml"}, dir.path());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("ok: windy.toml: scene \"windy\", mode mass-spring, 9 x 13 nodes"),
            std::string::npos)
      << result.out;
  EXPECT_EQ(dir.entry_count(), 1);  // validate writes nothing
}

TEST(SceneCommand, DefaultSceneRoundTrips) {
  TempDir dir;
  const ProcessResult printed = run_flag_sim({"scene", "--default"});
  ASSERT_EQ(printed.exit_code, 0);
  std::ifstream file(std::string(FLAGSIM_SOURCE_DIR) + "/scenes/default.toml");
  const std::string source((std::istreambuf_iterator<char>(file)),
                           std::istreambuf_iterator<char>());
  // The file as shipped but for its output.file, printed as a comment.
  const std::string pinned = "\nfile = \"out/default.h5\"\n";
  const std::size_t at = source.find(pinned);
  ASSERT_NE(at, std::string::npos);
  EXPECT_EQ(printed.out.substr(0, at), source.substr(0, at));
  EXPECT_EQ(printed.out.substr(at + 1, printed.out.find('\n', at + 1) - at - 1),
            "# file = \"out/default.h5\"  # absent: out/<scene.name>.h5");
  EXPECT_EQ(printed.out.substr(printed.out.find('\n', at + 1)),
            source.substr(at + pinned.size() - 1));
  dir.write("d.toml", printed.out);
  EXPECT_EQ(run_flag_sim({"validate", "d.toml"}, dir.path()).exit_code, 0);
}

// Issue 33, item 7: every scene key with its default, unit, range and meaning,
// from the parser itself.
TEST(SceneCommand, HelpKeysListsEveryKey) {
  const ProcessResult keys = run_flag_sim({"help", "keys"});
  ASSERT_EQ(keys.exit_code, 0) << keys.err;
  EXPECT_NE(keys.out.find("flag.areal_density = 0.2 (kg/m^2; in [0.0001, 100])"), std::string::npos)
      << keys.out;
  EXPECT_NE(keys.out.find("wind.friction = 0.015"), std::string::npos) << keys.out;
  const ProcessResult typo = run_flag_sim({"help", "kyes"});
  EXPECT_EQ(typo.exit_code, 2);
  EXPECT_NE(typo.err.find("did you mean 'keys'?"), std::string::npos) << typo.err;
}

// Issue 33, item 6: a minimal scene runs the schema's defaults, not the
// default scene's; validate says so, and that a flat flag will stay flat.
TEST(SceneCommand, AMinimalSceneIsToldWhatItsDefaultsAre) {
  TempDir dir;
  dir.write("min.toml", "[wind]\nvelocity = [5.0, 0.0, 0.0]\n");
  const ProcessResult check = run_flag_sim({"validate", "min.toml"}, dir.path());
  ASSERT_EQ(check.exit_code, 0) << check.err;
  EXPECT_NE(check.out.find("note: no scene.mode: mass-spring mode on the full 33 x 49 lattice"),
            std::string::npos)
      << check.out;
  EXPECT_NE(check.out.find("note: flag.initial_perturbation = 0 in a steady wind"),
            std::string::npos)
      << check.out;
  // With a mode and a perturbation, nothing to say.
  dir.write("set.toml",
            "[scene]\nmode = \"mass-spring\"\n[flag]\ninitial_perturbation = 0.005\n"
            "[wind]\nvelocity = [5.0, 0.0, 0.0]\n");
  const ProcessResult quiet = run_flag_sim({"validate", "set.toml"}, dir.path());
  ASSERT_EQ(quiet.exit_code, 0) << quiet.err;
  EXPECT_EQ(quiet.out.find("note:"), std::string::npos) << quiet.out;
}

// Issue 33, item 2: a copy of the printed default scene, renamed, writes
// out/<its name>.h5, not the default scene's file.
TEST(SceneCommand, ARenamedCopyOfTheDefaultSceneWritesUnderItsOwnName) {
  TempDir dir;
  std::string text = run_flag_sim({"scene", "--default"}).out;
  const std::size_t name = text.find("name = \"default\"");
  ASSERT_NE(name, std::string::npos);
  text.replace(name, std::string_view("name = \"default\"").size(), "name = \"windy\"");
  dir.write("windy.toml", text);
  const ProcessResult run = run_flag_sim(
      {"run", "windy.toml", "--set", "flag.fine=[17,25]", "--frames", "2", "--quiet"}, dir.path());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(fs::exists(dir.file("out/windy.h5")));
  EXPECT_FALSE(fs::exists(dir.file("out/default.h5")));
  // With --set, the printed scene leaves output.file out as well.
  const ProcessResult set = run_flag_sim({"scene", "--default", "--set", "scene.fps=24.0"});
  ASSERT_EQ(set.exit_code, 0) << set.err;
  EXPECT_EQ(set.out.find("file ="), std::string::npos) << set.out;
  EXPECT_NE(set.out.find("fps = 24"), std::string::npos) << set.out;
}

// Four frames of the default scene's hybrid on 17 x 25 into `dir`/`name`; the exit code.
int small_hybrid_run(const TempDir& dir, const std::string& name) {
  return run_flag_sim({"run", "--set", "flag.fine=[17,25]", "--frames", "4", "-o", name, "--quiet"},
                      dir.path())
      .exit_code;
}

// `scene FILE --set ...` prints what a run would take: the overrides applied,
// as TOML that runs the same scene again.
TEST(SceneCommand, PrintsTheSceneWithItsOverrides) {
  TempDir dir;
  dir.write("windy.toml", kWindy);
  const ProcessResult printed = run_flag_sim(
      {"scene", "windy.toml", "--set", "flag.fine=[5,7]", "--set", "seed=9"}, dir.path());
  ASSERT_EQ(printed.exit_code, 2) << "seed is scene.seed";  // a key in no table is an error
  const ProcessResult effective = run_flag_sim(
      {"scene", "windy.toml", "--set", "flag.fine=[5,7]", "--set", "scene.seed=9"}, dir.path());
  ASSERT_EQ(effective.exit_code, 0) << effective.err;
  EXPECT_NE(effective.out.find("fine = [5, 7]"), std::string::npos) << effective.out;
  // Every key the run takes, the ones the file leaves out marked (issue 33, item 7).
  EXPECT_NE(effective.out.find("shear_modulus = "), std::string::npos) << effective.out;
  EXPECT_NE(effective.out.find("# N/m; default"), std::string::npos) << effective.out;
  EXPECT_NE(effective.out.find("seed = 9"), std::string::npos) << effective.out;
  dir.write("effective.toml", effective.out);
  const ProcessResult check = run_flag_sim({"validate", "effective.toml"}, dir.path());
  EXPECT_NE(check.out.find("5 x 7 nodes"), std::string::npos) << check.out << check.err;
  const ProcessResult refused = run_flag_sim({"scene", "windy.toml", "--default"}, dir.path());
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_EQ(refused.err.rfind("error: scene", 0), 0u) << refused.err;
  // Without a file, validate and scene take the embedded scene, as run does
  // (issue 33, item 8).
  const ProcessResult embedded = run_flag_sim({"scene"}, dir.path());
  ASSERT_EQ(embedded.exit_code, 0) << embedded.err;
  EXPECT_NE(embedded.out.find("name = \"default\""), std::string::npos) << embedded.out;
  const ProcessResult valid = run_flag_sim({"validate"}, dir.path());
  ASSERT_EQ(valid.exit_code, 0) << valid.err;
  EXPECT_EQ(valid.out.rfind("ok: <default scene>: scene \"default\", mode hybrid", 0), 0u)
      << valid.out;
}

// --version names the libraries a bug report needs, as this binary runs them.
TEST(Version, NamesTheLibraries) {
  const ProcessResult version = run_flag_sim({"--version"});
  ASSERT_EQ(version.exit_code, 0);
  EXPECT_EQ(version.out.rfind("flag-sim ", 0), 0u) << version.out;
  for (const char* library :
       {"HDF5 1.", "Bullet 3.", "Eigen 3.", "Mesa", "toml++ ", "fmt ", "CLI11 "})
    EXPECT_NE(version.out.find(library), std::string::npos) << library << "\n" << version.out;
}

// `plot`: the run's statistics as a PNG of the size stats_plot.py draws
// (9 x 8 in at 100 dpi), written whole or not at all.
TEST(Plot, DrawsTheStatisticsOfARun) {
  TempDir dir;
  ASSERT_EQ(small_hybrid_run(dir, "p.h5"), 0);
  const ProcessResult plotted = run_flag_sim({"plot", "p.h5", "-o", "stats.png"}, dir.path());
  ASSERT_EQ(plotted.exit_code, 0) << plotted.err;
  std::ifstream png(dir.file("stats.png"), std::ios::binary);
  std::string header(24, '\0');
  png.read(header.data(), 24);
  EXPECT_EQ(header.substr(1, 3), "PNG");
  const auto be32 = [&](int at) {
    return (unsigned(std::uint8_t(header[at])) << 24) |
           (unsigned(std::uint8_t(header[at + 1])) << 16) |
           (unsigned(std::uint8_t(header[at + 2])) << 8) | unsigned(std::uint8_t(header[at + 3]));
  };
  EXPECT_EQ(be32(16), 900u);  // IHDR width
  EXPECT_EQ(be32(20), 800u);  // and height
  const int entries = dir.entry_count();
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"plot", "p.h5", "-o", "stats.jpg"},
        {"plot", "p.h5", "-o", "p.h5"},
        {"plot", "missing.h5", "-o", "m.png"}}) {
    const ProcessResult refused = run_flag_sim(args, dir.path());
    EXPECT_EQ(refused.exit_code, 2) << args[3];
    EXPECT_EQ(refused.err.rfind("error: ", 0), 0u) << refused.err;
    EXPECT_EQ(dir.entry_count(), entries) << args[3];
  }
}

TEST(Info, SummarisesARun) {
  TempDir dir;
  dir.write("windy.toml", kWindy);
  ASSERT_EQ(run_flag_sim({"run", "windy.toml", "-o", "i.h5", "--quiet"}, dir.path()).exit_code, 0);
  const ProcessResult result = run_flag_sim({"info", "i.h5"}, dir.path());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  for (const char* line : {"status    complete", "mode      mass-spring",
                           "lattice   9 x 13 (117 nodes)", "frames    7, t = 0 .. 0.2 s",
                           "effects   stretch,gravity,wind", "seed      3", "ms/frame (stretch "})
    EXPECT_NE(result.out.find(line), std::string::npos) << line << "\n" << result.out;
}

// info --json: the same facts as one JSON object a standard parser reads
// (Python's json here), with the hybrid's infill account.
TEST(Info, JsonCarriesTheSameFacts) {
  TempDir dir;
  ASSERT_EQ(small_hybrid_run(dir, "h.h5"), 0);
  const ProcessResult json = run_flag_sim({"info", "h.h5", "--json"}, dir.path());
  ASSERT_EQ(json.exit_code, 0) << json.err;
  dir.write("info.json", json.out);
  const ProcessResult parsed =
      run_process("/usr/bin/python3",
                  {"-c",
                   "import json, sys; d = json.load(open(sys.argv[1])); "
                   "print(d['status'], d['mode'], d['lattice']['nodes'], d['frames'], d['seed'], "
                   "d['infill']['frames'], d['infill']['converged_frames'], "
                   "d['strain']['max'] < 0.01, sorted(d['stage_ms'])[0], d['effects'][0])",
                   "info.json"},
                  dir.path());
  ASSERT_EQ(parsed.exit_code, 0) << parsed.err << json.out;
  EXPECT_EQ(parsed.out, "complete hybrid 425 4 1 4 4 True checks stretch\n") << json.out;
}

// A mode chosen on the command line runs any valid scene: the tables it does
// not use are named in one note and ignored (in the file itself they stay an
// error), so compare can run a hybrid scene with [wrinkles] against the
// mass-spring reference.
TEST(Run, AModeFromTheCommandLineIgnoresTablesItDoesNotUse) {
  TempDir dir;
  dir.write(
      "w.toml",
      "[scene]\nmode = \"hybrid\"\nduration = 0.1\n[flag]\nfine = [17, 25]\ncoarse = [9, 13]\n"
      "[wrinkles]\nfiber_radius = 0.001\n[infill]\nsolver = \"smooth\"\n");
  const ProcessResult run =
      run_flag_sim({"run", "w.toml", "--mode", "mass-spring", "-o", "m.h5", "--quiet"}, dir.path());
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("note: mass-spring mode does not use [infill], [wrinkles]: ignored"),
            std::string::npos)
      << run.out;
  const ProcessResult compared =
      run_flag_sim({"compare", "w.toml", "--frames", "3", "-o", "c.csv"}, dir.path());
  EXPECT_EQ(compared.exit_code, 0) << compared.err;
  dir.write("strict.toml", "[scene]\nmode = \"mass-spring\"\n[wrinkles]\nfiber_radius = 0.001\n");
  const ProcessResult strict = run_flag_sim({"validate", "strict.toml"}, dir.path());
  EXPECT_EQ(strict.exit_code, 2);
  EXPECT_NE(strict.err.find("strict.toml:3:1: wrinkles: wrinkles are made by the infill"),
            std::string::npos)
      << strict.err;
}

}  // namespace
}  // namespace flagsim::test
