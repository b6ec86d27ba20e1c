#pragma once
// Step 3.3: secondary move toward the fiber length (Fig. 7).
// positions_m is the whole dense lattice [J*K] in m, row-major; previous_m the
// lattice before this deformation step (the paper's motion vectors are
// positions_m - previous_m at a fiber's end nodes).
#include <span>
#include <vector>

#include "flagsim/core/vec3.hpp"
#include "flagsim/infill/fiber.hpp"

namespace flagsim::infill {

/// Step 3.3 on one fiber: if its length differs from the rest length by more
/// than `tolerance` (relative), move its interior nodes along the straight
/// lines toward the unweighted targets previous + interpolated motion (Fig. 7),
/// in tenths of the way, as long as the length keeps approaching the rest
/// length; stop when it no longer does. Returns the fraction moved (0 to 1).
double length_search(const Fiber& fiber, std::span<Vec3> positions_m,
                     std::span<const Vec3> previous_m, double tolerance);

/// Working space of length_search, kept by a caller that searches many fibers
/// (no allocation per fiber); nothing in it carries from one call to the next.
struct LengthSearchScratch {
  std::vector<Vec3> step;
  std::vector<double> aa, ab, bb;
};
/// The same, working in `scratch`.
double length_search(const Fiber& fiber, std::span<Vec3> positions_m,
                     std::span<const Vec3> previous_m, double tolerance,
                     LengthSearchScratch& scratch);

}  // namespace flagsim::infill
