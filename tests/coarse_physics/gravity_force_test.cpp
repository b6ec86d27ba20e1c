#include "flagsim/coarse_physics/gravity_force.hpp"

#include <gtest/gtest.h>

#include "finite_difference.hpp"
#include "flagsim/coarse_physics/cloth_model.hpp"
#include "scene_fixtures.hpp"
#include "tolerances.hpp"

namespace flagsim::physics {
namespace {

TEST(GravityForce, ForceIsMinusEnergyGradient) {
  const ClothModel model = make_cloth_model(test::small_cloth(3, 4));
  const GravityForce gravity(model.mass_kg, Vec3(0.3, -9.81, 0.1));
  test::expect_force_is_minus_energy_gradient(gravity, test::jiggled(model.lattice, 0.05, 4));
}

TEST(GravityForce, TotalIsWeightOfTheCloth) {
  const ClothModel model = make_cloth_model(test::small_cloth(3, 4));
  const GravityForce gravity(model.mass_kg, Vec3(0, -9.81, 0));
  std::vector<Vec3> x = model.lattice.rest_positions(), v(x.size(), Vec3::Zero()),
                    f(x.size(), Vec3::Zero());
  gravity.add_forces(x, v, f);
  Vec3 total = Vec3::Zero();
  for (const Vec3& fi : f) total += fi;
  EXPECT_NEAR(total.y(), -9.81 * 0.2 * 1.0 * 0.8, test::kRoundOff);
}

}  // namespace
}  // namespace flagsim::physics
