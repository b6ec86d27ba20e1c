#include "flagsim/infill/paper/relax.hpp"

#include <algorithm>
#include <cmath>

#include "flagsim/core/stop_request.hpp"

namespace flagsim::infill {

int relax_fiber(const Fiber& fiber, std::span<Vec3> positions_m, int max_sweeps, double tolerance) {
  for (int sweep = 1; sweep <= max_sweeps && !stop_requested(); ++sweep) {
    double worst = 0.0;
    for (int i = 0; i < fiber.segments; ++i) {
      worst =
          std::max(worst, project_link(positions_m[fiber.node(i)], positions_m[fiber.node(i + 1)],
                                       i == 0, i + 1 == fiber.segments, fiber.rest_spacing_m,
                                       1.0 / fiber.rest_spacing_m));
    }
    if (worst <= tolerance) return sweep;
  }
  return max_sweeps;
}

int relax_lattice(const Lattice& lattice, std::span<const std::uint8_t> held,
                  std::span<Vec3> positions_m, int max_sweeps, double tolerance) {
  const int rows = lattice.rows, cols = lattice.cols;
  const double sx = lattice.spacing_x_m, sy = lattice.spacing_y_m;
  const double inv_sx = 1.0 / sx, inv_sy = 1.0 / sy;
  const std::size_t stride = std::size_t(cols);
  Vec3* x = positions_m.data();
  const std::uint8_t* h = held.data();
  for (int sweep = 1; sweep <= max_sweeps && !stop_requested(); ++sweep) {
    // Red-black order: row links from even columns, then odd; column links from
    // even rows, then odd. Links of one pass share no node, so each pass has
    // no chain of dependent updates and the CPU overlaps them (a plain
    // row-major sweep waits on every square root and division in turn).
    double worst = 0.0;
    for (int parity = 0; parity < 2; ++parity)
      for (int j = 0; j < rows; ++j) {
        const std::size_t row = std::size_t(j) * stride;
        for (int k = parity; k + 1 < cols; k += 2) {
          const std::size_t a = row + std::size_t(k);
          worst = std::max(worst, project_link(x[a], x[a + 1], h[a], h[a + 1], sx, inv_sx));
        }
      }
    for (int parity = 0; parity < 2; ++parity)
      for (int j = parity; j + 1 < rows; j += 2) {
        const std::size_t row = std::size_t(j) * stride;
        for (int k = 0; k < cols; ++k) {
          const std::size_t a = row + std::size_t(k);
          worst =
              std::max(worst, project_link(x[a], x[a + stride], h[a], h[a + stride], sy, inv_sy));
        }
      }
    if (worst <= tolerance) return sweep;
  }
  // Not converged: the coarse nodes ask for more (or less) length than the
  // fibers have. Red-black passes then leave the surplus on every other link;
  // one row-major pass spreads it along the fibers instead.
  for_each_link(lattice, [&](const Link& link) {
    project_link(x[link.a], x[link.b], h[link.a], h[link.b], link.rest_m, 1.0 / link.rest_m);
  });
  return max_sweeps;
}

}  // namespace flagsim::infill
