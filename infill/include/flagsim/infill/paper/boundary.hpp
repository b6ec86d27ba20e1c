#pragma once
// Step 3.1: the edges of a cell, the fibers between two neighbouring coarse
// nodes, placed from their ends. The paper gives the edges directly ("or
// computed by something else"); interpretation:
//  - an edge on a coarse line with more coarse nodes (the hybrid case) is laid
//    on the circular arc through its ends on which every link has its rest
//    length exactly (lay_arc): the fiber keeps its length by construction,
//    at the cost of a few sines, where relaxing a chain into shape took up to
//    hundreds of passes. The arc bulges out of the cloth (along its normal),
//    to the side it bulged to in the previous step, so that edges do not jump
//    across their chords from frame to frame; a straight edge takes the side
//    the coarse line bends to (the Catmull-Rom curve through the coarse nodes
//    before and after). An edge whose ends are farther apart than its length
//    is laid evenly on the chord.
//  - an edge alone on its line (corners only, paper Figs. 9-10) gets the fiber
//    treatment of 3.2-3.3 from its two ends and its previous shape; the caller
//    then relaxes it as a fiber (3.4).
#include <cstddef>
#include <span>

#include "flagsim/core/vec3.hpp"
#include "flagsim/infill/fiber.hpp"

namespace flagsim::infill {

/// Places the interior nodes of the edge `fiber`, whose end nodes are already
/// at their new positions. before_node / after_node: dense indices of the
/// coarse nodes one cell before its start and one cell after its end on the
/// same coarse line, or -1. normal: the cloth's normal at the edge (zero when
/// unknown). previous_m: the lattice before this step.
void move_edge(const Fiber& fiber, std::ptrdiff_t before_node, std::ptrdiff_t after_node,
               const Vec3& normal, std::span<Vec3> positions_m, std::span<const Vec3> previous_m,
               double length_tolerance);

/// Lays the interior nodes of `fiber` (ends in place) on the circular arc
/// through its ends, bulging toward `bow` (its part across the chord), on which
/// every neighbour pair is exactly S apart: n equal chords S on a circle span
/// the ends when c / S = sin(phi/2) / sin(phi/(2n)), phi the arc's angle. With
/// no slack (ends n S apart or more) the nodes go evenly on the chord and it
/// returns false.
bool lay_arc(const Fiber& fiber, std::span<Vec3> positions_m, const Vec3& bow);

}  // namespace flagsim::infill
