#pragma once
// Whole-scene checks run after every key has been read on its own.
#include "flagsim/scene/scene.hpp"
#include "toml_reader.hpp"

namespace flagsim::detail {

/// Cross-key consistency: lattice sizes, coarse divisibility, mode requirements.
/// Tables the scene's mode does not use are an error, unless the mode was
/// chosen on the command line (`mode_from_command_line`): then they are
/// dropped from `scene` and named in one of `scene.notes`.
void check_consistency(Scene& scene, const TableReader& root, const TableReader& scene_in,
                       const TableReader& flag_in, bool mode_from_command_line);

}  // namespace flagsim::detail
