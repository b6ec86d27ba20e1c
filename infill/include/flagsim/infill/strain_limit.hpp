#pragma once
// What makes the infill's problem solvable: every dense fiber between two
// coarse nodes must span their distance at its rest length, so no coarse row
// or column link may be longer than its rest length (plus what the dense links
// may stretch). The coarse physics stretches its links by a percent or more
// where the fly end whips; no infill can then keep the dense links within 1%.
//
// limit_stretch shortens the too-long links of a lattice (Provot 1995's strain
// limiting, stretch only: a short link is slack, which the fibers take up by
// bending): Gauss-Seidel passes, each moving a link's nodes toward each other
// to (1 + max_strain) S, split half and half, all on the free one when the
// other is fixed. The hybrid applies it to the coarse nodes it hands to the
// infill, never to the physics' own state.
#include <cstdint>
#include <span>

#include "flagsim/core/lattice.hpp"

namespace flagsim::infill {

/// @param fixed       [J*K], 1 for nodes that must not move (pins)
/// @param max_strain  largest relative stretch a row or column link keeps
/// @return the passes made; stops after a pass that moved nothing, or `max_passes`
int limit_stretch(const Lattice& lattice, std::span<const std::uint8_t> fixed,
                  std::span<Vec3> positions_m, double max_strain, int max_passes);

}  // namespace flagsim::infill
