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

void CellGrid::coarse_surface(const Lattice& fine, std::span<const Vec3> coarse_m,
                              std::span<Vec3> out_m) const {
  assert(coarse_m.size() == coarse_count() && out_m.size() == fine.node_count());
  for (int j = 0; j < fine.rows; ++j) {
    for (int k = 0; k < fine.cols; ++k) {
      const auto [jc, kc, u, v] = place(j, k);
      const Vec3& a00 = coarse_m[coarse_index(jc, kc)];
      const Vec3& a01 = coarse_m[coarse_index(jc, kc + 1)];
      const Vec3& a10 = coarse_m[coarse_index(jc + 1, kc)];
      const Vec3& a11 = coarse_m[coarse_index(jc + 1, kc + 1)];
      // Half 0 (u >= v): (jc,kc)-(jc,kc+1)-(jc+1,kc+1); half 1: (jc,kc)-(jc+1,kc+1)-(jc+1,kc).
      out_m[fine.index(j, k)] = u >= v ? Vec3((1.0 - u) * a00 + (u - v) * a01 + v * a11)
                                       : Vec3((1.0 - v) * a00 + (v - u) * a10 + u * a11);
    }
  }
}

double Fiber::length_m(std::span<const Vec3> positions_m) const {
  double length = 0.0;
  for (int i = 0; i < segments; ++i)
    length += (positions_m[node(i + 1)] - positions_m[node(i)]).norm();
  return length;
}

}  // namespace flagsim::infill
