#pragma once
// Step 3.2: initial move by interpolated, weighted motion vectors.
// positions_m is the whole dense lattice [J*K] in m, row-major; previous_m the
// lattice before this deformation step (the paper's motion vectors are
// positions_m - previous_m at a fiber's end nodes).
#include <Eigen/Core>
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

/// The rigid motion that best carries a cell's boundary nodes from `previous_m`
/// to `positions_m` (least squares, Kabsch): x -> R (x - c_old) + c_new.
struct CellFrame {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Vec3 old_centre = Vec3::Zero();
  Vec3 new_centre = Vec3::Zero();
  Vec3 apply(const Vec3& x) const { return rotation * (x - old_centre) + new_centre; }
};

/// The CellFrame of the cell with top-left dense node (j0, k0), rows x cols links.
CellFrame cell_frame(const Lattice& lattice, int j0, int k0, int rows, int cols,
                     std::span<const Vec3> positions_m, std::span<const Vec3> previous_m);

/// Step 3.2 for the interior of every cell, in the cell's co-moving frame
/// (CellFrame F, fitted to the edges): node (j, k) of the cell with corners
/// (j0, k0), (j0+rs, k0+cs) goes to F(its previous position) plus the average
/// of its row's and its column's interpolated end motions relative to F, each
/// times its end_weight (the ends are on the cell's edges, placed by 3.1).
/// Interpretation: the paper's weights keep the previous shape for the small
/// motions it assumes; a cell that turns or travels by a fair part of its size
/// in one step (a flag's fly end) would leave its middle behind and stretch its
/// links by tens of percent. Carried by F, the shape is kept whatever the
/// cell's rigid motion; for a cell that does not turn or travel it is the
/// paper's move exactly.
void initial_move_cells(const Lattice& lattice, const CellGrid& grid, std::span<Vec3> positions_m,
                        std::span<const Vec3> previous_m);

}  // namespace flagsim::infill
