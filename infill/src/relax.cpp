#include "flagsim/infill/relax.hpp"

#include <algorithm>

#include "flagsim/infill/steps.hpp"

namespace flagsim::infill {

int relax_lattice(const Lattice& lattice, std::span<const std::uint8_t> held,
                  std::span<Vec3> positions_m, int max_sweeps, double tolerance) {
  const int rows = lattice.rows, cols = lattice.cols;
  const double sx = lattice.spacing_x_m, sy = lattice.spacing_y_m;
  auto link = [&](std::size_t a, std::size_t b, double rest) {
    return project_distance(positions_m[a], positions_m[b], held[a] ? 0.0 : 1.0,
                            held[b] ? 0.0 : 1.0, rest);
  };
  const std::size_t stride = std::size_t(cols);
  for (int sweep = 1; sweep <= max_sweeps; ++sweep) {
    double worst = 0.0;
    for (int j = 0; j < rows; ++j) {
      for (int k = 0; k < cols; ++k) {
        const std::size_t a = lattice.index(j, k);
        if (k + 1 < cols) worst = std::max(worst, link(a, a + 1, sx));
        if (j + 1 < rows) worst = std::max(worst, link(a, a + stride, sy));
      }
    }
    if (worst <= tolerance) return sweep;
  }
  return max_sweeps;
}

}  // namespace flagsim::infill
