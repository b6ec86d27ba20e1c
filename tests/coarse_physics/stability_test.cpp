// The explicit steppers' stability policy (stability.hpp).
#include "flagsim/coarse_physics/stability.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "flagsim/coarse_physics/force_terms.hpp"
#include "flagsim/coarse_physics/pin_motion.hpp"
#include "scene_fixtures.hpp"

namespace flagsim::physics {
namespace {

TEST(Stability, SubstepsAreEnoughForTheSafetyFactorAndAtLeastTheMinimum) {
  // 1/30 s at a limit of 1 ms: 0.5 ms substeps, 66.7 -> 67.
  EXPECT_EQ(substeps_per_frame(1.0 / 30.0, 1e-3, 1), 67);
  EXPECT_EQ(substeps_per_frame(1.0 / 30.0, 1e-3, 100), 100);
  // Exactly divisible: no extra substep from round-off.
  EXPECT_EQ(substeps_per_frame(0.01, 0.002, 1), 10);
  // Nothing bounds the step: the minimum.
  EXPECT_EQ(substeps_per_frame(0.01, std::numeric_limits<double>::infinity(), 3), 3);
}

TEST(Stability, LimitIsTwoOverTheLargestFrequencyBound) {
  // Springs only: omega_max^2 = max over free nodes of (row sum of 2k per link) / m.
  const Scene scene = test::small_cloth(4, 5);
  const ClothModel model = make_cloth_model(scene);
  const auto terms = make_force_terms(scene, model);
  std::vector<double> row_sum(model.lattice.node_count(), 0.0);
  for (const auto& term : terms) term->add_stiffness_bound(row_sum);
  double omega2 = 0.0;
  for (std::size_t i = 0; i < row_sum.size(); ++i)
    if (!model.pinned[i]) omega2 = std::max(omega2, row_sum[i] / model.mass_kg[i]);
  ASSERT_GT(omega2, 0.0);
  EXPECT_DOUBLE_EQ(explicit_stability_limit(model, terms), 2.0 / std::sqrt(omega2));
  // No terms: nothing bounds it.
  EXPECT_TRUE(std::isinf(explicit_stability_limit(model, {})));
}

}  // namespace
}  // namespace flagsim::physics
