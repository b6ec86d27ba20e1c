#include "flagsim/coarse_physics/bending_springs.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "finite_difference.hpp"
#include "scene_fixtures.hpp"
#include "tolerances.hpp"

namespace flagsim::physics {
namespace {

TEST(BendingSprings, ForceIsMinusEnergyGradient) {
  const ClothModel model = make_cloth_model(test::small_cloth(5, 6));
  const BendingSprings bending(model, 0.01);
  test::expect_force_is_minus_energy_gradient(bending, test::jiggled(model.lattice, 0.05, 3));
}

TEST(BendingSprings, EnergyMatchesContinuumAtAnyResolution) {
  // Roll the cloth into a cylinder of curvature kappa about the y axis (rows
  // bend, columns stay straight): continuum energy 1/2 D kappa^2 w h.
  const double rigidity = 0.02, kappa = 1.0;
  for (int cols : {21, 81}) {
    const ClothModel model = make_cloth_model(test::small_cloth(9, cols));
    const BendingSprings bending(model, rigidity);
    std::vector<Vec3> x = model.lattice.rest_positions();
    for (Vec3& p : x) {
      const double s = p.x();
      p.x() = std::sin(kappa * s) / kappa;
      p.z() = (1.0 - std::cos(kappa * s)) / kappa;
    }
    const double continuum = 0.5 * rigidity * kappa * kappa * 1.0 * 0.8;
    // The discrete sum leaves out half a segment at each end: (K-2)/(K-1) of the length.
    const double covered = double(cols - 2) / (cols - 1);
    EXPECT_NEAR(bending.energy(x), continuum * covered, test::kContinuumRelTol * continuum) << cols;
  }
}

TEST(BendingSprings, HessianIsMinusForceJacobian) {
  const ClothModel model = make_cloth_model(test::small_cloth(4, 5));
  BendingSprings bending(model, 0.02);
  const std::vector<Vec3> x = test::jiggled(model.lattice, 0.05, 5);
  test::expect_derivative_is_minus_force_jacobian(bending, x, std::vector<Vec3>(x.size()),
                                                  test::Wrt::kPosition);
}

}  // namespace
}  // namespace flagsim::physics
