#pragma once
// Whole-scene checks run after every key has been read on its own.
#include <optional>
#include <string>
#include <utility>

#include "flagsim/scene/scene.hpp"
#include "toml_reader.hpp"

namespace flagsim::detail {

/// Cross-key consistency: lattice sizes, coarse divisibility, mode requirements.
/// Tables the scene's mode does not use are an error, unless the mode was
/// chosen on the command line (`mode_from_command_line`): then they are
/// dropped from `scene` and named in one of `scene.notes`.
void check_consistency(Scene& scene, const TableReader& root, const TableReader& scene_in,
                       const TableReader& flag_in, bool mode_from_command_line);

/// What stops the creases of `scene` from running, as (dotted key, message):
/// fold lines without [creases], creases without [bending], or a mode or
/// backend without creases; nullopt when nothing does. Shared by the parser
/// (which names the line) and check_scene (a Scene built in code).
std::optional<std::pair<const char*, std::string>> crease_problem(const Scene& scene);

}  // namespace flagsim::detail
