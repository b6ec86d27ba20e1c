// scene_keys.cpp: the scene as its run takes it (flag-sim scene FILE) and the
// key reference (flag-sim help keys), both from the parser's own reads.
#include "flagsim/scene/scene_keys.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "flagsim/scene/scene_parser.hpp"

namespace flagsim {
namespace {

namespace fs = std::filesystem;

std::string read(const fs::path& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

// Every shipped scene, the embedded default first.
std::vector<std::pair<std::string, std::string>> shipped_scenes() {
  std::vector<std::pair<std::string, std::string>> scenes = {
      {"default", std::string(default_scene_toml())}};
  std::vector<fs::path> paths;
  for (const auto& entry :
       fs::recursive_directory_iterator(fs::path(FLAGSIM_SOURCE_DIR) / "scenes"))
    if (entry.path().extension() == ".toml") paths.push_back(entry.path());
  std::sort(paths.begin(), paths.end());
  for (const fs::path& path : paths) scenes.emplace_back(path.string(), read(path));
  return scenes;
}

// The printed scene's keys and values: its comment lines and the comments
// after values left out (a printed default is given when read back).
std::string values_only(const std::string& text) {
  std::istringstream in(text);
  std::string out, line;
  while (std::getline(in, line)) {
    if (line.starts_with("#")) continue;
    if (const std::size_t comment = line.find("  #"); comment != std::string::npos)
      line.erase(line.find_last_not_of(' ', comment) + 1);
    out += line + "\n";
  }
  return out;
}

bool has_meaning(const std::string& key) {
  const auto meanings = key_meanings();
  return std::any_of(meanings.begin(), meanings.end(),
                     [&](const KeyMeaning& m) { return m.key == key && !m.meaning.empty(); });
}

// Issue 33, item 7: the printed scene is the same scene (what a run reads
// from it is the same), prints the same keys and values again, and every key
// the parser read has a meaning in the reference.
TEST(SceneKeys, EveryShippedSceneReadsBackAsItself) {
  const auto scenes = shipped_scenes();
  ASSERT_GT(scenes.size(), 40u);
  for (const auto& [name, text] : scenes) {
    std::vector<SceneKey> keys;
    const Scene scene = parse_scene(text, name, std::span<const Override>(), &keys);
    const std::string printed = effective_scene_toml(scene, keys);
    std::vector<SceneKey> again_keys;
    const Scene again = parse_scene(printed, name, std::span<const Override>(), &again_keys);
    EXPECT_EQ(values_only(effective_scene_toml(again, again_keys)), values_only(printed)) << name;
    // The same scene: everything a run reads from it, but the text it came from.
    EXPECT_EQ(again.name, scene.name) << name;
    EXPECT_EQ(again.mode, scene.mode) << name;
    EXPECT_EQ(again.simulated_frames(), scene.simulated_frames()) << name;
    EXPECT_EQ(again.flag.fine_rows, scene.flag.fine_rows) << name;
    EXPECT_EQ(again.flag.coarse, scene.flag.coarse) << name;
    EXPECT_EQ(again.flag.shear_modulus_n_m, scene.flag.shear_modulus_n_m) << name;
    EXPECT_EQ(again.wind.has_value(), scene.wind.has_value()) << name;
    EXPECT_EQ(again.gravity.has_value(), scene.gravity.has_value()) << name;
    EXPECT_EQ(again.keyframes.size(), scene.keyframes.size()) << name;
    EXPECT_EQ(again.infill.has_value(), scene.infill.has_value()) << name;
    EXPECT_EQ(again.solver.backend, scene.solver.backend) << name;
    EXPECT_EQ(again.output.file, scene.output.file) << name;
    EXPECT_EQ(again.notes, scene.notes) << name;
    for (const SceneKey& k : keys) EXPECT_TRUE(has_meaning(k.key)) << k.key << " in " << name;
  }
}

TEST(SceneKeys, NumbersInTheirShortestFormAndDefaultsMarked) {
  std::vector<SceneKey> keys;
  const Scene scene =
      parse_scene(default_scene_toml(), "default", std::span<const Override>(), &keys);
  const std::string printed = effective_scene_toml(scene, keys);
  EXPECT_NE(printed.find("areal_density = 0.2 "), std::string::npos) << printed;
  EXPECT_NE(printed.find("acceleration = [0.0, -9.81, 0.0]"), std::string::npos) << printed;
  EXPECT_EQ(printed.find("0000000"), std::string::npos) << printed;
  // Keys the file leaves out but the run uses, marked.
  EXPECT_NE(printed.find("shear_modulus = 2000.0"), std::string::npos) << printed;
  EXPECT_NE(printed.find("# N/m; default"), std::string::npos) << printed;
  EXPECT_NE(printed.find("[solver]\nbackend = \"spring-damper\""), std::string::npos) << printed;
  // In the file's order of tables, not alphabetical.
  EXPECT_LT(printed.find("[scene]"), printed.find("[flag]"));
  EXPECT_LT(printed.find("[flag]"), printed.find("[wind]"));
  // The implicit backend's keys only where that backend runs.
  EXPECT_EQ(printed.find("linear"), std::string::npos) << printed;
  const std::vector<std::string> sets = {"solver.backend=\"implicit\""};
  std::vector<SceneKey> implicit_keys;
  const Scene implicit =
      parse_scene(default_scene_toml(), "default", set_overrides(sets), &implicit_keys);
  EXPECT_NE(effective_scene_toml(implicit, implicit_keys).find("linear = \"cg\""),
            std::string::npos);
}

TEST(SceneKeys, TheReferenceListsEveryKeyWithItsDefaultAndMeaning) {
  const std::string reference = keys_reference();
  for (const KeyMeaning& m : key_meanings()) {
    EXPECT_NE(reference.find("  " + std::string(m.key)), std::string::npos) << m.key;
    EXPECT_NE(reference.find(std::string(m.meaning)), std::string::npos) << m.key;
  }
  EXPECT_NE(reference.find("flag.shear_modulus = 2000.0 (N/m; in [0, 1e+08])"), std::string::npos)
      << reference;
  EXPECT_NE(reference.find("wind.drag = 1.0"), std::string::npos) << reference;
  EXPECT_NE(reference.find("solver.linear = \"cg\""), std::string::npos) << reference;
  EXPECT_NE(reference.find("keyframe.time (no default)"), std::string::npos) << reference;
}

}  // namespace
}  // namespace flagsim
