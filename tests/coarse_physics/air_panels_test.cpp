#include "flagsim/coarse_physics/air_panels.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "flagsim/core/lattice.hpp"
#include "tolerances.hpp"

namespace flagsim::physics {
namespace {

using test::kRoundOff;

// The default flag: 1.5 x 1.0 m.
Lattice flag(int rows, int cols) {
  return Lattice::rectangle(rows, cols, 1.5, 1.0, Vec3::Zero());
}

// Cloth node (j, k)'s share of the rectangle's area (trapezoid weights), m^2.
double area_share(const Lattice& lattice, int j, int k) {
  const double row = (j == 0 || j == lattice.rows - 1) ? 0.5 : 1.0;
  const double col = (k == 0 || k == lattice.cols - 1) ? 0.5 : 1.0;
  return row * col * lattice.spacing_x_m * lattice.spacing_y_m;
}

std::vector<Vec3> joined(const std::vector<double> (&axes)[3]) {
  std::vector<Vec3> out(axes[0].size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = Vec3(axes[0][i], axes[1][i], axes[2][i]);
  return out;
}

TEST(AirPanels, PanelsOfAFixedSizeWhateverTheCloth) {
  // 0.125 m panels on 1.5 x 1.0 m: 12 x 8 panels, 9 x 13 nodes, at any finer lattice.
  for (const auto& [rows, cols] : {std::pair{17, 25}, std::pair{33, 49}, std::pair{129, 193}}) {
    const AirPanels panels(flag(rows, cols), 0.125);
    EXPECT_FALSE(panels.same_lattice());
    EXPECT_EQ(panels.lattice().rows, 9);
    EXPECT_EQ(panels.lattice().cols, 13);
    EXPECT_DOUBLE_EQ(panels.lattice().spacing_x_m, 0.125);
  }
  // A panel wider than its side leaves the two end nodes; a side that is not a
  // whole number of panels gets panels of at most the size asked.
  EXPECT_EQ(AirPanels(flag(33, 49), 5.0).lattice().rows, 2);
  EXPECT_EQ(AirPanels(flag(33, 49), 0.4).lattice().cols, 5);  // 1.5 / 0.4 = 3.75 -> 4 panels
}

TEST(AirPanels, ACoarserClothIsItsOwnPanelLattice) {
  // The hybrid's coarse 9 x 13 lattice has 0.125 m cells: nothing to average.
  for (const auto& [rows, cols] : {std::pair{9, 13}, std::pair{5, 7}, std::pair{9, 40}}) {
    const AirPanels panels(flag(rows, cols), 0.125);
    EXPECT_TRUE(panels.same_lattice());
    EXPECT_EQ(panels.lattice().rows, rows);
    EXPECT_EQ(panels.lattice().cols, cols);
    EXPECT_EQ(panels.weight(3, 3), 1.0);
    EXPECT_EQ(panels.weight(3, 4), 0.0);
  }
}

TEST(AirPanels, EachPanelNodeIsAWeightedAverageOfTheClothUnderItsHat) {
  const Lattice cloth = flag(33, 49);
  const AirPanels panels(cloth, 0.125);
  const std::size_t n = cloth.node_count(), np = panels.lattice().node_count();
  const std::vector<Vec3> rest = cloth.rest_positions(),
                          panel_rest = panels.lattice().rest_positions();
  for (std::size_t a = 0; a < np; ++a) {
    double sum = 0.0, farthest = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double w = panels.weight(a, i);
      EXPECT_GE(w, 0.0);
      sum += w;
      if (w > 0.0) {
        const Vec3 d = rest[i] - panel_rest[a];
        farthest = std::max({farthest, std::abs(d.x()), std::abs(d.y())});
      }
    }
    EXPECT_NEAR(sum, 1.0, kRoundOff) << a;
    // Under the hat: within a panel and a cloth cell each way.
    EXPECT_LT(farthest, 0.125 + cloth.spacing_x_m) << a;
  }
  // A constant field samples to itself; an affine one to its hat-weighted
  // mean: itself at interior panel nodes (symmetric hats), a third of a panel
  // inside at an edge (the mean of a half hat), whatever the cloth's lattice.
  std::vector<Vec3> field(n);
  for (std::size_t i = 0; i < n; ++i)
    field[i] = Vec3(2.0, -3.0, 0.5 + 0.7 * rest[i].x() - 0.3 * rest[i].y());
  std::vector<double> sampled[3];
  for (auto& s : sampled) s.assign(np, 0.0);
  panels.sample(field, sampled);
  const Lattice& p = panels.lattice();
  for (int j = 0; j < p.rows; ++j)
    for (int k = 0; k < p.cols; ++k) {
      const std::size_t a = p.index(j, k);
      EXPECT_NEAR(sampled[0][a], 2.0, kRoundOff);
      EXPECT_NEAR(sampled[1][a], -3.0, kRoundOff);
      const auto inward = [](int at, int last) { return at == 0 ? 1.0 : at == last ? -1.0 : 0.0; };
      const Vec3 r = p.rest_position(j, k) +
                     (0.125 / 3.0) * Vec3(inward(k, p.cols - 1), -inward(j, p.rows - 1), 0.0);
      EXPECT_NEAR(sampled[2][a], 0.5 + 0.7 * r.x() - 0.3 * r.y(), kRoundOff) << j << " " << k;
    }
}

TEST(AirPanels, TwoFieldsSampledInOnePassAreTheirOwnSamplesBitForBit) {
  // The wind samples positions and velocities together (one pass over the
  // weights): the same operations in the same order per field as one at a time.
  const Lattice cloth = flag(17, 25);
  const AirPanels panels(cloth, 0.25);
  ASSERT_FALSE(panels.same_lattice());
  const std::size_t n = cloth.node_count(), np = panels.lattice().node_count();
  std::vector<Vec3> a(n), b(n);
  for (std::size_t i = 0; i < n; ++i) {
    a[i] = Vec3(std::sin(0.3 * double(i)), std::cos(0.7 * double(i)), 0.01 * double(i));
    b[i] = Vec3(std::exp(-0.01 * double(i)), -0.5 * double(i % 7), std::sin(1.3 * double(i)));
  }
  std::vector<double> one_a[3], one_b[3], both_a[3], both_b[3];
  for (auto* s : {&one_a, &one_b, &both_a, &both_b})
    for (auto& axis : *s) axis.assign(np, 0.0);
  panels.sample(a, one_a);
  panels.sample(b, one_b);
  panels.sample(a, both_a, b, both_b);
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_EQ(both_a[axis], one_a[axis]) << axis;
    EXPECT_EQ(both_b[axis], one_b[axis]) << axis;
  }
}

TEST(AirPanels, AUniformPressureOnThePanelsIsTheSameForcePerAreaOnEveryClothNode) {
  // Panel node a carries p times its own area share; spread back, every cloth
  // node gets p times its share, at every lattice (the weights' integrals are
  // exact, also where 0.125 m is not a whole number of cloth cells).
  const double pressure = 61.25;  // Pa: 1/2 rho U^2 at 10 m/s
  for (const auto& [rows, cols] : {std::pair{17, 25}, std::pair{65, 97}, std::pair{29, 37}}) {
    const Lattice cloth = flag(rows, cols);
    const AirPanels panels(cloth, 0.125);
    const Lattice& p = panels.lattice();
    std::vector<double> force[3];
    for (auto& f : force) f.assign(p.node_count(), 0.0);
    for (int j = 0; j < p.rows; ++j)
      for (int k = 0; k < p.cols; ++k) force[2][p.index(j, k)] = pressure * area_share(p, j, k);
    std::vector<Vec3> on_cloth(cloth.node_count(), Vec3::Zero());
    panels.spread(force, on_cloth);
    for (int j = 0; j < cloth.rows; ++j)
      for (int k = 0; k < cloth.cols; ++k) {
        const Vec3& f = on_cloth[cloth.index(j, k)];
        EXPECT_NEAR(f.z(), pressure * area_share(cloth, j, k), kRoundOff) << j << " " << k;
        EXPECT_EQ(f.x(), 0.0);
      }
  }
}

TEST(AirPanels, SpreadingIsTheTransposeOfSampling) {
  // sum_i f_i . x_i = sum_a F_a . X_a: the spread forces do the panels' virtual work.
  const Lattice cloth = flag(29, 37);  // 0.125 m is not a whole number of its cells
  const AirPanels panels(cloth, 0.125);
  const std::size_t n = cloth.node_count(), np = panels.lattice().node_count();
  std::vector<Vec3> x(n);
  for (std::size_t i = 0; i < n; ++i)
    x[i] = Vec3(std::sin(0.3 * double(i)), std::cos(1.1 * double(i)), 0.01 * double(i % 17));
  std::vector<double> sampled[3], force[3];
  for (int axis = 0; axis < 3; ++axis) {
    sampled[axis].assign(np, 0.0);
    force[axis].resize(np);
    for (std::size_t a = 0; a < np; ++a) force[axis][a] = std::cos(0.7 * double(a) + axis);
  }
  panels.sample(x, sampled);
  std::vector<Vec3> f(n, Vec3::Zero());
  panels.spread(force, f);
  double cloth_work = 0.0, panel_work = 0.0;
  for (std::size_t i = 0; i < n; ++i) cloth_work += f[i].dot(x[i]);
  const std::vector<Vec3> X = joined(sampled), F = joined(force);
  for (std::size_t a = 0; a < np; ++a) panel_work += F[a].dot(X[a]);
  EXPECT_NEAR(cloth_work, panel_work, kRoundOff * 100.0);
}

}  // namespace
}  // namespace flagsim::physics
