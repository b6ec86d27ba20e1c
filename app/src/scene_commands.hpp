#pragma once
// `flag-sim validate` and `flag-sim scene`, and the scene loading every command shares.
// Returns the process exit code (contract: "Exit codes"); user mistakes are
// thrown as UserError and reported by main.
#include <span>
#include <string>
#include <vector>

#include "flagsim/scene/scene.hpp"
#include "flagsim/scene/scene_parser.hpp"

namespace flagsim::app {

/// Reads the scene a command names (or the default one), with the overrides.
Scene load_scene(const std::string& scene_path, std::span<const Override> overrides);
Scene load_scene(const std::string& scene_path, const std::vector<std::string>& overrides);

/// The embedded default scene as `scene --default` prints it: its output.file
/// line a comment, so that a renamed copy writes out/<scene.name>.h5.
std::string printable_default_scene();

int validate_command(const std::string& scene_path, const std::vector<std::string>& sets);
/// `scene`: the embedded default scene as shipped (--default), or a scene (a
/// file, or with none the embedded one) as its run takes it, --set applied:
/// every key it uses, defaults marked (effective_scene_toml).
int scene_command(const std::string& scene_path, bool print_default,
                  const std::vector<std::string>& sets);

}  // namespace flagsim::app
