#pragma once
// The paper's deformation steps (section 3), each on fibers of the dense
// lattice. positions_m is the whole dense lattice [J*K] in m, row-major;
// previous_m the lattice before this deformation step (the motion vectors of
// the paper are positions_m - previous_m at a fiber's end nodes).
#include <cstdint>
#include <span>

#include "flagsim/core/vec3.hpp"
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

/// Step 3.3 on one fiber: if its length differs from the rest length by more
/// than `tolerance` (relative), move its interior nodes along the straight
/// lines toward the unweighted targets previous + interpolated motion (Fig. 7),
/// in tenths of the way, as long as the length keeps approaching the rest
/// length; stop when it no longer does. Returns the fraction moved (0 to 1).
double length_search(const Fiber& fiber, std::span<Vec3> positions_m,
                     std::span<const Vec3> previous_m, double tolerance);

/// Step 3.4 on one fiber (Gauss-Seidel along it, ends held): passes that move
/// each neighbour pair back toward the rest distance S, at most `max_sweeps`,
/// stopping once a pass finds every pair within `tolerance`. Returns the passes.
int relax_fiber(const Fiber& fiber, std::span<Vec3> positions_m, int max_sweeps, double tolerance);

/// Moves a and b (weights w_a, w_b: 1 free, 0 held) along their link so that
/// their distance becomes `rest_m`; returns the relative error |d - S|/S before.
inline double project_distance(Vec3& a, Vec3& b, double w_a, double w_b, double rest_m) {
  const Vec3 d = b - a;
  const double length = d.norm();
  const double total = w_a + w_b;
  if (length == 0.0 || total == 0.0) return length == 0.0 ? 1.0 : std::abs(length - rest_m) / rest_m;
  const Vec3 correction = ((length - rest_m) / (length * total)) * d;
  a += w_a * correction;
  b -= w_b * correction;
  return std::abs(length - rest_m) / rest_m;
}

}  // namespace flagsim::infill
