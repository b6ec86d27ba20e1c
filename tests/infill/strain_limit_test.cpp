#include "flagsim/infill/strain_limit.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "flagsim/core/strain.hpp"

namespace flagsim::infill {
namespace {

TEST(LimitStretch, NoLinkStaysLongerAndFixedNodesStay) {
  const Lattice lattice = Lattice::rectangle(5, 7, 0.6, 0.4, Vec3::Zero());
  std::vector<Vec3> x = lattice.rest_positions();
  std::vector<std::uint8_t> fixed(x.size(), 0);
  for (int j = 0; j < 5; ++j) fixed[lattice.index(j, 0)] = 1;  // the pole
  for (std::size_t i = 0; i < x.size(); ++i)                   // stretched 4% along x, bent in z
    x[i] = Vec3(1.04 * x[i].x(), x[i].y(), 0.05 * x[i].x() * x[i].x());
  const std::vector<Vec3> start = x;
  // Cyclic projection onto the (convex) set of short-enough links: it
  // converges, slowly where the set is thin (next to the pole, whose links
  // cannot shorten); 200 passes leave every link within 1e-4 of the bound.
  limit_stretch(lattice, fixed, x, -0.01, 200);
  for (int j = 0; j < 5; ++j)
    for (int k = 0; k < 7; ++k) {
      const std::size_t a = lattice.index(j, k);
      if (k + 1 < 7) {
        EXPECT_LE((x[a + 1] - x[a]).norm(), 0.99 * lattice.spacing_x_m * (1 + 1e-4));
      }
      if (j + 1 < 5 && !(fixed[a] && fixed[a + 7])) {  // two pins keep their distance
        EXPECT_LE((x[a + 7] - x[a]).norm(), 0.99 * lattice.spacing_y_m * (1 + 1e-4));
      }
      if (fixed[a]) {
        EXPECT_EQ(x[a], start[a]);
      }
    }
}

TEST(LimitStretch, ALatticeWithSlackIsLeftAlone) {
  const Lattice lattice = Lattice::rectangle(4, 4, 0.3, 0.3, Vec3::Zero());
  std::vector<Vec3> x = lattice.rest_positions();
  for (Vec3& p : x) p *= 0.98;
  const std::vector<Vec3> start = x;
  const std::vector<std::uint8_t> fixed(x.size(), 0);
  EXPECT_EQ(limit_stretch(lattice, fixed, x, -0.01, 50), 1);
  EXPECT_EQ(x, start);
}

}  // namespace
}  // namespace flagsim::infill
