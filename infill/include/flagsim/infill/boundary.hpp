#pragma once
// Step 3.1: the edges of a cell, the fibers between two neighbouring coarse
// nodes, placed from their ends. The paper gives the edges directly ("or
// computed by something else"); interpretation:
//  - an edge on a coarse line with more coarse nodes (the hybrid case) starts
//    on the Catmull-Rom curve through the coarse nodes of that line, so it
//    bends the way the coarse lattice does (interpolating the end motions alone
//    keeps every edge a straight chord, which no relaxation can bend: a straight
//    chain has no stiffness across itself);
//  - an edge alone on its line (corners only, paper Figs. 9-10) gets the fiber
//    treatment of 3.2-3.3 from its two ends and its previous shape.
// The caller then relaxes it as a fiber (3.4).
#include <cstddef>
#include <span>

#include "flagsim/core/vec3.hpp"
#include "flagsim/infill/fiber.hpp"

namespace flagsim::infill {

/// Places the interior nodes of the edge `fiber`, whose end nodes are already
/// at their new positions. before_node / after_node: dense indices of the
/// coarse nodes one cell before its start and one cell after its end on the
/// same coarse line, or -1. previous_m: the lattice before this step.
void move_edge(const Fiber& fiber, std::ptrdiff_t before_node, std::ptrdiff_t after_node,
               std::span<Vec3> positions_m, std::span<const Vec3> previous_m,
               double length_tolerance);

}  // namespace flagsim::infill
