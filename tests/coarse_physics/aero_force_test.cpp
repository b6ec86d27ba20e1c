#include "flagsim/coarse_physics/aero_force.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "scene_fixtures.hpp"
#include "tolerances.hpp"

namespace flagsim::physics {
namespace {

using test::kAnalyticRelTol;

Wind air(double drag, double lift) {
  Wind wind;
  wind.drag = drag;
  wind.lift = lift;
  wind.air_density_kg_m3 = 1.225;
  return wind;
}

// A right triangle of area 0.5 m^2 in the z = 0 plane, normal +z.
const Vec3 kA(0, 0, 0), kB(1, 0, 0), kC(0, 1, 0);

TEST(AeroForce, FlatPlateFacingTheFlowGetsTheTextbookDrag) {
  const double speed = 10.0, area = 0.5;
  const Vec3 f = triangle_aero_force(kA, kB, kC, Vec3(0, 0, speed), air(1.0, 0.5));
  const double expected = 0.5 * 1.225 * 1.0 * area * speed * speed;  // 1/2 rho C_d A U^2
  EXPECT_NEAR(f.z(), expected, kAnalyticRelTol * expected);
  EXPECT_NEAR(f.x(), 0.0, kAnalyticRelTol * expected);
  EXPECT_NEAR(f.y(), 0.0, kAnalyticRelTol * expected);
}

TEST(AeroForce, BothFacesCatchTheWind) {
  const Vec3 u(3.0, -1.0, 7.0);
  const Vec3 front = triangle_aero_force(kA, kB, kC, u, air(1.0, 0.5));
  const Vec3 back = triangle_aero_force(kA, kC, kB, u, air(1.0, 0.5));  // flipped normal
  EXPECT_LT((front - back).norm(), kAnalyticRelTol * front.norm());
  EXPECT_GT(front.dot(u), 0.0);  // pushed downstream
}

TEST(AeroForce, FlowAlongThePlateGivesNoForce) {
  EXPECT_EQ(triangle_aero_force(kA, kB, kC, Vec3(10, 3, 0), air(1.0, 0.5)).norm(), 0.0);
  EXPECT_EQ(triangle_aero_force(kA, kB, kC, Vec3::Zero(), air(1.0, 0.5)).norm(), 0.0);
}

TEST(AeroForce, LiftAtFortyFiveDegrees) {
  // u at 45 degrees to the normal: lift = 1/2 rho C_l A U^2 cos sin = 1/4 rho C_l A U^2,
  // perpendicular to u, in the plane of u and n.
  const double speed = 8.0, area = 0.5;
  const Vec3 u = speed * Vec3(1, 0, 1).normalized();
  const Vec3 lift = triangle_aero_force(kA, kB, kC, u, air(0.0, 0.7));
  const double expected = 0.25 * 1.225 * 0.7 * area * speed * speed;
  EXPECT_NEAR(lift.norm(), expected, kAnalyticRelTol * expected);
  EXPECT_NEAR(lift.dot(u), 0.0, kAnalyticRelTol * expected * speed);
  EXPECT_NEAR(lift.y(), 0.0, kAnalyticRelTol * expected);
  // Drag alone at 45 degrees: the normal component of the flow, (U cos 45)^2.
  const Vec3 drag = triangle_aero_force(kA, kB, kC, u, air(1.0, 0.0));
  EXPECT_NEAR(drag.z(), 0.5 * 1.225 * area * speed * speed * 0.5, kAnalyticRelTol * expected);
}

TEST(AeroForce, WholeFlatFlagFacingWindAndMovingWithIt) {
  Scene scene = test::small_cloth(5, 7);
  const ClothModel model = make_cloth_model(scene);
  Wind wind = air(1.0, 0.5);
  wind.velocity_m_s = Vec3(0, 0, 10);
  const AeroForce aero(model, wind, 0, scene.flag.areal_density_kg_m2, 0.0);
  const std::vector<Vec3> x = model.lattice.rest_positions();
  std::vector<Vec3> v(x.size(), Vec3::Zero()), f(x.size(), Vec3::Zero());
  aero.add_forces(x, v, f);
  Vec3 total = Vec3::Zero();
  for (const Vec3& fi : f) total += fi;
  const double expected = 0.5 * 1.225 * 1.0 * (1.0 * 0.8) * 100.0;
  EXPECT_NEAR(total.z(), expected, kAnalyticRelTol * expected * 10);
  // Cloth moving with the air feels nothing.
  std::fill(v.begin(), v.end(), wind.velocity_m_s);
  std::fill(f.begin(), f.end(), Vec3::Zero());
  aero.add_forces(x, v, f);
  for (const Vec3& fi : f) EXPECT_EQ(fi.norm(), 0.0);
}

}  // namespace
}  // namespace flagsim::physics
