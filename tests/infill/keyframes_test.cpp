#include "flagsim/infill/keyframes.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "tolerances.hpp"

namespace flagsim::infill {
namespace {

// Corners of a unit square shifted by `dx` along x, at `time_s`.
Keyframe square_at(double time_s, double dx) {
  Keyframe key;
  key.time_s = time_s;
  key.corners_m = {Vec3(dx, 1.0, 0.0), Vec3(1.0 + dx, 1.0, 0.0), Vec3(dx, 0.0, 0.0),
                   Vec3(1.0 + dx, 0.0, 0.0)};
  return key;
}

TEST(Keyframes, HeldBeforeTheFirstAndAfterTheLast) {
  const std::vector<Keyframe> keys = {square_at(1.0, 0.0), square_at(2.0, 0.5)};
  EXPECT_EQ(corners_at(keys, 0.0), keys.front().corners_m);
  EXPECT_EQ(corners_at(keys, 1.0), keys.front().corners_m);
  EXPECT_EQ(corners_at(keys, 2.0), keys.back().corners_m);
  EXPECT_EQ(corners_at(keys, 9.0), keys.back().corners_m);
}

TEST(Keyframes, LinearBetweenTheTwoAroundTheTime) {
  // Three keyframes: each time falls in its own segment, every corner moves alike.
  const std::vector<Keyframe> keys = {square_at(0.0, 0.0), square_at(1.0, 1.0),
                                      square_at(3.0, -1.0)};
  const std::array<Vec3, 4> quarter = corners_at(keys, 0.25);
  const std::array<Vec3, 4> later = corners_at(keys, 2.0);  // halfway from 1.0 to -1.0
  for (int c = 0; c < 4; ++c) {
    EXPECT_NEAR(quarter[c].x(), keys[0].corners_m[c].x() + 0.25, test::kAnalyticRelTol) << c;
    EXPECT_NEAR(later[c].x(), keys[0].corners_m[c].x(), test::kAnalyticRelTol) << c;
    EXPECT_EQ(quarter[c].y(), keys[0].corners_m[c].y()) << c;
  }
  EXPECT_EQ(corners_at(keys, 1.0), keys[1].corners_m);  // exact at a keyframe
}

TEST(Keyframes, OneKeyframeHoldsForEver) {
  const std::vector<Keyframe> keys = {square_at(0.5, 0.2)};
  EXPECT_EQ(corners_at(keys, 0.0), keys[0].corners_m);
  EXPECT_EQ(corners_at(keys, 5.0), keys[0].corners_m);
}

}  // namespace
}  // namespace flagsim::infill
