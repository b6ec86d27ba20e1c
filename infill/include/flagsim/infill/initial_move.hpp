#pragma once
// Step 3.2: initial move by interpolated, weighted motion vectors.
// positions_m is the whole dense lattice [J*K] in m, row-major; previous_m the
// lattice before this deformation step (the paper's motion vectors are
// positions_m - previous_m at a fiber's end nodes).
#include <span>

#include "flagsim/core/lattice.hpp"
#include "flagsim/core/vec3.hpp"
#include "flagsim/infill/cell_grid.hpp"
#include "flagsim/infill/fiber.hpp"

namespace flagsim::infill {

/// Step 3.2's weight of a node at fraction s in [0, 1] along its fiber.
/// Interpretation (the paper gives only the shape: near 1 at the ends, 0 at the
/// middle): the simplest such weight, linear in the distance to the nearer end,
/// w(s) = |1 - 2 s|.
double end_weight(double s);

/// Unweighted motion at fraction s, linear in the index between the motions of
/// the two end nodes (the interpolation of 3.2 before weighting, and the target
/// of 3.3, Fig. 7).
Vec3 interpolated_motion(const Fiber& fiber, double s, std::span<const Vec3> positions_m,
                         std::span<const Vec3> previous_m);

/// Step 3.2 on one fiber alone (used for cell edges, whose only neighbours
/// along the fiber are its ends): interior node i moves from its previous
/// position by w(s) times the interpolated motion of the ends.
void weighted_initial_move(const Fiber& fiber, std::span<Vec3> positions_m,
                           std::span<const Vec3> previous_m);

/// Step 3.2 for the interior of every cell: node (j, k) of the cell with
/// corners (j0, k0), (j0+rs, k0+cs) moves from its previous position by the
/// average of its row's and its column's interpolated end motions, each times
/// its end_weight (the ends are on the cell's edges, placed by 3.1).
void initial_move_cells(const Lattice& lattice, const CellGrid& grid, std::span<Vec3> positions_m,
                        std::span<const Vec3> previous_m);

}  // namespace flagsim::infill
