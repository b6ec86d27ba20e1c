#include "flagsim/coarse_physics/pin_motion.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tolerances.hpp"

namespace flagsim::physics {
namespace {

TEST(PinMotion, WithoutAPoleThePinsStayAtRest) {
  const PinMotion still(std::nullopt);
  for (double t : {0.0, 0.3, 7.0}) {
    EXPECT_EQ(still.offset_m(t), Vec3::Zero()) << t;
    EXPECT_EQ(still.velocity_m_s(t), Vec3::Zero()) << t;
  }
  EXPECT_EQ(still.max_speed_m_s(), 0.0);
}

TEST(PinMotion, ShakesAlongItsAxisAndItsVelocityIsTheOffsetsDerivative) {
  PoleMotion pole;
  pole.axis_unit = Vec3(0.0, 0.6, 0.8);
  pole.amplitude_m = 0.05;
  pole.frequency_hz = 2.0;
  const PinMotion shaken(pole);
  EXPECT_EQ(shaken.offset_m(0.0), Vec3::Zero());
  // A quarter period: the full amplitude along the axis.
  EXPECT_TRUE(shaken.offset_m(0.125).isApprox(0.05 * pole.axis_unit, test::kAnalyticRelTol));
  const double h = test::kFiniteDifferenceStep, top = shaken.max_speed_m_s();
  for (double t : {0.0, 0.07, 0.31, 1.9}) {
    const Vec3 central = (shaken.offset_m(t + h) - shaken.offset_m(t - h)) / (2.0 * h);
    EXPECT_LE((shaken.velocity_m_s(t) - central).norm(), test::kFiniteDifferenceRelTol * top) << t;
    EXPECT_LE(shaken.velocity_m_s(t).cross(pole.axis_unit).norm(), test::kAnalyticRelTol * top)
        << t;
  }
  // 2 pi f A, reached as the pole passes its rest position.
  EXPECT_NEAR(shaken.max_speed_m_s(), 2.0 * std::numbers::pi * 2.0 * 0.05, test::kAnalyticRelTol);
  EXPECT_NEAR(shaken.velocity_m_s(0.0).norm(), shaken.max_speed_m_s(), test::kAnalyticRelTol);
}

}  // namespace
}  // namespace flagsim::physics
