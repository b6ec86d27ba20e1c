#include "flagsim/infill/paper/relax.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "fiber_fixtures.hpp"
#include "tolerances.hpp"

namespace flagsim::infill {
namespace {

using test::straight;

TEST(Relax, RelaxFiberRestoresNeighbourDistancesWithEndsHeld) {
  const Fiber fiber{0, 1, 8, 0.1};
  std::vector<Vec3> x = straight();
  for (int i = 1; i < 8; ++i)
    x[i] += Vec3(0.0, 0.01 * std::sin(double(i)), 0.02 * std::cos(double(i)));
  x[8] = Vec3(0.7, 0.0, 0.0);          // chord 0.7 < 0.8: the fiber must bulge, not shrink
  constexpr double kTolerance = 1e-4;  // relative, what relax_fiber stops at
  const int sweeps = relax_fiber(fiber, x, 1000, kTolerance);
  EXPECT_LT(sweeps, 1000);
  for (int i = 0; i < 8; ++i)
    EXPECT_NEAR((x[i + 1] - x[i]).norm(), 0.1, kTolerance * 0.1 * (1.0 + flagsim::test::kRoundOff));
  EXPECT_EQ(x[0], Vec3(0, 0, 0));
  EXPECT_EQ(x[8], Vec3(0.7, 0, 0));
}

TEST(Relax, ProjectLinkRespectsHeldNodes) {
  Vec3 a(0, 0, 0), b(2, 0, 0);
  EXPECT_DOUBLE_EQ(project_link(a, b, true, false, 1.0, 1.0), 1.0);
  EXPECT_EQ(a, Vec3(0, 0, 0));
  EXPECT_EQ(b, Vec3(1, 0, 0));
  Vec3 c(0, 0, 0), d(0, 3, 0);
  project_link(c, d, false, false, 1.0, 1.0);
  EXPECT_EQ(c, Vec3(0, 1, 0));
  EXPECT_EQ(d, Vec3(0, 2, 0));
}

}  // namespace
}  // namespace flagsim::infill
