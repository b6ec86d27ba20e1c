#include "flagsim/core/strain.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

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

TEST(Strain, FourLinksAtATimeAreEachLinksOwnStrainBitForBit) {
  // A lattice whose rows are not a multiple of four links (the lanes' tails)
  // in a random state: each node's strain is the float of the largest
  // strain_of of its links, exactly; the max is the largest, the mean within
  // round-off of the links' sum in order.
  const Lattice lattice = Lattice::rectangle(7, 11, 1.5, 1.0, Vec3::Zero());
  std::vector<Vec3> x = lattice.rest_positions();
  std::uint64_t seed = 12345;
  const auto uniform = [&] {
    seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
    return double(seed >> 11) / double(1ULL << 53) - 0.5;
  };
  for (Vec3& p : x) p += 0.02 * Vec3(uniform(), uniform(), uniform());
  std::vector<float> node(lattice.node_count(), -1.0f), expected(lattice.node_count(), 0.0f);
  double max = 0.0, sum = 0.0;
  int links = 0;
  for_each_link(lattice, [&](const Link& link) {
    const double s = strain_of(x, link);
    max = std::max(max, s);
    sum += s;
    ++links;
    expected[link.a] = std::max(expected[link.a], float(s));
    expected[link.b] = std::max(expected[link.b], float(s));
  });
  const StrainStats stats = link_strain(lattice, x, node);
  EXPECT_EQ(stats.max, max);
  EXPECT_NEAR(stats.mean, sum / links, test::kRoundOff);
  EXPECT_EQ(node, expected);
}

}  // namespace
}  // namespace flagsim
