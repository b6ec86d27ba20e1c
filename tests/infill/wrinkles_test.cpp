#include "flagsim/infill/wrinkles.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "flagsim/infill/paper/relax.hpp"
#include "tolerances.hpp"

namespace flagsim::infill {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(Wrinkles, TurningAngle) {
  EXPECT_NEAR(turning_angle(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)), 0.0, test::kExact);
  EXPECT_NEAR(turning_angle(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0)), kPi / 2, 1e-15);
  EXPECT_NEAR(turning_angle(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 1)), kPi / 4,
              flagsim::test::kExact);
}

TEST(Wrinkles, TurningAngleMatchesTheSecondFiniteDifference) {
  // On a smooth curve sampled at arc steps h, theta_i = |x_{i+1} - 2 x_i + x_{i-1}| / h
  // + O(h^2): eq. (1)'s angle is the curvature times h, the finite-difference
  // bending of the Terzopoulos model, at every node of a helix.
  const double radius = 0.3, pitch = 0.1;
  const double speed = std::hypot(radius, pitch);
  for (double h : {0.02, 0.01, 0.005}) {
    auto at = [&](double s) {
      const double u = s / speed;
      return Vec3(radius * std::cos(u), radius * std::sin(u), pitch * u);
    };
    for (int i = 1; i < 20; ++i) {
      const Vec3 a = at((i - 1) * h), b = at(i * h), c = at((i + 1) * h);
      const double finite_difference = (c - 2.0 * b + a).norm() / h;
      EXPECT_NEAR(turning_angle(a, b, c), finite_difference,
                  flagsim::test::kSecondDifferenceRelTol * finite_difference)
          << h;
    }
  }
}

TEST(Wrinkles, BendingConstantIsEquationTen) {
  // k = 1/2 E pi/4 (eq. (10)); times r^4.
  EXPECT_DOUBLE_EQ(bending_constant_k_r4(2.0e9, 1e-3), 0.5 * 2.0e9 * kPi / 4 * 1e-12);
}

// Nodes of a fiber on the wave y = A sin(m pi x / c) in the xz plane, spaced evenly in x.
std::vector<Vec3> wave(int segments, double chord, double amplitude, int half_waves) {
  std::vector<Vec3> x;
  for (int i = 0; i <= segments; ++i) {
    const double s = double(i) / segments;
    x.emplace_back(s * chord, 0.0, amplitude * std::sin(half_waves * kPi * s));
  }
  return x;
}

TEST(Wrinkles, BendingEnergyOfAnArcIsTheSumOfEquationOne) {
  // A circular arc: every turning angle is h/R (eq. (1) at each node, summed by eq. (11)).
  const double radius = 0.5, h = 0.01, k_r4 = 3e-4;
  const int segments = 40;
  std::vector<Vec3> x;
  for (int i = 0; i <= segments; ++i) {
    const double phi = i * h / radius;
    x.emplace_back(radius * std::sin(phi), 0.0, radius * (1 - std::cos(phi)));
  }
  const Fiber fiber{0, 1, segments, h};
  // Nodes at arc-length steps h: every turning angle is exactly h / R.
  EXPECT_NEAR(fiber_bending_energy(fiber, x, k_r4),
              (segments - 1) * k_r4 * (h / radius) * (h / radius), test::kRoundOff);
}

TEST(Wrinkles, BendingEnergyOfAWaveMatchesTheContinuum) {
  // E ~ k r^4 h * integral(curvature^2) = k r^4 h * (A^2/2) (m pi/c)^4 c for small slopes.
  const double chord = 1.0, amplitude = 0.004, k_r4 = 1e-3;
  const int segments = 400, m = 6;
  const std::vector<Vec3> x = wave(segments, chord, amplitude, m);
  const Fiber fiber{0, 1, segments, chord / segments};
  const double q = m * kPi / chord;
  const double continuum =
      k_r4 * (chord / segments) * 0.5 * amplitude * amplitude * std::pow(q, 4) * chord;
  EXPECT_NEAR(fiber_bending_energy(fiber, x, k_r4), continuum,
              test::kWaveContinuumRelTol * continuum);
}

