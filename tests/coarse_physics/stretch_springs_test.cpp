#include "flagsim/coarse_physics/stretch_springs.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "finite_difference.hpp"
#include "scene_fixtures.hpp"

namespace flagsim::physics {
namespace {

TEST(StretchSprings, ForceIsMinusEnergyGradient) {
  const ClothModel model = make_cloth_model(test::small_cloth(4, 5));
  const StretchSprings springs(model);
  test::expect_force_is_minus_energy_gradient(springs, test::jiggled(model.lattice, 0.05, 1));
}

TEST(StretchSprings, NoForceAtRestAndBalancedTotal) {
  const ClothModel model = make_cloth_model(test::small_cloth(4, 5));
  const StretchSprings springs(model);
  std::vector<Vec3> x = model.lattice.rest_positions(), v(x.size(), Vec3::Zero()),
                    f(x.size(), Vec3::Zero());
  springs.add_forces(x, v, f);
  for (const Vec3& fi : f) EXPECT_LT(fi.norm(), 1e-9);
  x = test::jiggled(model.lattice, 0.05, 2);
  std::fill(f.begin(), f.end(), Vec3::Zero());  // add_forces adds: start from zero again
  springs.add_forces(x, v, f);
  double largest = 0.0;
  for (const Vec3& fi : f) largest = std::max(largest, fi.norm());
  EXPECT_GT(largest, 1.0);  // jiggled by 5 cm the springs pull: the total below is a real sum
  Vec3 total = Vec3::Zero();
  for (const Vec3& fi : f) total += fi;
  EXPECT_LT(total.norm(), 1e-9);  // internal forces: Newton's third law
}

}  // namespace
}  // namespace flagsim::physics
