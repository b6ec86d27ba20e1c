#pragma once
// Self-contact ([contact] thickness; issue 31): the cloth keeps its
// non-neighbouring parts at least `thickness` apart.
//
// The cloth is the lattice's triangles, two per cell: (j, k), (j, k+1),
// (j+1, k+1) and (j, k), (j+1, k+1), (j+1, k), and their edges (rows,
// columns and that diagonal). A node and a triangle, or two edges, are
// neighbours, and never pushed apart, when they share a node or lie closer
// than kNeighbourReach x thickness at rest: a fold brings such parts together
// by construction (a cloth folded flat on itself turns through a half circle
// of diameter `thickness`, about 1.6 thickness of cloth, around its fold line).
//
// Method: a projection after each step, as for the solids (obstacles.hpp), so
// no stiffness and no change of any stability limit, and the same code for
// every backend. Every node closer than `thickness` to a non-neighbouring
// triangle is pushed out to `thickness`, node and triangle corners moving in
// proportion to their weights (free nodes 1, pinned 0; the corners by their
// barycentric weights: the position-based point-triangle constraint of
// Bridson, Fedkiw & Anderson 2002 and Mueller et al. 2007); every two
// non-neighbouring edges closer than `thickness` between their ends are pushed
// apart along the line of their closest points the same way. The part of the
// relative velocity that closes the gap is removed (inelastic, frictionless).
// Each keeps the side it was on at the step's start (`before`): a node that
// passed through a triangle, or an edge through an edge, in one step goes
// back to its own side, which is what keeps two layers from crossing. With
// both kinds of pair a mesh that starts without intersections keeps none
// while no node travels `thickness` in a step (an intersection begins with a
// node through a triangle or an edge through an edge). Gauss-Seidel over the
// pairs (kContactPasses).
//
// Cost: candidate pairs (closer than thickness + margin) are found only when
// some node has moved half the margin since they last were, and every step
// looks at those alone: a pair closer than `thickness` now was closer than
// thickness + margin then. To find them, nodes, triangles and edges are
// grouped in blocks of up to 4 x 4 cells; a pair of blocks is looked into only
// when their boxes (widened by the reach) overlap, and a block with itself or
// a neighbouring block only when their triangles' normals do not fit in one
// cone of kFlatAngle about a common axis: a patch within 55 degrees of one
// plane cannot bring parts more than 2 thicknesses apart in the cloth (1 / cos
// 55 = 1.74, with room for 15% compression) within `thickness` of each other.
// The blocks are grouped again in super-blocks of kSuperBlock x kSuperBlock,
// with boxes and cones that hold their blocks': the pairs of super-blocks
// whose boxes overlap are found by sweep and prune along the lattice's longer
// side, a super-block with itself or a neighbour that is one flat patch is
// passed over whole, and the pairs of blocks are looked for only in the rest
// (then visited in a fixed order). A flapping flag is flat over most of its
// 16-cell patches: the hybrid's dense lattice (1536 blocks, laid anew and
// searched every frame) spends 0.6 ms a frame on its search instead of 2.9.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "flagsim/core/lattice.hpp"
#include "flagsim/core/vec3.hpp"

namespace flagsim::physics {

/// Parts of the cloth closer than this many thicknesses at rest are neighbours.
inline constexpr double kNeighbourReach = 2.0;
/// Half-angle of the normal cone within which a patch cannot touch itself, rad (55 degrees).
inline constexpr double kFlatAngle = 0.96;
/// Gauss-Seidel passes over the pairs a projection found, at most: a pass
/// that finds no pair short of the thickness by more than kContactTolerance
/// of it is the last (pairs share nodes, so one pass leaves some short).
inline constexpr int kContactPasses = 16;
inline constexpr double kContactTolerance = 1e-3;
/// Blocks a side of a super-block (16 cells with blocks of 4): the search's
/// first level, on which a flat patch is passed over whole.
inline constexpr int kSuperBlock = 4;

class SelfContact {
 public:
  SelfContact(const Lattice& lattice, double thickness_m);

  /// Pushes every node out of the `thickness` of every non-neighbouring
  /// triangle, and every two non-neighbouring edges apart to it, on the side
  /// they were on in `before_m` [n] (empty: the side they are on now);
  /// velocities [n] m/s (may be empty) lose their closing part. Nodes with
  /// `pinned` (may be empty) do not move. Returns how many pairs were pushed
  /// (0: nothing moved).
  int project(std::span<Vec3> x_m, std::span<Vec3> v_m_s, std::span<const std::uint8_t> pinned,
              std::span<const Vec3> before_m);

