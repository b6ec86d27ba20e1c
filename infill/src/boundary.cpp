#include "flagsim/infill/boundary.hpp"

#include "flagsim/infill/initial_move.hpp"
#include "flagsim/infill/length_search.hpp"

namespace flagsim::infill {

void move_edge(const Fiber& fiber, std::ptrdiff_t before_node, std::ptrdiff_t after_node,
               std::span<Vec3> positions_m, std::span<const Vec3> previous_m,
               double length_tolerance) {
  if (before_node < 0 && after_node < 0) {  // alone on its line: the paper's fiber steps
    weighted_initial_move(fiber, positions_m, previous_m);
    length_search(fiber, positions_m, previous_m, length_tolerance);
    return;
  }
  // Uniform Catmull-Rom through p_before, p0, p1, p_after; a missing neighbour
  // is the straight continuation of the edge.
  const Vec3 p0 = positions_m[fiber.node(0)], p1 = positions_m[fiber.node(fiber.segments)];
  const Vec3 before =
      before_node >= 0 ? positions_m[std::size_t(before_node)] : Vec3(2.0 * p0 - p1);
  const Vec3 after = after_node >= 0 ? positions_m[std::size_t(after_node)] : Vec3(2.0 * p1 - p0);
  const Vec3 m0 = 0.5 * (p1 - before), m1 = 0.5 * (after - p0);  // tangents per cell
  for (int i = 1; i < fiber.segments; ++i) {
    const double t = double(i) / fiber.segments, t2 = t * t, t3 = t2 * t;
    positions_m[fiber.node(i)] = (2 * t3 - 3 * t2 + 1) * p0 + (t3 - 2 * t2 + t) * m0 +
                                 (-2 * t3 + 3 * t2) * p1 + (t3 - t2) * m1;
  }
}

}  // namespace flagsim::infill
