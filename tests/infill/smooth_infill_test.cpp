#include "flagsim/infill/smooth_infill.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "flagsim/core/strain.hpp"

namespace flagsim::infill {
namespace {

struct FlagCells {
  Lattice fine = Lattice::rectangle(65, 97, 1.5, 1.0, Vec3(0, 2, 0));
  CellGrid grid = CellGrid::of(fine, 9, 13);
  std::vector<Vec3> coarse_of(const auto& move) const {
    std::vector<Vec3> coarse(grid.coarse_count());
    for (int jc = 0; jc < grid.coarse_rows; ++jc)
      for (int kc = 0; kc < grid.coarse_cols; ++kc)
        coarse[grid.coarse_index(jc, kc)] =
            move(fine.rest_position(jc * grid.row_stride, kc * grid.col_stride));
    return coarse;
  }
};

TEST(SmoothInfill, ARigidMotionOfTheCoarseNodesMovesTheClothRigidly) {
  const FlagCells s;
  SmoothInfill infill(s.fine, s.grid);
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Vec3 shift(0.3, -0.2, 0.5);
  const auto rigid = [&](const Vec3& p) { return Vec3(turn * p + shift); };
  std::vector<Vec3> dense = s.fine.rest_positions();
  infill.fill(s.coarse_of(rigid), dense, nullptr);
  EXPECT_TRUE(infill.last_report().converged);
  EXPECT_LT(infill.last_report().coarse_offset_m, 1e-9);
  for (int j = 0; j < s.fine.rows; ++j)
    for (int k = 0; k < s.fine.cols; ++k)
      EXPECT_LT((dense[s.fine.index(j, k)] - rigid(s.fine.rest_position(j, k))).norm(), 1e-9);
}

TEST(SmoothInfill, KeepsFibersWithinTheBandOnABentCompressedCloth) {
  // Rolled onto a cylinder and pushed 3% together along the rows: the
  // coarse links are short, the dense fibers must keep their length.
  const FlagCells s;
  SmoothInfill infill(s.fine, s.grid);
  std::vector<std::uint8_t> pole(s.fine.node_count(), 0);
  for (int j = 0; j < s.fine.rows; ++j) pole[s.fine.index(j, 0)] = 1;
  infill.hold(pole);
  const auto rolled = [](const Vec3& p) {
    const double a = 0.97 * p.x() / 0.6;
    return Vec3(0.6 * std::sin(a), p.y(), 0.6 * (1 - std::cos(a)));
  };
  std::vector<Vec3> dense = s.fine.rest_positions();
  const std::vector<Vec3> coarse = s.coarse_of(rolled);
  infill.fill(coarse, dense, nullptr);
  const FillReport report = infill.last_report();
  EXPECT_TRUE(report.converged);
  EXPECT_LE(link_strain(s.fine, dense).max, kBand + kProjectionTolerance);
  // The coarse nodes are the mean surface: the counterparts stay near them.
  EXPECT_LT(report.coarse_offset_m, 0.05);
  for (int j = 0; j < s.fine.rows; ++j)  // pinned nodes where the surface put them
    EXPECT_LT((dense[s.fine.index(j, 0)] - rolled(s.fine.rest_position(j, 0))).norm(), 1e-9);
  // Same input, same bytes.
  std::vector<Vec3> again = s.fine.rest_positions();
  SmoothInfill twin(s.fine, s.grid);
  twin.hold(pole);
  twin.fill(coarse, again, nullptr);
  EXPECT_EQ(again, dense);
}

TEST(SmoothInfill, FollowsTheCoarseStretchUpToTheCap) {
  // Coarse rows stretched by 0.7%: the dense rows follow (not pulled to 0.5%);
  // stretched by 3%: capped at kStretchCap.
  for (const double stretch : {0.007, 0.03}) {
    const FlagCells s;
    SmoothInfill infill(s.fine, s.grid);
    std::vector<Vec3> dense = s.fine.rest_positions();
    infill.fill(s.coarse_of([&](const Vec3& p) { return Vec3((1 + stretch) * p.x(), p.y(), p.z()); }),
                dense, nullptr);
    ASSERT_TRUE(infill.last_report().converged) << stretch;
    double longest = 0.0;
    for (int j = 0; j < s.fine.rows; ++j)
      for (int k = 0; k + 1 < s.fine.cols; ++k)
        longest = std::max(longest, (dense[s.fine.index(j, k + 1)] - dense[s.fine.index(j, k)]).norm() /
                                        s.fine.spacing_x_m);
    EXPECT_NEAR(longest - 1.0, std::min(stretch, kStretchCap), kProjectionTolerance + 1e-9) << stretch;
  }
}

}  // namespace
}  // namespace flagsim::infill
