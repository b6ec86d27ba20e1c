#include "flagsim/infill/cell_grid.hpp"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace flagsim::infill
