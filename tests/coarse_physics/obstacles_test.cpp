// The solids ([pole] radius, [ground]; issue 31): a node inside one goes back
// to its surface, its speed into it is removed, and Coulomb friction takes at
// most mu times that removed speed off its sliding.
#include "flagsim/coarse_physics/obstacles.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace flagsim::physics {
namespace {

Scene scene_with(std::optional<SolidPole> pole, std::optional<Ground> ground) {
  Scene scene;
  scene.flag.origin_m = Vec3(0.0, 2.0, 0.0);
  scene.solid_pole = pole;
  scene.ground = ground;
  return scene;
}

TEST(Obstacles, NoneWithoutSolids) {
  EXPECT_FALSE(Obstacles::of(scene_with(std::nullopt, std::nullopt)).has_value());
}

TEST(Obstacles, ANodeInsideThePoleGoesToItsSurfaceAndLosesItsSpeedIntoIt) {
  // Axis at x = -0.1, z = 0; the pinned edge (x = 0) on its surface.
  auto solids = Obstacles::of(scene_with(SolidPole{0.1, 0.5}, std::nullopt));
  ASSERT_TRUE(solids.has_value());
  std::vector<Vec3> x = {Vec3(0.0, 1.5, 0.0),           // 0.1 from the axis: on the surface
                         Vec3(-0.1 + 0.03, 1.2, 0.04),  // 0.05 from it: inside
                         Vec3(0.3, 1.0, 0.0)};          // far outside
  // Node 1 moves into the pole at 2 m/s along -n and slides along y at 0.5 m/s:
  // friction 0.5 x 2 = 1 m/s takes all of the sliding.
  const Vec3 n(0.6, 0.0, 0.8);
  std::vector<Vec3> v = {Vec3(-1.0, 0.0, 0.0), -2.0 * n + Vec3(0.0, 0.5, 0.0), Vec3(-5, 0, 0)};
  const std::vector<Vec3> before_x = x, before_v = v;
  EXPECT_EQ(solids->project(0.0, x, v, {}), 1);
  EXPECT_EQ(x[0], before_x[0]);
  EXPECT_EQ(v[0], before_v[0]);
  EXPECT_NEAR((x[1] - Vec3(-0.1, 1.2, 0.0)).norm(), 0.1, 1e-15);
  EXPECT_NEAR((x[1] - Vec3(-0.1 + 0.06, 1.2, 0.08)).norm(), 0.0, 1e-15);  // along its radius
  EXPECT_NEAR(v[1].norm(), 0.0, 1e-15);
  EXPECT_EQ(x[2], before_x[2]);
  EXPECT_EQ(v[2], before_v[2]);
  EXPECT_NEAR(solids->depth_m(0.0, before_x[1]), 0.05, 1e-15);
  EXPECT_EQ(solids->depth_m(0.0, x[1]), 0.0);

  // Sliding faster than friction stops: 3 m/s along the surface keeps 3 - 0.5 x 2.
  x = {Vec3(-0.1 + 0.03, 1.2, 0.04)};
  v = {-2.0 * n + Vec3(0.0, 3.0, 0.0)};
  solids->project(0.0, x, v, {});
  EXPECT_NEAR((v[0] - Vec3(0.0, 2.0, 0.0)).norm(), 0.0, 1e-14);
  // Leaving already: the velocity stays, the position is corrected.
  v = {2.0 * n};
  x = {Vec3(-0.1 + 0.03, 1.2, 0.04)};
  solids->project(0.0, x, v, {});
  EXPECT_EQ(v[0], 2.0 * n);
}

TEST(Obstacles, TheGroundStopsAFallAndFrictionSlowsTheSlide) {
  auto solids = Obstacles::of(scene_with(std::nullopt, Ground{0.5, 0.25}));
  std::vector<Vec3> x = {Vec3(1.0, 0.4, 0.0), Vec3(1.0, 0.6, 0.0)};
  std::vector<Vec3> v = {Vec3(2.0, -4.0, 0.0), Vec3(0.0, -4.0, 0.0)};
  EXPECT_EQ(solids->project(0.0, x, v, {}), 1);
  EXPECT_EQ(x[0], Vec3(1.0, 0.5, 0.0));
  EXPECT_NEAR((v[0] - Vec3(1.0, 0.0, 0.0)).norm(), 0.0, 1e-15);  // 2 - 0.25 x 4
  EXPECT_EQ(x[1], Vec3(1.0, 0.6, 0.0));
}

TEST(Obstacles, SettleRaisesAWrinkleUnderTheGroundAboveItWithItsLengths) {
  // A cloth of 3 x 9 nodes lying on the ground (y = 0.5) in 0.1 m links, each
  // row with a dip under it: node 4 of every row 50 mm down, its two links at
  // 30 degrees, so every link is 0.1 m long as laid (what the infill gives).
  auto solids = Obstacles::of(scene_with(std::nullopt, Ground{0.5, 0.25}));
  const Lattice lattice = Lattice::rectangle(3, 9, 0.8, 0.2, Vec3::Zero());
  const double c = 0.1 * std::cos(M_PI / 6.0), s = 0.1 * std::sin(M_PI / 6.0);
  std::vector<Vec3> x(lattice.node_count());
  for (int j = 0; j < 3; ++j)
    for (int k = 0; k < 9; ++k) {
      const double along = k <= 3 ? 0.1 * k : 0.3 + (k == 4 ? c : 2.0 * c + 0.1 * (k - 5));
      x[lattice.index(j, k)] = Vec3(along, k == 4 ? 0.5 - s : 0.5, 0.1 * j);
    }
  const std::vector<Vec3> laid = x;
  EXPECT_EQ(solids->settle(0.0, lattice, x, {}, {}, 10, 2), 3);
  // Mirrored: 50 mm above the ground, every other node where it was, and the
  // fibers as long as laid (laid flat on the ground instead, the two links
  // were 87 mm and the sweeps stretched the row along the ground).
  for (int j = 0; j < 3; ++j)
    for (int k = 0; k < 9; ++k) {
      const Vec3 expected = k == 4 ? Vec3(laid[lattice.index(j, k)].x(), 0.5 + s, 0.1 * j)
                                   : laid[lattice.index(j, k)];
      EXPECT_NEAR((x[lattice.index(j, k)] - expected).norm(), 0.0, 1e-12) << j << ", " << k;
      if (k < 8) {
        EXPECT_NEAR((x[lattice.index(j, k + 1)] - x[lattice.index(j, k)]).norm(), 0.1, 1e-12);
      }
    }
}

TEST(Obstacles, PinnedNodesAreLeftWhereTheyAre) {
  auto solids = Obstacles::of(scene_with(SolidPole{0.1, 0.3}, Ground{1.0, 0.5}));
  std::vector<Vec3> x = {Vec3(-0.1, 0.5, 0.0), Vec3(-0.1, 0.5, 0.0)};
  std::vector<Vec3> v(2, Vec3::Zero());
  const std::vector<std::uint8_t> pinned = {1, 0};
  EXPECT_EQ(solids->project(0.0, x, v, pinned), 1);  // node 1: out of the pole, onto the ground
  EXPECT_EQ(x[0], Vec3(-0.1, 0.5, 0.0));
  EXPECT_NEAR(solids->depth_m(0.0, x[1]), 0.0, 1e-15);
  EXPECT_EQ(x[1], Vec3(0.0, 1.0, 0.0));  // on the axis: pushed towards the fly end
}

TEST(Obstacles, AShakenPoleMovesWithItsPins) {
  Scene scene = scene_with(SolidPole{0.1, 0.0}, std::nullopt);
  scene.pole = PoleMotion{Vec3::UnitZ(), 0.2, 1.0};  // z = 0.2 sin(2 pi t)
  auto solids = Obstacles::of(scene);
  const Vec3 at_quarter(-0.1, 1.0, 0.2 - 0.05);  // 5 cm from the axis at t = 1/4 s
  EXPECT_NEAR(solids->depth_m(0.25, at_quarter), 0.05, 1e-12);
  EXPECT_EQ(solids->depth_m(0.0, at_quarter), 0.0);
  // Friction 0 and the pole moving at its top speed at t = 0 (2 pi 0.2 m/s along z):
  // a node resting inside it is carried out at the pole's normal speed.
  std::vector<Vec3> x = {Vec3(-0.1, 1.0, 0.05)}, v = {Vec3::Zero()};
  solids->project(0.0, x, v, {});
  EXPECT_NEAR(x[0].z(), 0.1, 1e-15);
  EXPECT_NEAR(v[0].z(), 2.0 * M_PI * 0.2, 1e-12);
}

// A link whose ends are both outside the pole but whose segment cuts it is
// pushed out, and project() says something moved (Bullet writes its nodes back
// only then: it used to drop these corrections, and its coarse links cut the
// pole by up to 14 mm of 40).
TEST(Obstacles, ALinkThroughThePoleIsPushedOutAndCounted) {
  Scene scene = scene_with(SolidPole{0.1, 0.0}, std::nullopt);
  scene.flag.fine_rows = 2;
  scene.flag.fine_cols = 2;
  const Lattice lattice = Lattice::rectangle(2, 2, 1.0, 1.0, scene.flag.origin_m);
  auto solids = Obstacles::of(scene, lattice);
  ASSERT_TRUE(solids.has_value());
  // Axis at x = -0.1, z = 0. Nodes 0 and 1 (a row link) on either side of the
  // pole, 0.15 m from the axis, their segment 0.05 m from it; nodes 2 and 3 far.
  std::vector<Vec3> x = {Vec3(-0.1, 1.0, 0.15), Vec3(-0.1, 1.0, -0.15), Vec3(2.0, 0.0, 2.0),
                         Vec3(3.0, 0.0, 2.0)};
  const std::vector<Vec3> before = x;
  EXPECT_GE(solids->project(0.0, x, {}, {}), 1);
  // The segment now clears the disc (to rounding), both ends moved the same way.
  const double dx = x[1].x() - x[0].x(), dz = x[1].z() - x[0].z();
  const double ax = x[0].x() + 0.1, az = x[0].z();
  const double t = std::clamp(-(ax * dx + az * dz) / (dx * dx + dz * dz), 0.0, 1.0);
  EXPECT_GE(std::hypot(ax + t * dx, az + t * dz), 0.1 - 1e-12);
  EXPECT_GT(x[0].x(), before[0].x());
  EXPECT_GT(x[1].x(), before[1].x());
  EXPECT_EQ(x[2], before[2]);
  EXPECT_EQ(x[3], before[3]);
  // Nothing inside and no link through: nothing moved, 0.
  std::vector<Vec3> clear = {Vec3(0.5, 1.0, 0.15), Vec3(0.5, 1.0, -0.15), Vec3(2.0, 0.0, 2.0),
                             Vec3(3.0, 0.0, 2.0)};
  EXPECT_EQ(solids->project(0.0, clear, {}, {}), 0);
}

}  // namespace
}  // namespace flagsim::physics
