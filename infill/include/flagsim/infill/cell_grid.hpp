#pragma once
// The coarse lattice inside the dense one (contract: flag.coarse): coarse node
// (jc, kc) is dense node (jc * row_stride, kc * col_stride). The coarse nodes
// split the dense lattice into (Jc-1) x (Kc-1) cells; neighbouring cells share
// the dense nodes of their common edge.
#include <algorithm>
#include <cstddef>
#include <span>

#include "flagsim/core/lattice.hpp"
#include "flagsim/core/vec3.hpp"

namespace flagsim::infill {

struct CellGrid {
  int coarse_rows = 2;  ///< Jc
  int coarse_cols = 2;  ///< Kc
  int row_stride = 1;   ///< (J-1)/(Jc-1): dense rows per cell
  int col_stride = 1;   ///< (K-1)/(Kc-1): dense columns per cell

  /// Precondition (checked by the scene): (J-1) and (K-1) are multiples of (Jc-1), (Kc-1).
  static CellGrid of(const Lattice& fine, int coarse_rows, int coarse_cols);

  std::size_t coarse_count() const { return std::size_t(coarse_rows) * coarse_cols; }
  std::size_t coarse_index(int jc, int kc) const { return std::size_t(jc) * coarse_cols + kc; }
  /// Dense index of coarse node (jc, kc) in `fine`.
  std::size_t dense_index(const Lattice& fine, int jc, int kc) const {
    return fine.index(jc * row_stride, kc * col_stride);
  }
  /// Where dense node (j, k) lies: its cell (jc, kc), the last one for the
  /// last dense row or column, and its place in it, u along the row and v
  /// down the column, in [0, 1].
  struct Place {
    int jc = 0, kc = 0;
    double u = 0.0, v = 0.0;
  };
  Place place(int j, int k) const {
    Place at;
    at.jc = std::min(j / row_stride, coarse_rows - 2);
    at.kc = std::min(k / col_stride, coarse_cols - 2);
    at.v = double(j - at.jc * row_stride) / row_stride;
    at.u = double(k - at.kc * col_stride) / col_stride;
    return at;
  }
  /// Every dense node's point on the coarse lattice's triangles, out_m [J*K]
  /// from coarse_m [Jc*Kc]: linear on each triangle of a cell, the cell
  /// split along its diagonal (jc, kc)-(jc+1, kc+1) (as self_contact.hpp
  /// splits it), at the dense node's place in the cell. The coarse surface
  /// seen at dense resolution, without the infill's curvature or relief.
  void coarse_surface(const Lattice& fine, std::span<const Vec3> coarse_m,
                      std::span<Vec3> out_m) const;
};

}  // namespace flagsim::infill