TEST(Wrinkles, TargetEnergyIsEquationThirteenPerUnitLength) {
  const Fiber fiber{0, 1, 10, 0.1};  // rest length 1.0
  std::vector<Vec3> x = wave(10, 0.8, 0.0, 1);
  EXPECT_NEAR(fiber_target_energy(fiber, x, 2.0), 2.0 * 0.1 * 0.2 * 0.2, test::kExact);
}

// A compressed fiber (chord 0.8 of its rest length 1.0) with a small bulge,
// re-laid by 3.5 and relaxed along itself: its number of sign changes.
int half_waves_after_rewrinkle(double radius_m, int segments = 96) {
  const Fiber fiber{0, 1, segments, 1.0 / segments};
  std::vector<Vec3> x = wave(segments, 0.8, 0.01, 1);
  WrinkleParams params;
  params.k_r4 = bending_constant_k_r4(1e9, radius_m);
  params.k_prime = 1.0;
  EXPECT_TRUE(rewrinkle_fiber(fiber, x, Vec3(0, 0, 1), params));
  relax_fiber(fiber, x, 2000, 1e-4);
  EXPECT_NEAR(fiber.length_m(x), 1.0, test::kFiberLengthRelTol);  // property 1 along the fiber
  int changes = 0;
  for (int i = 2; i < segments; ++i)
    if ((x[i].z() > 0) != (x[i - 1].z() > 0)) ++changes;
  return changes + 1;
}

TEST(Wrinkles, ThickerFibersMakeFewerBroaderWaves) {
  // Property 3 on one fiber: m ~ 1/r^2, so r = 0.5, 1, 2 mm give 16, 4, 1
  // half-waves here ((c/pi) sqrt(k' dL / (2 k r^4)) = 16.3, 4.1, 1.0 for
  // c = 0.8 m, dL = 0.2 m, E_f = 1 GPa, k' = 1 J/m^3): wavelength 2c/m grows 16x.
  const int thin = half_waves_after_rewrinkle(0.5e-3);
  const int medium = half_waves_after_rewrinkle(1.0e-3);
  const int thick = half_waves_after_rewrinkle(2.0e-3);
  EXPECT_EQ(thin, 16);
  EXPECT_EQ(medium, 4);
  EXPECT_EQ(thick, 1);
}

TEST(Wrinkles, ReLayingIsIdempotentAndToleranceLeavesBalancedFibers) {
  const Fiber fiber{0, 1, 96, 1.0 / 96};
  std::vector<Vec3> x = wave(96, 0.8, 0.01, 1);
  WrinkleParams params;
  params.k_r4 = bending_constant_k_r4(1e9, 1e-3);
  ASSERT_TRUE(rewrinkle_fiber(fiber, x, Vec3(0, 0, 1), params));
  // The laid wave keeps the fiber's rest length and spaces the nodes evenly (the
  // nodes sit on the arc, whose chords are shorter by ~ (curvature h)^2 / 24).
  EXPECT_NEAR(fiber.length_m(x), 1.0, test::kRelaidLengthRelTol);
  for (int i = 0; i < 96; ++i)
    EXPECT_NEAR((x[i + 1] - x[i]).norm(), 1.0 / 96, test::kRelaidLinkRelTol / 96);
  // Default tolerance 0: laid again, the same shape comes back (persistence).
  const std::vector<Vec3> laid = x;
  ASSERT_TRUE(rewrinkle_fiber(fiber, x, Vec3(0, 0, 1), params));
  for (std::size_t i = 0; i < x.size(); ++i) EXPECT_LT((x[i] - laid[i]).norm(), 1e-9);
  // With a tolerance, a fiber near its balance E = e is left as it is.
  params.tolerance = 0.5;
  EXPECT_FALSE(rewrinkle_fiber(fiber, x, Vec3(0, 0, 1), params));
}

TEST(Wrinkles, KeepsTheSideItBulgesTo) {
  const Fiber fiber{0, 1, 96, 1.0 / 96};
  std::vector<Vec3> x = wave(96, 0.8, -0.01, 1);  // bulging toward -z
  WrinkleParams params;
  params.k_r4 = bending_constant_k_r4(1e9, 2e-3);
  ASSERT_TRUE(rewrinkle_fiber(fiber, x, Vec3(0, 0, 1), params));
  EXPECT_LT(x[48].z(), 0.0);
}

}  // namespace
}  // namespace flagsim::infill
