#include "flagsim/infill/cell_grid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace flagsim::infill {
namespace {

TEST(CellGrid, CoarseNodesSitOnEveryStrideThDenseNode) {
  // The default scene: 129 x 193 dense, 9 x 13 coarse, cells of 16 links.
  const Lattice fine = Lattice::rectangle(129, 193, 1.5, 1.0, Vec3(0.0, 2.0, 0.0));
  const CellGrid grid = CellGrid::of(fine, 9, 13);
  EXPECT_EQ(grid.row_stride, 16);
  EXPECT_EQ(grid.col_stride, 16);
  EXPECT_EQ(grid.coarse_count(), 117u);
  EXPECT_EQ(grid.coarse_index(8, 12), 116u);
  EXPECT_EQ(grid.dense_index(fine, 0, 0), fine.index(0, 0));
  EXPECT_EQ(grid.dense_index(fine, 8, 12), fine.index(128, 192));  // the far corners agree
  EXPECT_EQ(grid.dense_index(fine, 3, 5), fine.index(48, 80));
  // Rows and columns may differ: 49 x 161 from 4 x 11.
  const CellGrid wide = CellGrid::of(Lattice::rectangle(49, 161, 2.0, 0.6, Vec3::Zero()), 4, 11);
  EXPECT_EQ(wide.row_stride, 16);
  EXPECT_EQ(wide.col_stride, 16);
  const CellGrid tall = CellGrid::of(Lattice::rectangle(97, 49, 0.6, 1.2, Vec3::Zero()), 13, 7);
  EXPECT_EQ(tall.row_stride, 8);
  EXPECT_EQ(tall.col_stride, 8);
}

TEST(CellGrid, TheCoarseSurfaceIsLinearOnEachCoarseTriangle) {
  // 9 x 13 dense from 3 x 4 coarse (cells of 4 x 4 links), coarse nodes
  // scattered in 3D.
  const Lattice fine = Lattice::rectangle(9, 13, 1.2, 0.8, Vec3::Zero());
  const CellGrid grid = CellGrid::of(fine, 3, 4);
  std::vector<Vec3> coarse(grid.coarse_count());
  for (int jc = 0; jc < 3; ++jc)
    for (int kc = 0; kc < 4; ++kc)
      coarse[grid.coarse_index(jc, kc)] =
          Vec3(0.3 * kc, -0.4 * jc, 0.05 * std::sin(1.7 * double(grid.coarse_index(jc, kc))));
  std::vector<Vec3> dense(fine.node_count());
  grid.coarse_surface(fine, coarse, dense);
  // On the coarse nodes: the coarse nodes, exactly.
  for (int jc = 0; jc < 3; ++jc)
    for (int kc = 0; kc < 4; ++kc)
      EXPECT_EQ(dense[grid.dense_index(fine, jc, kc)], coarse[grid.coarse_index(jc, kc)]);
  // Cell (1, 2): its half 0 (above the diagonal (jc,kc)-(jc+1,kc+1)) is the
  // plane of its corners (1,2), (1,3), (2,3); half 1 of (1,2), (2,3), (2,2).
  const Vec3 a00 = coarse[grid.coarse_index(1, 2)], a01 = coarse[grid.coarse_index(1, 3)];
  const Vec3 a10 = coarse[grid.coarse_index(2, 2)], a11 = coarse[grid.coarse_index(2, 3)];
  // Dense (5, 11): v = 1/4, u = 3/4 (half 0); (7, 9): v = 3/4, u = 1/4 (half 1).
  EXPECT_LT((dense[fine.index(5, 11)] - (0.25 * a00 + 0.5 * a01 + 0.25 * a11)).norm(), 1e-14);
  EXPECT_LT((dense[fine.index(7, 9)] - (0.25 * a00 + 0.5 * a10 + 0.25 * a11)).norm(), 1e-14);
  // On the diagonal both halves agree: the midpoint.
  EXPECT_LT((dense[fine.index(6, 10)] - 0.5 * (a00 + a11)).norm(), 1e-14);
}

}  // namespace
}  // namespace flagsim::infill
