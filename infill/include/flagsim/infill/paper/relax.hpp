#pragma once
// Step 3.4 over the whole dense lattice: Gauss-Seidel passes over every row and
// column link, each moving its two nodes back toward the rest distance S (a
// held node does not move, its partner takes the whole correction). "Repeating
// gives an approximate solution": it stops after `max_sweeps`, or as soon as a
// whole pass found every link within `tolerance` (relative) of its rest length.
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "flagsim/core/lattice.hpp"
#include "flagsim/infill/fiber.hpp"

namespace flagsim::infill {

/// Step 3.4 on one fiber (Gauss-Seidel along it, ends held): passes that move
/// each neighbour pair back toward the rest distance S, at most `max_sweeps`,
/// stopping once a pass finds every pair within `tolerance`. Returns the passes.
int relax_fiber(const Fiber& fiber, std::span<Vec3> positions_m, int max_sweeps, double tolerance);

/// One link of 3.4: moves a and b along their link to distance `rest_m` (half
/// each; all of it on the free one when the other is held). Returns |d - S| / S
/// before the move. One square root and one division: it is the hot loop.
inline double project_link(Vec3& a, Vec3& b, bool a_held, bool b_held, double rest_m,
                           double inv_rest) {
  const Vec3 d = b - a;
  const double length2 = d.squaredNorm();
  if (length2 == 0.0) return 1.0;
  const double length = std::sqrt(length2);
  const double error = std::abs(length * inv_rest - 1.0);
  if (a_held && b_held) return error;
  const double shrink = 1.0 - rest_m / length;  // fraction of d that closes the gap
  if (a_held) {
    b -= shrink * d;
  } else if (b_held) {
    a += shrink * d;
  } else {
    const Vec3 half = (0.5 * shrink) * d;
    a += half;
    b -= half;
  }
  return error;
}

/// @param held  [J*K], 1 for nodes that must not move (the coarse nodes)
/// @return the number of passes made
int relax_lattice(const Lattice& lattice, std::span<const std::uint8_t> held,
                  std::span<Vec3> positions_m, int max_sweeps, double tolerance);

}  // namespace flagsim::infill
