#include "flagsim/sim/divergence.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace flagsim {
namespace {

TEST(Divergence, HealthyStatePasses) {
  const std::vector<Vec3> x(4, Vec3(1, 2, 3)), v(4, Vec3(0.5, 0, 0));
  EXPECT_FALSE(divergence_reason(x, v, {0.01, 0.005}, Limits{}).has_value());
}

TEST(Divergence, NamesEachCause) {
  std::vector<Vec3> x(4, Vec3::Zero()), v(4, Vec3::Zero());
  Limits limits;
  limits.max_strain = 0.1;
  limits.max_speed_m_s = 50.0;
  x[2].z() = INFINITY;
  EXPECT_NE(divergence_reason(x, v, {}, limits)->find("position"), std::string::npos);
  x[2].z() = 0.0;
  v[1].x() = std::nan("");
  EXPECT_NE(divergence_reason(x, v, {}, limits)->find("velocity"), std::string::npos);
  v[1].x() = 60.0;
  EXPECT_NE(divergence_reason(x, v, {}, limits)->find("max_speed"), std::string::npos);
  v[1].x() = 0.0;
  EXPECT_NE(divergence_reason(x, v, {0.2, 0.1}, limits)->find("max_strain"), std::string::npos);
  EXPECT_TRUE(divergence_reason(x, v, {std::nan(""), 0.0}, limits).has_value());
}

}  // namespace
}  // namespace flagsim
