#include "flagsim/infill/initial_move.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "fiber_fixtures.hpp"

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
  EXPECT_NEAR(x[4].y(), 0.0, 1e-15);        // the middle has weight 0
  EXPECT_NEAR(x[2].y(), 0.5 * 0.2, 1e-15);  // a quarter of the way: weight 1/2
  EXPECT_NEAR(x[1].y(), 0.75 * 0.2, 1e-15);
}

}  // namespace
}  // namespace flagsim::infill
