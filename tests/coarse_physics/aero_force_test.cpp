#include "flagsim/coarse_physics/aero_force.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "finite_difference.hpp"
#include "flagsim/coarse_physics/cloth_model.hpp"
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

TEST(AeroForce, TheLatticeForceIsEveryTriangleThirdAddedInTheTriangleLoopsOrderToTheBit) {
  // add_forces computes four triangles side by side and each node sums its
  // six thirds; a row of 10 cells exercises the lanes and the scalar tail, a
  // degenerate (collapsed) triangle and nodes moving with the air the zero
  // cases. Reference: one triangle at a time, as the cells' loop adds them.
  Scene scene = test::small_cloth(5, 11);
  const ClothModel model = make_cloth_model(scene);
  Wind wind = air(1.2, 0.7);
  wind.velocity_m_s = Vec3(9, 1, 2);
  const AeroForce aero(model, wind, 0, scene.flag.areal_density_kg_m2, 0.0);
  const Lattice& lattice = model.lattice;
  std::vector<Vec3> x = lattice.rest_positions(), v(x.size()), f(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double s = double(i);
    x[i] += 0.05 * Vec3(std::sin(1.3 * s), std::cos(0.7 * s), std::sin(2.1 * s + 0.4));
    v[i] = Vec3(std::cos(0.9 * s), 0.5 * std::sin(1.7 * s), 3.0 * std::cos(0.3 * s));
    f[i] = Vec3(0.1 * s, -0.2, 1e-3 * s);  // what the terms before it left there
  }
  x[lattice.index(2, 4)] = x[lattice.index(2, 3)];  // cell (2, 3)'s upper triangle collapses
  v[lattice.index(4, 10)] = wind.velocity_m_s;
  std::vector<Vec3> expected = f;
  for (int j = 0; j + 1 < lattice.rows; ++j)
    for (int k = 0; k + 1 < lattice.cols; ++k) {
      const std::size_t n00 = lattice.index(j, k), n01 = n00 + 1, n10 = lattice.index(j + 1, k),
                        n11 = n10 + 1;
      for (const auto& [a, b, c] :
           {std::array<std::size_t, 3>{n00, n01, n10}, std::array<std::size_t, 3>{n01, n11, n10}}) {
        const Vec3 u = (1.0 / 3.0) * ((wind.velocity_m_s + wind.velocity_m_s + wind.velocity_m_s) -
                                      (v[a] + v[b] + v[c]));
        const Vec3 third = (1.0 / 3.0) * triangle_aero_force(x[a], x[b], x[c], u, wind);
        expected[a] += third;
        expected[b] += third;
        expected[c] += third;
      }
    }
  aero.add_forces(x, v, f);
  for (std::size_t i = 0; i < f.size(); ++i) EXPECT_EQ(f[i], expected[i]) << i;
}

TEST(AeroForce, VelocityJacobianOfOneTriangleMatchesFiniteDifferences) {
  const Vec3 x0(0.1, 0.0, 0.02), x1(1.0, 0.1, -0.1), x2(0.0, 0.9, 0.2);
  const Wind wind = air(1.0, 0.5);
  for (const Vec3& u : {Vec3(10, 0, 0), Vec3(3, -1, 7), Vec3(-2, 5, -4), Vec3(0.5, 0.2, 9)}) {
    const Mat3 analytic = triangle_aero_velocity_jacobian(x0, x1, x2, u, wind);
    const double h = test::kFiniteDifferenceStep * 10.0;
    for (int c = 0; c < 3; ++c) {
      Vec3 du = Vec3::Zero();
      du[c] = h;
      const Vec3 numeric = (triangle_aero_force(x0, x1, x2, u + du, wind) -
                            triangle_aero_force(x0, x1, x2, u - du, wind)) /
                           (2.0 * h);
      EXPECT_LT((analytic.col(c) - numeric).norm(), test::kFiniteDifferenceRelTol * analytic.norm())
          << "u = " << u.transpose() << " column " << c;
    }
  }
}

TEST(AeroForce, DampingIsMinusForceVelocityJacobian) {
  Scene scene = test::small_cloth(4, 5);
  scene.wind = Wind{};
  scene.wind->velocity_m_s = Vec3(10, 0, 1);
  const ClothModel model = make_cloth_model(scene);
  AeroForce aero(model, *scene.wind, 0, scene.flag.areal_density_kg_m2, 0.0);
  const std::vector<Vec3> x = test::jiggled(model.lattice, 0.1, 8);
  std::vector<Vec3> v = test::jiggled(model.lattice, 4.0, 9);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] -= model.lattice.rest_positions()[i];
  test::expect_derivative_is_minus_force_jacobian(aero, x, v, test::Wrt::kVelocity);
}

TEST(AeroForce, ProjectedDampingIsPositiveSemidefinite) {
  // The lift's response is not symmetric; the projection keeps a damping
  // matrix the implicit stepper can solve with conjugate gradients.
  Scene scene = test::small_cloth(4, 5);
  scene.wind = Wind{};
  scene.wind->velocity_m_s = Vec3(10, 0, 3);
  const ClothModel model = make_cloth_model(scene);
  AeroForce aero(model, *scene.wind, 0, scene.flag.areal_density_kg_m2, 0.0);
  const std::vector<Vec3> x = test::jiggled(model.lattice, 0.1, 10);
  const std::vector<Vec3> v(x.size(), Vec3::Zero());
  aero.linearize(x, v, Definiteness::kProjected);
  double loaded = 0.0;
  for (unsigned seed = 0; seed < 50; ++seed) {
    const std::vector<Vec3> dv = test::jiggled(model.lattice, 1.0, 100 + seed);
    std::vector<Vec3> out(x.size(), Vec3::Zero());
    aero.add_damping_product(dv, out);
    double quadratic = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) quadratic += dv[i].dot(out[i]);
    EXPECT_GE(quadratic, 0.0);
    loaded = std::max(loaded, quadratic);
  }
  EXPECT_GT(loaded, 0.0);
}

}  // namespace
}  // namespace flagsim::physics
