#pragma once
// Step 3.4 over the whole dense lattice: Gauss-Seidel passes over every row and
// column link, each moving its two nodes back toward the rest distance S (a
// held node does not move, its partner takes the whole correction). "Repeating
// gives an approximate solution": it stops after `max_sweeps`, or as soon as a
// whole pass found every link within `tolerance` (relative) of its rest length.
#include <cstdint>
#include <span>
#include <vector>

#include "flagsim/core/lattice.hpp"

namespace flagsim::infill {

/// @param held  [J*K], 1 for nodes that must not move (the coarse nodes)
/// @return the number of passes made
int relax_lattice(const Lattice& lattice, std::span<const std::uint8_t> held,
                  std::span<Vec3> positions_m, int max_sweeps, double tolerance);

}  // namespace flagsim::infill
