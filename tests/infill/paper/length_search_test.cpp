#include "flagsim/infill/paper/length_search.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "fiber_fixtures.hpp"
#include "flagsim/infill/paper/initial_move.hpp"
#include "tolerances.hpp"

namespace flagsim::infill {
namespace {

using test::straight;

TEST(LengthSearch, LengthSearchWalksTowardTheTargetsWhileTheLengthImproves) {
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
  EXPECT_NEAR(fiber.length_m(x), 0.8, flagsim::test::kRoundOff);
  // Already at its rest length: nothing moves.
  const std::vector<Vec3> before = x;
  EXPECT_EQ(length_search(fiber, x, previous, 0.005), 0.0);
  EXPECT_EQ(x, before);
}

}  // namespace
}  // namespace flagsim::infill
