#include "flagsim/infill/paper/initial_move.hpp"

#include <Eigen/SVD>
#include <cmath>

namespace flagsim::infill {

double end_weight(double s) {
  return std::abs(1.0 - 2.0 * s);
}

Vec3 interpolated_motion(const Fiber& fiber, double s, std::span<const Vec3> positions_m,
                         std::span<const Vec3> previous_m) {
  const std::size_t a = fiber.node(0), b = fiber.node(fiber.segments);
  return (1.0 - s) * (positions_m[a] - previous_m[a]) + s * (positions_m[b] - previous_m[b]);
}

void weighted_initial_move(const Fiber& fiber, std::span<Vec3> positions_m,
                           std::span<const Vec3> previous_m) {
  for (int i = 1; i < fiber.segments; ++i) {
    const double s = double(i) / fiber.segments;
    const std::size_t n = fiber.node(i);
    positions_m[n] =
        previous_m[n] + end_weight(s) * interpolated_motion(fiber, s, positions_m, previous_m);
  }
}

CellFrame cell_frame(const Lattice& lattice, int j0, int k0, int rows, int cols,
                     std::span<const Vec3> positions_m, std::span<const Vec3> previous_m) {
  // The cell's boundary nodes, before and after 3.1.
  Vec3 old_centre = Vec3::Zero(), new_centre = Vec3::Zero();
  int count = 0;
  auto for_boundary = [&](auto&& visit) {
    for (int k = k0; k <= k0 + cols; ++k) {
      visit(lattice.index(j0, k));
      visit(lattice.index(j0 + rows, k));
    }
    for (int j = j0 + 1; j < j0 + rows; ++j) {
      visit(lattice.index(j, k0));
      visit(lattice.index(j, k0 + cols));
    }
  };
  for_boundary([&](std::size_t n) {
    old_centre += previous_m[n];
    new_centre += positions_m[n];
    ++count;
  });
  old_centre /= count;
  new_centre /= count;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for_boundary([&](std::size_t n) {
    covariance += (positions_m[n] - new_centre) * (previous_m[n] - old_centre).transpose();
  });
  // Kabsch: the rotation closest to the covariance (no reflection).
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(covariance,
                                              Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d flip = Eigen::Matrix3d::Identity();
  if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0) flip(2, 2) = -1.0;
  CellFrame frame;
  frame.rotation = svd.matrixU() * flip * svd.matrixV().transpose();
  frame.old_centre = old_centre;
  frame.new_centre = new_centre;
  return frame;
}

void initial_move_cells(const Lattice& lattice, const CellGrid& grid, std::span<Vec3> positions_m,
                        std::span<const Vec3> previous_m) {
  // Node (j, k) inside the cell with corners (j0, k0), (j0+rs, k0+cs): its row
  // ends are (j, k0) and (j, k0+cs), its column ends (j0, k) and (j0+rs, k).
  const int rs = grid.row_stride, cs = grid.col_stride;
  for (int jc = 0; jc + 1 < grid.coarse_rows; ++jc) {
    for (int kc = 0; kc + 1 < grid.coarse_cols; ++kc) {
      const int j0 = jc * rs, k0 = kc * cs;
      const CellFrame frame = cell_frame(lattice, j0, k0, rs, cs, positions_m, previous_m);
      // Motions in the cell's co-moving frame: what is left of an edge node's
      // motion once the cell's rigid motion is taken out.
      auto motion = [&](std::size_t n) -> Vec3 {
        return positions_m[n] - frame.apply(previous_m[n]);
      };
      for (int j = j0 + 1; j < j0 + rs; ++j) {
        const double s_col = double(j - j0) / rs;
        const Vec3 left = motion(lattice.index(j, k0)), right = motion(lattice.index(j, k0 + cs));
        for (int k = k0 + 1; k < k0 + cs; ++k) {
          const double s_row = double(k - k0) / cs;
          const Vec3 along_row = (1.0 - s_row) * left + s_row * right;
          const Vec3 along_col = (1.0 - s_col) * motion(lattice.index(j0, k)) +
                                 s_col * motion(lattice.index(j0 + rs, k));
          const std::size_t n = lattice.index(j, k);
          // 3.2: each interpolated motion times its weight, the two averaged.
          positions_m[n] = frame.apply(previous_m[n]) +
                           0.5 * (end_weight(s_row) * along_row + end_weight(s_col) * along_col);
        }
      }
    }
  }
}

}  // namespace flagsim::infill
