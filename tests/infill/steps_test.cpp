#include "flagsim/infill/steps.hpp"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace flagsim::infill {
namespace {

TEST(Steps, EndWeightIsOneAtTheEndsZeroInTheMiddle) {
  EXPECT_EQ(end_weight(0.0), 1.0);
  EXPECT_EQ(end_weight(1.0), 1.0);
  EXPECT_EQ(end_weight(0.5), 0.0);
  EXPECT_EQ(end_weight(0.25), 0.5);
}

// A straight fiber of 8 segments of 0.1 m along x.
std::vector<Vec3> straight(int segments = 8) {
  std::vector<Vec3> x;
  for (int i = 0; i <= segments; ++i) x.emplace_back(0.1 * i, 0.0, 0.0);
  return x;
}

TEST(Steps, WeightedInitialMoveKeepsTheMiddleAndFollowsTheEnds) {
  const Fiber fiber{0, 1, 8, 0.1};
  const std::vector<Vec3> previous = straight();
  std::vector<Vec3> x = previous;
  x[0] += Vec3(0, 0.2, 0);
  x[8] += Vec3(0, 0.2, 0);
  weighted_initial_move(fiber, x, previous);
  EXPECT_NEAR(x[4].y(), 0.0, 1e-15);          // the middle has weight 0
  EXPECT_NEAR(x[2].y(), 0.5 * 0.2, 1e-15);    // a quarter of the way: weight 1/2
  EXPECT_NEAR(x[1].y(), 0.75 * 0.2, 1e-15);
}

TEST(Steps, LengthSearchWalksTowardTheTargetsWhileTheLengthImproves) {
  // Ends moved up together, middle left behind: the fiber is too long; the
  // unweighted targets are the translated fiber, whose length is exact.
  const Fiber fiber{0, 1, 8, 0.1};
  const std::vector<Vec3> previous = straight();
  std::vector<Vec3> x = previous;
  x[0] += Vec3(0, 0.3, 0);
  x[8] += Vec3(0, 0.3, 0);
  weighted_initial_move(fiber, x, previous);
  ASSERT_GT(fiber.length_m(x), 0.8 * 1.01);
  EXPECT_EQ(length_search(fiber, x, previous, 0.005), 1.0);
  EXPECT_NEAR(fiber.length_m(x), 0.8, 1e-12);
  // Already at its rest length: nothing moves.
  const std::vector<Vec3> before = x;
  EXPECT_EQ(length_search(fiber, x, previous, 0.005), 0.0);
  EXPECT_EQ(x, before);
}

TEST(Steps, RelaxFiberRestoresNeighbourDistancesWithEndsHeld) {
  const Fiber fiber{0, 1, 8, 0.1};
  std::vector<Vec3> x = straight();
  for (int i = 1; i < 8; ++i) x[i] += Vec3(0.0, 0.01 * std::sin(double(i)), 0.02 * std::cos(double(i)));
  x[8] = Vec3(0.7, 0.0, 0.0);  // chord 0.7 < 0.8: the fiber must bulge, not shrink
  const int sweeps = relax_fiber(fiber, x, 1000, 1e-4);
  EXPECT_LT(sweeps, 1000);
  for (int i = 0; i < 8; ++i) EXPECT_NEAR((x[i + 1] - x[i]).norm(), 0.1, 1e-4 * 0.1 * 1.0001);
  EXPECT_EQ(x[0], Vec3(0, 0, 0));
  EXPECT_EQ(x[8], Vec3(0.7, 0, 0));
}

TEST(Steps, ProjectDistanceRespectsHeldNodes) {
  Vec3 a(0, 0, 0), b(2, 0, 0);
  EXPECT_DOUBLE_EQ(project_distance(a, b, 0.0, 1.0, 1.0), 1.0);
  EXPECT_EQ(a, Vec3(0, 0, 0));
  EXPECT_EQ(b, Vec3(1, 0, 0));
  Vec3 c(0, 0, 0), d(0, 3, 0);
  project_distance(c, d, 1.0, 1.0, 1.0);
  EXPECT_EQ(c, Vec3(0, 1, 0));
  EXPECT_EQ(d, Vec3(0, 2, 0));
}

}  // namespace
}  // namespace flagsim::infill
