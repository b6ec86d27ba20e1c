#include "flagsim/coarse_physics/cloth_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <vector>

#include "flagsim/coarse_physics/stretch_springs.hpp"
#include "scene_fixtures.hpp"
#include "tolerances.hpp"

namespace flagsim::physics {
namespace {

TEST(ClothModel, MassIsDensityTimesAreaAtAnyResolution) {
  for (auto [rows, cols] : {std::pair{2, 2}, {5, 7}, {33, 49}}) {
    const ClothModel model = make_cloth_model(test::small_cloth(rows, cols));
    const double total = std::accumulate(model.mass_kg.begin(), model.mass_kg.end(), 0.0);
    EXPECT_NEAR(total, 0.2 * 1.0 * 0.8, test::kRoundOff) << rows << "x" << cols;
  }
}

TEST(ClothModel, UniaxialStretchStoresTheContinuumEnergy) {
  // No shear springs: stretching by eps along x stores 1/2 Y eps^2 w h exactly.
  for (auto [rows, cols] : {std::pair{3, 4}, {9, 25}}) {
    Scene scene = test::small_cloth(rows, cols);
    scene.flag.shear_modulus_n_m = 0.0;
    const ClothModel model = make_cloth_model(scene);
    std::vector<Vec3> x = model.lattice.rest_positions();
    const double eps = 0.01;
    for (Vec3& p : x) p.x() *= 1.0 + eps;
    const double expected = 0.5 * scene.flag.stretch_modulus_n_m * eps * eps * 1.0 * 0.8;
    EXPECT_NEAR(StretchSprings(model).energy(x), expected,
                test::kRoundOff * expected + test::kExact);
  }
}

TEST(ClothModel, SimpleShearStoresTheShearModulusEnergy) {
  // u_x = gamma * y: only the diagonals change length to first order.
  Scene scene = test::small_cloth(9, 13);
  const ClothModel model = make_cloth_model(scene);
  std::vector<Vec3> x = model.lattice.rest_positions();
  const double gamma = 1e-3;
  for (Vec3& p : x) p.x() += gamma * p.y();
  const double expected = 0.5 * scene.flag.shear_modulus_n_m * gamma * gamma * 1.0 * 0.8;
  EXPECT_NEAR(StretchSprings(model).energy(x), expected, test::kContinuumRelTol * expected);
}

TEST(ClothModel, PinSets) {
  const Lattice lattice = Lattice::rectangle(3, 4, 1, 1, Vec3::Zero());
  auto count = [&](PinSet pin) {
    const auto pinned = pinned_nodes(lattice, pin);
    return std::accumulate(pinned.begin(), pinned.end(), 0);
  };
  EXPECT_EQ(count(PinSet::kLeft), 3);
  EXPECT_EQ(count(PinSet::kRight), 3);
  EXPECT_EQ(count(PinSet::kTop), 4);
  EXPECT_EQ(count(PinSet::kCorners), 4);
  EXPECT_EQ(count(PinSet::kNone), 0);
  EXPECT_EQ(pinned_nodes(lattice, PinSet::kLeft)[lattice.index(2, 0)], 1);
  EXPECT_EQ(pinned_nodes(lattice, PinSet::kRight)[lattice.index(1, 3)], 1);
}

TEST(ClothModel, KineticEnergyAndTheDampingEveryBackendApplies) {
  const std::vector<double> mass = {0.5, 2.0};
  const std::vector<Vec3> v = {Vec3(2.0, 0.0, 0.0), Vec3(0.0, 1.0, -1.0)};
  EXPECT_EQ(kinetic_energy_j(mass, v), 0.5 * 0.5 * 4.0 + 0.5 * 2.0 * 2.0);
  ClothModel model;
  model.material.damping_per_s = 0.1;
  // v <- v / (1 + c dt): after 1 s in 1000 steps, exp(-c t) to first order in dt: off by
  // c^2 dt t / 2 = 5e-6 (relative).
  double v_left = 1.0;
  for (int i = 0; i < 1000; ++i) v_left *= model.velocity_damping(1e-3);
  EXPECT_NEAR(v_left, std::exp(-0.1), 6e-6 * std::exp(-0.1));
  EXPECT_DOUBLE_EQ(model.velocity_damping(0.02) * model.damping_mass_scale(0.02), 1.0);
  model.material.damping_per_s = 0.0;
  EXPECT_EQ(model.velocity_damping(0.02), 1.0);
}

}  // namespace
}  // namespace flagsim::physics
