#include "flagsim/core/lattice.hpp"

#include <gtest/gtest.h>

namespace flagsim {
namespace {

TEST(Lattice, RestPositionsFollowTheContract) {
  const Lattice lattice = Lattice::rectangle(3, 5, 2.0, 1.0, Vec3(0.0, 2.0, 0.0));
  EXPECT_DOUBLE_EQ(lattice.spacing_x_m, 0.5);
  EXPECT_DOUBLE_EQ(lattice.spacing_y_m, 0.5);
  // Row 0 is the top edge, +x from the pole to the fly end, z = 0.
  EXPECT_EQ(lattice.rest_position(0, 0), Vec3(0.0, 2.0, 0.0));
  EXPECT_EQ(lattice.rest_position(0, 4), Vec3(2.0, 2.0, 0.0));
  EXPECT_EQ(lattice.rest_position(2, 0), Vec3(0.0, 1.0, 0.0));
  const auto positions = lattice.rest_positions();
  ASSERT_EQ(positions.size(), 15u);
  EXPECT_EQ(positions[lattice.index(1, 3)], Vec3(1.5, 1.5, 0.0));
}

TEST(Lattice, CornersInContractOrder) {
  const Lattice lattice = Lattice::rectangle(4, 6, 1.0, 1.0, Vec3::Zero());
  const auto corners = lattice.corners();
  EXPECT_EQ(corners[0], lattice.index(0, 0));
  EXPECT_EQ(corners[1], lattice.index(0, 5));
  EXPECT_EQ(corners[2], lattice.index(3, 0));
  EXPECT_EQ(corners[3], lattice.index(3, 5));
}

}  // namespace
}  // namespace flagsim