  /// With `before_m`, a pair closer than `reach_m` there (a node to its
  /// triangle's plane, two edges between their closest points) keeps the side
  /// it has now rather than the one it had there: for a `before_m` that is not
  /// the cloth a moment ago but a coarser surface (the hybrid's dense lattice
  /// takes its sides from the coarse one, on which parts of one layer lie in
  /// one plane). 0 (the default): every pair keeps its side at `before_m`.
  void set_side_reach(double reach_m) { side_reach_m_ = reach_m; }

  /// The smallest distance between non-neighbouring parts (a node and a
  /// triangle, or two edges between their ends) among those within `reach_m`
  /// of each other, m (reach_m when none is): what the tests read.
  double closest_m(std::span<const Vec3> x_m, double reach_m);

 private:
  /// A node against a triangle (its cell and which half).
  struct NodeTriangle {
    std::uint32_t node;
    std::uint32_t cell;
    std::uint8_t half;
    float apart_m;  ///< their distance when found
  };
  /// Two edges (indices into edges_).
  struct EdgeEdge {
    std::uint32_t a, b;
    float apart_m;  ///< their distance when found
  };
  /// The triangle's corners: half 0 (j,k)-(j,k+1)-(j+1,k+1), half 1 (j,k)-(j+1,k+1)-(j+1,k).
  std::array<std::uint32_t, 3> corners(std::uint32_t cell, int half) const;
  /// Whether `node` and `cell` are neighbours in the cloth (see the top).
  bool neighbours(std::uint32_t node, std::uint32_t cell) const;
  bool edge_neighbours(std::uint32_t a, std::uint32_t b) const;
  /// node_triangles_ and edge_edges_: every pair within `reach_m` of each
  /// other at `x_m` that are not neighbours.
  void find_candidates(std::span<const Vec3> x_m, double reach_m);
  /// One Gauss-Seidel pass (`first`: over every candidate, keeping the near
  /// ones for the passes after it); returns the largest gap it closed, m.
  double pass(bool first, std::span<Vec3> x_m, std::span<Vec3> v_m_s,
              std::span<const std::uint8_t> pinned, std::span<const Vec3> before_m, int& pushed);

  Lattice lattice_;
  double thickness_m_;
  double side_reach_m_ = 0.0;    ///< set_side_reach
  double margin_m_;              ///< candidates are found within thickness + margin
  int block_cells_;              ///< cells per block side
  int block_rows_, block_cols_;  ///< blocks down and across
  double neighbour_cells_x_, neighbour_cells_y_;     ///< kNeighbourReach x thickness, in cells
  std::vector<std::array<std::uint32_t, 2>> edges_;  ///< nodes of every edge
  std::vector<std::uint32_t> block_edges_;           ///< edges owned by each block, block by block
  std::vector<std::uint32_t> block_edge_start_;      ///< [blocks + 1] into block_edges_
  std::vector<NodeTriangle> node_triangles_;         ///< candidates
  std::vector<EdgeEdge> edge_edges_;                 ///< candidates
  std::vector<NodeTriangle> near_nt_;                ///< the first pass's near candidates
  std::vector<EdgeEdge> near_ee_;
  std::vector<Vec3> anchor_;  ///< where the nodes were when the candidates were found
  /// [n] how far each node has moved since, m: a pair found `apart_m` apart
  /// that its nodes' moves cannot have brought near is passed over.
  std::vector<double> moved_;
  // Per block: box low and high corners; its normals' cone (unit axis, half-angle rad).
  std::vector<Vec3> low_, high_, axis_;
  std::vector<double> spread_;
  std::vector<Vec3> normal_sum_;            ///< per block: the sum of its unit normals
  std::vector<Vec3> normals_;               ///< per triangle (2 per cell), at x
  std::vector<std::uint32_t> block_order_;  ///< super-blocks by their box's low end (scratch)
  std::vector<std::array<std::uint32_t, 2>> block_pairs_;  ///< blocks whose boxes overlap
  // Super-blocks of kSuperBlock x kSuperBlock blocks: boxes and cones that
  // hold their blocks', and the pairs whose boxes overlap.
  int super_rows_, super_cols_;
  std::vector<Vec3> super_low_, super_high_, super_axis_;
  std::vector<double> super_spread_;
  std::vector<std::array<std::uint32_t, 2>> super_pairs_;
};

}  // namespace flagsim::physics
