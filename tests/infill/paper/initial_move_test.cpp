#include "flagsim/infill/paper/initial_move.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "fiber_fixtures.hpp"
#include "flagsim/core/lattice.hpp"
#include "flagsim/infill/cell_grid.hpp"
#include "tolerances.hpp"

namespace flagsim::infill {
namespace {

using test::straight;

TEST(InitialMove, EndWeightIsOneAtTheEndsZeroInTheMiddle) {
  EXPECT_EQ(end_weight(0.0), 1.0);
  EXPECT_EQ(end_weight(1.0), 1.0);
  EXPECT_EQ(end_weight(0.5), 0.0);
  EXPECT_EQ(end_weight(0.25), 0.5);
}

TEST(InitialMove, WeightedInitialMoveKeepsTheMiddleAndFollowsTheEnds) {
  const Fiber fiber{0, 1, 8, 0.1};
  const std::vector<Vec3> previous = straight();
  std::vector<Vec3> x = previous;
  x[0] += Vec3(0, 0.2, 0);
  x[8] += Vec3(0, 0.2, 0);
  weighted_initial_move(fiber, x, previous);
  EXPECT_NEAR(x[4].y(), 0.0, flagsim::test::kExact);        // the middle has weight 0
  EXPECT_NEAR(x[2].y(), 0.5 * 0.2, flagsim::test::kExact);  // a quarter of the way: weight 1/2
  EXPECT_NEAR(x[1].y(), 0.75 * 0.2, flagsim::test::kExact);
}

}  // namespace
}  // namespace flagsim::infill

namespace flagsim::infill {
namespace {

// A rigid motion: a turn of 0.7 rad about a tilted axis and a shift.
Vec3 moved(const Vec3& x) {
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(0.7, Vec3(0.3, 1.0, 0.2).normalized()).toRotationMatrix();
  return turn * x + Vec3(0.4, -0.25, 0.9);
}

// A 9 x 9 dense cell with a bumpy (wrinkled) interior.
std::vector<Vec3> bumpy_cell(const Lattice& lattice) {
  std::vector<Vec3> x = lattice.rest_positions();
  for (int j = 1; j + 1 < lattice.rows; ++j)
    for (int k = 1; k + 1 < lattice.cols; ++k)
      x[lattice.index(j, k)].z() += 0.01 * std::sin(0.9 * j) * std::cos(1.3 * k);
  return x;
}

TEST(CellFrame, RecoversTheRigidMotionOfTheEdges) {
  const Lattice lattice = Lattice::rectangle(9, 9, 0.4, 0.3, Vec3::Zero());
  const std::vector<Vec3> previous = bumpy_cell(lattice);
  std::vector<Vec3> x(previous.size());
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = moved(previous[i]);
  const CellFrame frame = cell_frame(lattice, 0, 0, 8, 8, x, previous);
  for (const Vec3& p : previous) EXPECT_LT((frame.apply(p) - moved(p)).norm(), 1e-12);
}

TEST(InitialMove, ACellThatTurnsAndTravelsKeepsItsShape) {
  // 3.2 in the cell's co-moving frame: edges moved rigidly by 3.1 carry the
  // whole interior, wrinkles and all (the plain weighted move would leave the
  // middle 0.5 m behind).
  const Lattice lattice = Lattice::rectangle(9, 9, 0.4, 0.3, Vec3::Zero());
  const CellGrid grid = CellGrid::of(lattice, 2, 2);
  const std::vector<Vec3> previous = bumpy_cell(lattice);
  std::vector<Vec3> x = previous;
  for (int j = 0; j < 9; ++j)
    for (int k = 0; k < 9; ++k)
      if (j == 0 || k == 0 || j == 8 || k == 8)
        x[lattice.index(j, k)] = moved(previous[lattice.index(j, k)]);
  initial_move_cells(lattice, grid, x, previous);
  for (std::size_t i = 0; i < x.size(); ++i) EXPECT_LT((x[i] - moved(previous[i])).norm(), 1e-12);
}

TEST(InitialMove, ACellThatStaysIsThePapersWeightedMove) {
  // Edges bulged symmetrically in z: the best rigid motion is none, and each
  // interior node moves by the paper's weighted average of its ends' motions.
  const Lattice lattice = Lattice::rectangle(9, 9, 0.4, 0.3, Vec3::Zero());
  const CellGrid grid = CellGrid::of(lattice, 2, 2);
  const std::vector<Vec3> previous = lattice.rest_positions();
  std::vector<Vec3> x = previous;
  x[lattice.index(0, 4)].z() += 0.02;  // top edge middle up
  x[lattice.index(8, 4)].z() += 0.02;  // bottom edge middle up
  x[lattice.index(4, 0)].z() -= 0.02;  // left and right middles down: no net turn
  x[lattice.index(4, 8)].z() -= 0.02;
  initial_move_cells(lattice, grid, x, previous);
  // Node (1, 4): its column's ends moved +0.02 (top) and +0.02 (bottom), weight
  // 0.75; its row's ends did not move.
  EXPECT_NEAR(x[lattice.index(1, 4)].z(), 0.5 * 0.75 * 0.02, flagsim::test::kRoundOff);
  EXPECT_NEAR(x[lattice.index(4, 4)].z(), 0.0, flagsim::test::kRoundOff);  // the middle: weight 0
}

}  // namespace
}  // namespace flagsim::infill
