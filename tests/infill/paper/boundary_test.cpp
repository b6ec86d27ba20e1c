// Step 3.1's edges: arcs on which every link keeps its rest length.
#include "flagsim/infill/paper/boundary.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "fiber_fixtures.hpp"
#include "tolerances.hpp"

namespace flagsim::infill {
namespace {

using test::straight;

double worst_link_error(const Fiber& fiber, const std::vector<Vec3>& x) {
  double worst = 0.0;
  for (int i = 0; i < fiber.segments; ++i)
    worst = std::max(
        worst, std::abs((x[fiber.node(i + 1)] - x[fiber.node(i)]).norm() - fiber.rest_spacing_m) /
                   fiber.rest_spacing_m);
  return worst;
}

TEST(LayArc, EveryLinkHasItsRestLengthAndTheArcBulgesToTheGivenSide) {
  const Fiber fiber{0, 1, 8, 0.1};
  for (double slack : {0.001, 0.01, 0.1, 0.5}) {
    std::vector<Vec3> x = straight();
    x[8] = Vec3(0.8 * (1.0 - slack), 0.0, 0.0);  // ends closer than the fiber is long
    EXPECT_TRUE(lay_arc(fiber, x, Vec3(0.3, 0.0, -1.0)));
    EXPECT_LT(worst_link_error(fiber, x), 1e-9) << slack;
    EXPECT_EQ(x[8], Vec3(0.8 * (1.0 - slack), 0.0, 0.0));  // ends untouched
    for (int i = 1; i < 8; ++i) {
      EXPECT_LT(x[i].z(), 0.0) << slack;  // toward the bow's part across the chord
      EXPECT_NEAR(x[i].y(), 0.0, flagsim::test::kRoundOff);
    }
    EXPECT_NEAR(x[4].x(), 0.5 * x[8].x(), flagsim::test::kRoundOff);  // symmetric
  }
}

TEST(LayArc, ATautFiberGoesEvenlyOnTheChord) {
  const Fiber fiber{0, 1, 8, 0.1};
  std::vector<Vec3> x = straight();
  x[8] = Vec3(0.0, 0.0, 0.84);  // 5% farther apart than the fiber is long
  EXPECT_FALSE(lay_arc(fiber, x, Vec3::UnitX()));
  for (int i = 0; i <= 8; ++i) EXPECT_LT((x[i] - Vec3(0, 0, 0.105 * i)).norm(), 1e-12);
}

TEST(MoveEdge, AnEdgeKeepsTheSideItBulgedToBefore) {
  // The coarse line bends toward +z, but the edge bulged toward -z in the
  // previous step: it stays there rather than jumping across its chord.
  const Fiber fiber{1, 1, 8, 0.1};  // nodes 1..9; 0 and 10 are the coarse neighbours
  std::vector<Vec3> previous(11);
  for (int i = 0; i <= 10; ++i) previous[i] = Vec3(0.1 * (i - 1), 0.0, 0.0);
  previous[5].z() = -0.01;
  std::vector<Vec3> x = previous;
  x[9] = Vec3(0.79, 0.0, 0.0);
  x[0] = Vec3(-0.1, 0.0, 0.05);
  x[10] = Vec3(0.89, 0.0, 0.05);
  move_edge(fiber, 0, 10, Vec3::UnitZ(), x, previous, 1e-4);
  EXPECT_LT(x[5].z(), -0.01);
  EXPECT_LT(worst_link_error(fiber, x), 1e-9);
}

}  // namespace
}  // namespace flagsim::infill
