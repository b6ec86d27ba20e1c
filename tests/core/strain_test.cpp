#include "flagsim/core/strain.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tolerances.hpp"

namespace flagsim {
namespace {

TEST(Strain, ZeroAtRestAndExactUnderUniformStretch) {
  const Lattice lattice = Lattice::rectangle(4, 5, 1.0, 1.0, Vec3::Zero());
  std::vector<Vec3> x = lattice.rest_positions();
  EXPECT_LT(link_strain(lattice, x).max, 1e-14);  // round-off of the rest spacing only
  for (Vec3& p : x) p.x() *= 1.02;                // 2% along rows, 0 along columns
  const StrainStats s = link_strain(lattice, x);
  EXPECT_NEAR(s.max, 0.02, test::kRoundOff);
  const double row_links = 4.0 * 4, col_links = 3.0 * 5;
  EXPECT_NEAR(s.mean, 0.02 * row_links / (row_links + col_links), test::kRoundOff);
}

TEST(Strain, CompressionCountsAsStrain) {
  const Lattice lattice = Lattice::rectangle(2, 2, 1.0, 1.0, Vec3::Zero());
  std::vector<Vec3> x = lattice.rest_positions();
  x[1].x() = 0.9;  // top row link 10% short
  EXPECT_NEAR(link_strain(lattice, x).max, 0.1, test::kRoundOff);
}

TEST(Strain, NanIsNeverHidden) {
  const Lattice lattice = Lattice::rectangle(3, 3, 1.0, 1.0, Vec3::Zero());
  std::vector<Vec3> x = lattice.rest_positions();
  x[4].y() = std::nan("");
  EXPECT_TRUE(std::isnan(link_strain(lattice, x).max));
}

TEST(Strain, EachNodeGetsItsLargestLink) {
  // 3 x 3 nodes 1 m apart; node (1, 1) moved 0.1 m along +x: its left row
  // link is 10% long, its right one 10% short, the column links above and
  // below it sqrt(1.01) - 1 long; every other link at rest.
  const Lattice lattice = Lattice::rectangle(3, 3, 2.0, 2.0, Vec3::Zero());
  std::vector<Vec3> x = lattice.rest_positions();
  x[lattice.index(1, 1)].x() += 0.1;
  std::vector<float> node(lattice.node_count(), -1.0f);
  const StrainStats s = link_strain(lattice, x, node);
  EXPECT_NEAR(s.max, 0.1, test::kRoundOff);
  const float diagonal = float(std::sqrt(1.01) - 1.0);
  const float expected[3][3] = {{0.0f, diagonal, 0.0f}, {0.1f, 0.1f, 0.1f}, {0.0f, diagonal, 0.0f}};
  for (int j = 0; j < 3; ++j)
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(node[lattice.index(j, k)], expected[j][k], float(test::kFloat32))
          << j << "," << k;
  // The same statistics with or without the field.
  EXPECT_EQ(link_strain(lattice, x).max, s.max);
  EXPECT_EQ(link_strain(lattice, x).mean, s.mean);
}

}  // namespace
}  // namespace flagsim
