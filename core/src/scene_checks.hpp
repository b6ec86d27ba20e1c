#pragma once
// Whole-scene checks run after every key has been read on its own.
#include "flagsim/core/scene.hpp"
#include "toml_reader.hpp"

namespace flagsim::detail {

/// Cross-key consistency: lattice sizes, coarse divisibility, mode requirements.
void check_consistency(const Scene& scene, const TableReader& root, const TableReader& scene_in,
                       const TableReader& flag_in);

}  // namespace flagsim::detail
