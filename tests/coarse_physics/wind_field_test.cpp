#include "flagsim/coarse_physics/wind_field.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "tolerances.hpp"

namespace flagsim::physics {
namespace {

Wind turbulent(double intensity, double length_m) {
  Wind wind;
  wind.velocity_m_s = Vec3(10.0, 0.0, 0.0);
  wind.turbulence = Turbulence{intensity, length_m};
  return wind;
}

struct Sample {
  double mean_speed = 0.0;
  Vec3 std_m_s = Vec3::Zero();
};

// Statistics over a long record at many points of a flag-sized box.
Sample sample(const WindField& field) {
  std::mt19937_64 rng(99);
  std::vector<Vec3> u;
  for (int p = 0; p < 40; ++p) {
    const Vec3 x(3.0 * double(rng() >> 11) * 0x1.0p-53, 2.0 * double(rng() >> 11) * 0x1.0p-53,
                 double(rng() >> 11) * 0x1.0p-53);
    for (int t = 0; t < 500; ++t) u.push_back(field.velocity(x, 0.1 * t));  // 50 s
  }
  Sample s;
  Vec3 mean = Vec3::Zero();
  for (const Vec3& v : u) {
    mean += v;
    s.mean_speed += v.norm();
  }
  mean /= double(u.size());
  s.mean_speed /= double(u.size());
  Vec3 var = Vec3::Zero();
  for (const Vec3& v : u) var += (v - mean).cwiseAbs2();
  s.std_m_s = (var / double(u.size())).cwiseSqrt();
  return s;
}

TEST(WindField, SteadyWindIsTheMeanEverywhere) {
  Wind wind;
  wind.velocity_m_s = Vec3(10, 0, 1);
  const WindField field(wind, 3);
  EXPECT_TRUE(field.steady());
  EXPECT_EQ(field.velocity(Vec3(1, 2, 3), 7.5), wind.velocity_m_s);
}

TEST(WindField, GustsScaleTheMeanPeriodically) {
  Wind wind;
  wind.velocity_m_s = Vec3(10, 0, 0);
  wind.gusts = Gusts{0.3, 4.0};
  const WindField field(wind, 3);
  EXPECT_FALSE(field.steady());
  EXPECT_NEAR(field.velocity(Vec3::Zero(), 1.0).x(), 13.0,
              test::kRoundOff);  // a quarter period: the crest
  EXPECT_NEAR(field.velocity(Vec3::Zero(), 3.0).x(), 7.0, test::kRoundOff);
  EXPECT_NEAR(field.velocity(Vec3(5, 1, 0), 4.0).x(), 10.0, test::kRoundOff);
}

TEST(WindField, TurbulenceHasTheAskedMeanAndIntensity) {
  // Mean speed and intensity (std of the along-wind component / mean speed)
  // within 10%; the cross-wind components within 25% (finitely many modes).
  for (double intensity : {0.1, 0.3}) {
    const WindField field(turbulent(intensity, 1.0), 7);
    const Sample s = sample(field);
    // The mean of |u| grows a little with the cross-wind fluctuations: 10% holds.
    EXPECT_NEAR(s.mean_speed, 10.0, test::kTurbulenceMeanAbs_m_s) << intensity;
    EXPECT_NEAR(s.std_m_s.x() / s.mean_speed, intensity, test::kTurbulenceAlongRelTol * intensity);
    for (int c = 1; c < 3; ++c)
      EXPECT_NEAR(s.std_m_s[c] / 10.0, intensity, test::kTurbulenceAcrossRelTol * intensity) << c;
  }
}

TEST(WindField, TurbulenceIsCorrelatedOverItsLengthScale) {
  // Close points move together, distant ones do not: the length scale means something.
  const WindField field(turbulent(0.2, 1.0), 11);
  auto correlation = [&](double separation_m) {
    double sab = 0, saa = 0, sbb = 0;
    for (int t = 0; t < 4000; ++t) {
      const Vec3 x(0.0, 0.37 * t, 0.0);
      const double a = field.velocity(x, 0.0).x() - 10.0;
      const double b = field.velocity(x + Vec3(0, 0, separation_m), 0.0).x() - 10.0;
      sab += a * b;
      saa += a * a;
      sbb += b * b;
    }
    return sab / std::sqrt(saa * sbb);
  };
  EXPECT_GT(correlation(0.05), 0.9);
  EXPECT_LT(correlation(5.0), 0.5);
}

TEST(WindField, SameSeedSameField) {
  const WindField a(turbulent(0.2, 1.0), 5), b(turbulent(0.2, 1.0), 5), c(turbulent(0.2, 1.0), 6);
  const Vec3 x(0.3, 1.2, 0.1);
  EXPECT_EQ(a.velocity(x, 2.5), b.velocity(x, 2.5));
  EXPECT_NE(a.velocity(x, 2.5), c.velocity(x, 2.5));
}

}  // namespace
}  // namespace flagsim::physics
