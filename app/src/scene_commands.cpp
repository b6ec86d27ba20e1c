// `flag-sim validate` and `flag-sim scene`, and the shared scene loading.
#include "scene_commands.hpp"

#include <fmt/format.h>

#include "flagsim/core/errors.hpp"
#include "flagsim/scene/scene_keys.hpp"
#include "flagsim/scene/scene_parser.hpp"
#include "flagsim/sim/simulation.hpp"

namespace flagsim::app {

Scene load_scene(const std::string& scene_path, std::span<const Override> overrides) {
  if (scene_path.empty()) return parse_scene(default_scene_toml(), kDefaultSceneName, overrides);
  return load_scene_file(scene_path, overrides);
}

Scene load_scene(const std::string& scene_path, const std::vector<std::string>& overrides) {
  return load_scene(scene_path, set_overrides(overrides));
}

int validate_command(const std::string& scene_path, const std::vector<std::string>& sets) {
  const Scene scene = load_scene(scene_path, sets);
  const std::unique_ptr<sim::Simulation> simulation = sim::make_simulation(scene);
  std::string stepping;
  for (const NamedNumber& number : simulation->numbers())
    stepping += fmt::format(", {} {:.4g}{}", number.name, number.value,
                            number.units == "1" ? "" : " " + number.units);
  fmt::print("ok: {}: scene \"{}\", mode {}, {} x {} nodes, {} frames at {} fps, effects {}{}\n",
             scene_path.empty() ? std::string(kDefaultSceneName) : scene_path, scene.name,
             to_string(scene.mode), scene.flag.fine_rows, scene.flag.fine_cols,
             scene.simulated_frames(), scene.fps, fmt::join(simulation->effects(), ","), stepping);
  for (const std::string& note : scene.notes) fmt::print("{}\n", note);
  if (auto note = sim::wrinkle_resolution_note(scene)) fmt::print("{}\n", *note);
  return int(ExitCode::kSuccess);
}

std::string printable_default_scene() {
  // The embedded scene names its output file (a run of it writes where it
  // always has); a copy renamed should write out/<its name>.h5, so the copy
  // leaves the line as a comment (issue 33, item 2).
  std::string text(default_scene_toml());
  const std::string_view pinned = "\nfile = \"out/default.h5\"\n";
  if (const std::size_t at = text.find(pinned); at != std::string::npos)
    text.replace(at + 1, pinned.size() - 2,
                 "# file = \"out/default.h5\"  # absent: out/<scene.name>.h5");
  return text;
}

int scene_command(const std::string& scene_path, bool print_default,
                  const std::vector<std::string>& sets) {
  if (print_default && !scene_path.empty())
    throw UserError(
        fmt::format("scene {} --default: give a scene file or --default, not both", scene_path));
  if (print_default && sets.empty()) {  // the file itself, comments and all
    fmt::print("{}", printable_default_scene());
    return int(ExitCode::kSuccess);
  }
  // The scene as `run` would take it: the file with every --set applied,
  // checked, every key its run uses with its value (defaults marked).
  std::vector<SceneKey> keys;
  const std::vector<Override> overrides = set_overrides(sets);
  // No file: the embedded scene, as `run` with no file takes it.
  const Scene scene = scene_path.empty() ? parse_scene(printable_default_scene(), kDefaultSceneName,
                                                       overrides, &keys)
                                         : load_scene_file(scene_path, overrides, &keys);
  fmt::print("{}", effective_scene_toml(scene, keys));
  for (const std::string& note : scene.notes) fmt::print(stderr, "{}\n", note);
  return int(ExitCode::kSuccess);
}

}  // namespace flagsim::app
