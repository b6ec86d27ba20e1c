#include "flagsim/core/lattice.hpp"

#include <cassert>

namespace flagsim {

Lattice Lattice::rectangle(int rows, int cols, double width_m, double height_m,
                           const Vec3& origin_m) {
  assert(rows >= 2 && cols >= 2);
  Lattice lattice;
  lattice.rows = rows;
  lattice.cols = cols;
  lattice.spacing_x_m = width_m / (cols - 1);
  lattice.spacing_y_m = height_m / (rows - 1);
  lattice.origin_m = origin_m;
  return lattice;
}

std::vector<Vec3> Lattice::rest_positions() const {
  std::vector<Vec3> positions(node_count());
  for (int j = 0; j < rows; ++j)
    for (int k = 0; k < cols; ++k) positions[index(j, k)] = rest_position(j, k);
  return positions;
}

std::array<std::size_t, 4> Lattice::corners() const {
  return {index(0, 0), index(0, cols - 1), index(rows - 1, 0), index(rows - 1, cols - 1)};
}

}  // namespace flagsim
