#include "flagsim/core/strain.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace flagsim {
namespace {

TEST(Strain, ZeroAtRestAndExactUnderUniformStretch) {
  const Lattice lattice = Lattice::rectangle(4, 5, 1.0, 1.0, Vec3::Zero());
  std::vector<Vec3> x = lattice.rest_positions();
  EXPECT_LT(link_strain(lattice, x).max, 1e-14);  // round-off of the rest spacing only
  for (Vec3& p : x) p.x() *= 1.02;                // 2% along rows, 0 along columns
  const StrainStats s = link_strain(lattice, x);
  EXPECT_NEAR(s.max, 0.02, 1e-12);
  const double row_links = 4.0 * 4, col_links = 3.0 * 5;
  EXPECT_NEAR(s.mean, 0.02 * row_links / (row_links + col_links), 1e-12);
}

TEST(Strain, CompressionCountsAsStrain) {
  const Lattice lattice = Lattice::rectangle(2, 2, 1.0, 1.0, Vec3::Zero());
  std::vector<Vec3> x = lattice.rest_positions();
  x[1].x() = 0.9;  // top row link 10% short
  EXPECT_NEAR(link_strain(lattice, x).max, 0.1, 1e-12);
}

TEST(Strain, NanIsNeverHidden) {
  const Lattice lattice = Lattice::rectangle(3, 3, 1.0, 1.0, Vec3::Zero());
  std::vector<Vec3> x = lattice.rest_positions();
  x[4].y() = std::nan("");
  EXPECT_TRUE(std::isnan(link_strain(lattice, x).max));
}

}  // namespace
}  // namespace flagsim
