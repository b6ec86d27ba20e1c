#include "flagsim/infill/smooth/fiber_projection.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "flagsim/core/strain.hpp"
#include "tolerances.hpp"

namespace flagsim::infill {
namespace {

// A 17 x 25 lattice on a wavy, stretched and sheared surface, the pole edge
// (x = 0) at rest: links off their rest length by up to ~6%.
std::vector<Vec3> distorted(const Lattice& lattice) {
  std::vector<Vec3> x = lattice.rest_positions();
  for (Vec3& p : x)
    p = Vec3(1.04 * p.x(), p.y() * (1.0 + 0.03 * p.x()) + 0.02 * p.x(),
             0.05 * std::sin(6.0 * p.x()) * p.y());
  return x;
}

// A projection of `lattice` with its pole edge (column 0) held and every
// link's band `band` wide around its rest length.
FiberProjection pole_held(const Lattice& lattice, double band) {
  FiberProjection projection(lattice);
  std::vector<std::uint8_t> held(lattice.node_count(), 0);
  for (int j = 0; j < lattice.rows; ++j) held[lattice.index(j, 0)] = 1;
  projection.hold(held);
  projection.set_uniform_band(band);
  return projection;
}

TEST(FiberProjection, BringsEveryLinkIntoItsBandWithPinsHeld) {
  const Lattice lattice = Lattice::rectangle(17, 25, 1.5, 1.0, Vec3(0, 1, 0));
  FiberProjection projection = pole_held(lattice, 0.005);
  std::vector<Vec3> x = distorted(lattice);
  const std::vector<Vec3> start = x;
  EXPECT_GT(link_strain(lattice, x).max, 0.05);
  const ProjectionReport report = projection.project(x, 1e-4, 50, 3);
  EXPECT_TRUE(report.converged);
  EXPECT_LE(report.rounds, 10);
  EXPECT_LE(link_strain(lattice, x).max, 0.005 + 1e-4);
  for (int j = 0; j < 17; ++j) EXPECT_EQ(x[lattice.index(j, 0)], start[lattice.index(j, 0)]);
}

TEST(FiberProjection, ChecksOnlyWhatMovedAndStillFindsEveryLinkOutside) {
  // From the third round on, a fiber is checked again only where the other
  // family's solved fibers cross it. One bump on a long lattice, one
  // Gauss-Newton step a round: the late rounds solve a few fibers around it,
  // so most checks are partial, and a link they missed would end outside its
  // band with the projection saying it converged (checking no partial link
  // at all fails here). Measured here by every link.
  const Lattice lattice = Lattice::rectangle(33, 97, 3.0, 1.0, Vec3::Zero());
  FiberProjection projection = pole_held(lattice, 0.001);
  std::vector<Vec3> x = lattice.rest_positions();
  for (int dj = -3; dj <= 3; ++dj)
    for (int dk = -3; dk <= 3; ++dk)
      x[lattice.index(16 + dj, 50 + dk)].z() += 0.006 * (4 - std::abs(dj)) * (4 - std::abs(dk));
  const double tolerance = 2e-4;
  const ProjectionReport report = projection.project(x, tolerance, 100, 1);
  ASSERT_TRUE(report.converged);
  EXPECT_GE(report.rounds, 4);  // the partial checks ran
  double worst = 0.0;
  for_each_link(lattice, [&](const Link& link) {
    const double relative = (x[link.b] - x[link.a]).norm() / link.rest_m;
    worst = std::max(worst, std::abs(relative - 1.0) - 0.001);
  });
  EXPECT_LE(worst, tolerance + test::kRoundOff);
}

TEST(FiberProjection, LeavesALatticeWithinItsBandsAlone) {
  const Lattice lattice = Lattice::rectangle(9, 13, 1.5, 1.0, Vec3::Zero());
  FiberProjection projection(lattice);
  projection.set_uniform_band(0.01);
  std::vector<Vec3> x = lattice.rest_positions();
  for (Vec3& p : x) p *= 1.005;  // 0.5% stretched: inside a 1% band
  const std::vector<Vec3> start = x;
  const ProjectionReport report = projection.project(x, 1e-4, 10, 3);
  EXPECT_TRUE(report.converged);
  EXPECT_EQ(report.rounds, 1);
  EXPECT_EQ(report.fiber_steps, 0);
  EXPECT_EQ(x, start);
}

TEST(FiberProjection, ConvergesQuadraticallyOnOneFiber) {
  // Gauss-Newton on a chain: an error e falls to about e^2 per step.
  const Lattice lattice = Lattice::rectangle(2, 41, 1.0, 0.1, Vec3::Zero());
  FiberProjection projection(lattice);
  std::vector<std::uint8_t> held(lattice.node_count(), 1);
  for (int k = 1; k < 41; ++k) held[lattice.index(0, k)] = 0;  // row 0 free but its first node
  projection.hold(held);
  std::vector<Vec3> x = lattice.rest_positions();
  for (int k = 0; k < 41; ++k) {
    const double u = k / 40.0;
    x[lattice.index(0, k)] = Vec3(1.02 * u, 0.0, 0.03 * std::sin(5 * u));
  }
  auto row_error = [&] {
    double worst = 0.0;
    for (int k = 0; k < 40; ++k)
      worst =
          std::max(worst, std::abs((x[lattice.index(0, k + 1)] - x[lattice.index(0, k)]).norm() /
                                       lattice.spacing_x_m -
                                   1.0));
    return worst;
  };
  const double before = row_error();
  ProjectionReport report = projection.project(x, 0.0, 1, 1);  // one step
  const double after_one = row_error();
  report = projection.project(x, 0.0, 1, 1);
  const double after_two = row_error();
  EXPECT_GT(before, 0.02);
  EXPECT_LT(after_one, 10 * before * before);
  EXPECT_LT(after_two, 10 * after_one * after_one + 1e-12);
}

TEST(FiberProjection, ABandWiderThanOneLetsTheLinkStretch) {
  const Lattice lattice = Lattice::rectangle(5, 5, 1.0, 1.0, Vec3::Zero());
  FiberProjection projection(lattice);
  projection.set_uniform_band(0.0);
  for (LinkBand& band : projection.bands().rows()) band = {1.0, 1.03};
  std::vector<Vec3> x = lattice.rest_positions();
  for (Vec3& p : x) p.x() *= 1.05;  // rows 5% long, columns at rest
  ASSERT_TRUE(projection.project(x, 1e-6, 20, 3).converged);
  for (int j = 0; j < 5; ++j)
    for (int k = 0; k < 4; ++k)
      EXPECT_NEAR((x[lattice.index(j, k + 1)] - x[lattice.index(j, k)]).norm() / 0.25, 1.03,
                  test::kProjectedEdge);
}

// An unconverged projection reports how far the movable links are outside
// their bands; links held at both ends (the pole, given a band its rest length
// is 25% outside) cannot move and are not counted (they once set the residual
// of every unconverged frame to their own).
TEST(FiberProjection, TheResidualCountsOnlyLinksItCanMove) {
  const Lattice lattice = Lattice::rectangle(5, 9, 1.0, 0.5, Vec3::Zero());
  FiberProjection projection = pole_held(lattice, 0.005);
  for (int j = 0; j + 1 < 5; ++j) projection.bands().col(j, 0) = {1.25, 1.3};
  std::vector<Vec3> x = lattice.rest_positions();
  x[lattice.index(2, 8)].x() += 0.2 * lattice.spacing_x_m;  // one free link, 20% long
  const ProjectionReport capped = projection.project(x, 1e-6, 0, 1);
  EXPECT_FALSE(capped.converged);
  EXPECT_NEAR(capped.worst_excess, 0.2 - 0.005, test::kAccumulatedRoundOff);
  const ProjectionReport done = projection.project(x, 1e-6, 50, 4);
  EXPECT_TRUE(done.converged);
  EXPECT_EQ(done.worst_excess, 0.0);
}

}  // namespace
}  // namespace flagsim::infill
