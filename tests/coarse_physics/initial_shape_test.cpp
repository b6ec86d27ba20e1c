#include "flagsim/coarse_physics/initial_shape.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tolerances.hpp"

namespace flagsim::physics {
namespace {

TEST(InitialShape, SeededBoundedAndZeroAtThePole) {
  const Lattice lattice = Lattice::rectangle(9, 13, 1.5, 1.0, Vec3::Zero());
  const auto a = smooth_perturbation(lattice, 7, 0.01);
  const auto b = smooth_perturbation(lattice, 7, 0.01);
  const auto c = smooth_perturbation(lattice, 8, 0.01);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  double largest = 0.0;
  for (double z : a) largest = std::max(largest, std::abs(z));
  EXPECT_LE(largest, 0.01);
  EXPECT_GT(largest, 0.0);
  for (int j = 0; j < lattice.rows; ++j) EXPECT_EQ(a[lattice.index(j, 0)], 0.0);
}

TEST(InitialShape, SameShapeAtAnyResolution) {
  // Node (2j, 2k) of the fine lattice sits where node (j, k) of the coarse one does.
  const Lattice coarse = Lattice::rectangle(5, 7, 1.5, 1.0, Vec3::Zero());
  const Lattice fine = Lattice::rectangle(9, 13, 1.5, 1.0, Vec3::Zero());
  const auto zc = smooth_perturbation(coarse, 3, 0.02);
  const auto zf = smooth_perturbation(fine, 3, 0.02);
  for (int j = 0; j < coarse.rows; ++j)
    for (int k = 0; k < coarse.cols; ++k)
      EXPECT_NEAR(zc[coarse.index(j, k)], zf[fine.index(2 * j, 2 * k)], test::kExact);
}

}  // namespace
}  // namespace flagsim::physics
