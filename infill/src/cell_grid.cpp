#include "flagsim/infill/cell_grid.hpp"

#include <cassert>

#include "flagsim/infill/fiber.hpp"

namespace flagsim::infill {

CellGrid CellGrid::of(const Lattice& fine, int coarse_rows, int coarse_cols) {
  assert(coarse_rows >= 2 && coarse_cols >= 2);
  assert((fine.rows - 1) % (coarse_rows - 1) == 0 && (fine.cols - 1) % (coarse_cols - 1) == 0);
  return {coarse_rows, coarse_cols, (fine.rows - 1) / (coarse_rows - 1),
          (fine.cols - 1) / (coarse_cols - 1)};
}

double Fiber::length_m(std::span<const Vec3> positions_m) const {
  double length = 0.0;
  for (int i = 0; i < segments; ++i)
    length += (positions_m[node(i + 1)] - positions_m[node(i)]).norm();
  return length;
}

}  // namespace flagsim::infill
