#include "flagsim/infill/smooth/smooth_infill.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "flagsim/core/strain.hpp"
#include "tolerances.hpp"

namespace flagsim::infill {
namespace {

struct FlagCells {
  Lattice fine = Lattice::rectangle(65, 97, 1.5, 1.0, Vec3(0, 2, 0));
  CellGrid grid = CellGrid::of(fine, 9, 13);
  std::vector<Vec3> coarse_of(const auto& move) const {
    std::vector<Vec3> coarse(grid.coarse_count());
    for (int jc = 0; jc < grid.coarse_rows; ++jc)
      for (int kc = 0; kc < grid.coarse_cols; ++kc)
        coarse[grid.coarse_index(jc, kc)] =
            move(fine.rest_position(jc * grid.row_stride, kc * grid.col_stride));
    return coarse;
  }
  /// The pole: every node of column 0.
  std::vector<std::uint8_t> pole() const {
    std::vector<std::uint8_t> held(fine.node_count(), 0);
    for (int j = 0; j < fine.rows; ++j) held[fine.index(j, 0)] = 1;
    return held;
  }
};

// The rest plane rolled onto a cylinder of `radius` about the y axis, its
// rows pushed together to `squash` of their length.
auto rolled_onto(double radius, double squash) {
  return [=](const Vec3& p) {
    const double a = squash * p.x() / radius;
    return Vec3(radius * std::sin(a), p.y(), radius * (1 - std::cos(a)));
  };
}

TEST(SmoothInfill, ARigidMotionOfTheCoarseNodesMovesTheClothRigidly) {
  const FlagCells s;
  SmoothInfill infill(s.fine, s.grid);
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Vec3 shift(0.3, -0.2, 0.5);
  const auto rigid = [&](const Vec3& p) { return Vec3(turn * p + shift); };
  std::vector<Vec3> dense = s.fine.rest_positions();
  infill.fill(s.coarse_of(rigid), dense, nullptr);
  EXPECT_TRUE(infill.last_report().converged);
  EXPECT_LT(infill.last_report().coarse_offset_m, 1e-9);
  for (int j = 0; j < s.fine.rows; ++j)
    for (int k = 0; k < s.fine.cols; ++k)
      EXPECT_LT((dense[s.fine.index(j, k)] - rigid(s.fine.rest_position(j, k))).norm(), 1e-9);
}

TEST(SmoothInfill, KeepsFibersWithinTheBandOnABentCompressedCloth) {
  // Rolled onto a cylinder and pushed 3% together along the rows: the
  // coarse links are short, the dense fibers must keep their length.
  const FlagCells s;
  SmoothInfill infill(s.fine, s.grid);
  const std::vector<std::uint8_t> pole = s.pole();
  infill.hold(pole);
  const auto rolled = rolled_onto(0.6, 0.97);
  std::vector<Vec3> dense = s.fine.rest_positions();
  const std::vector<Vec3> coarse = s.coarse_of(rolled);
  infill.fill(coarse, dense, nullptr);
  const FillReport report = infill.last_report();
  EXPECT_TRUE(report.converged);
  EXPECT_LE(link_strain(s.fine, dense).max, kBand + kProjectionTolerance);
  // The coarse nodes are the mean surface: the counterparts stay near them.
  EXPECT_LT(report.coarse_offset_m, 0.05);
  for (int j = 0; j < s.fine.rows; ++j)  // pinned nodes where the surface put them
    EXPECT_LT((dense[s.fine.index(j, 0)] - rolled(s.fine.rest_position(j, 0))).norm(), 1e-9);
  // Same input, same bytes.
  std::vector<Vec3> again = s.fine.rest_positions();
  SmoothInfill twin(s.fine, s.grid);
  twin.hold(pole);
  twin.fill(coarse, again, nullptr);
  EXPECT_EQ(again, dense);
}

TEST(SmoothInfill, AMildlyCompressedClothKeepsItsFiberLengthsAsRelief) {
  // Rolled onto a cylinder and pushed 0.3% together along the rows, less
  // than the 0.5% a fiber could once shorten by: the fibers still keep their
  // rest length (a compressed membrane wrinkles, it does not shorten), and the
  // length the surface lacks goes into relief off the cylinder.
  const FlagCells s;
  SmoothInfill infill(s.fine, s.grid);
  infill.hold(s.pole());
  constexpr double kRadius = 0.6;
  std::vector<Vec3> dense = s.fine.rest_positions();
  infill.fill(s.coarse_of(rolled_onto(kRadius, 0.997)), dense, nullptr);
  ASSERT_TRUE(infill.last_report().converged);
  // Issue 34's 0.1% (kBand + kProjectionTolerance); the fibers sat at -0.3% before.
  EXPECT_LE(link_strain(s.fine, dense).max, 0.001);
  double relief = 0.0;  // largest distance from the cylinder
  for (const Vec3& p : dense)
    relief = std::max(relief, std::abs(std::hypot(p.x(), kRadius - p.z()) - kRadius));
  // A sine of wavelength w is longer than w by (pi A / w)^2: 0.3% of excess
  // in waves of about 8 cm is A = w sqrt(0.003) / pi = 1.4 mm (measured 1.46).
  EXPECT_GT(relief, 1e-3);
}

TEST(SmoothInfill, FollowsTheCoarseStretchUpToTheCap) {
  // Coarse rows stretched by 0.7%: every dense row link at 0.7% (not anywhere
  // in a band around its rest length); stretched by 3%: at kStretchCap. The
  // columns, unstretched, keep their rest length.
  for (const double stretch : {0.007, 0.03}) {
    const FlagCells s;
    SmoothInfill infill(s.fine, s.grid);
    std::vector<Vec3> dense = s.fine.rest_positions();
    infill.fill(
        s.coarse_of([&](const Vec3& p) { return Vec3((1 + stretch) * p.x(), p.y(), p.z()); }),
        dense, nullptr);
    ASSERT_TRUE(infill.last_report().converged) << stretch;
    const double target = std::min(stretch, kStretchCap);
    // Converged: within the band around the target, less the projection's tolerance.
    const double within = (1.0 + target) * kBand + kProjectionTolerance + 1e-9;
    double worst_row = 0.0, worst_col = 0.0;
    for (int j = 0; j < s.fine.rows; ++j)
      for (int k = 0; k < s.fine.cols; ++k) {
        const Vec3& p = dense[s.fine.index(j, k)];
        if (k + 1 < s.fine.cols)
          worst_row = std::max(
              worst_row, std::abs((dense[s.fine.index(j, k + 1)] - p).norm() / s.fine.spacing_x_m -
                                  1.0 - target));
        if (j + 1 < s.fine.rows)
          worst_col = std::max(
              worst_col,
              std::abs((dense[s.fine.index(j + 1, k)] - p).norm() / s.fine.spacing_y_m - 1.0));
      }
    EXPECT_LE(worst_row, within) << stretch;
    EXPECT_LE(worst_col, kBand + kProjectionTolerance + 1e-9) << stretch;
  }
}

// A cloth whose corners are pushed 3% together along its rows (the paper's
// Figs. 9-10 case): the mean surface is the shrunk plane, every row has 3%
// of slack, and 3.5 lays waves across the whole row.
constexpr double kChord = 1.455;  // the rows' 1.5 m pushed 3% together

struct Pushed {
  Lattice fine = Lattice::rectangle(17, 193, 1.5, 0.5, Vec3::Zero());
  CellGrid grid = CellGrid::of(fine, 2, 2);
  std::vector<Vec3> corners = {Vec3(0, 0, 0), Vec3(kChord, 0, 0), Vec3(0, -0.5, 0),
                               Vec3(kChord, -0.5, 0)};
  std::vector<std::uint8_t> held() const {
    std::vector<std::uint8_t> h(fine.node_count(), 0);
    for (std::size_t c : fine.corners()) h[c] = 1;
    return h;
  }
  // Half-waves along the middle row: sign changes of its offset from the plane, plus one.
  int half_waves(const std::vector<Vec3>& x) const {
    int changes = 0;
    double last = 0.0;
    for (int k = 1; k + 1 < fine.cols; ++k) {
      const double z = x[fine.index(8, k)].z();
      if (std::abs(z) < 1e-6) continue;
      if (last != 0.0 && (z > 0) != (last > 0)) ++changes;
      last = z;
    }
    return changes + 1;
  }
};

TEST(SmoothInfillWrinkles, WavesSpanTheWholeFiberAndGrowAsTheFiberRadiusSquared) {
  const Pushed p;
  std::vector<double> radius, wavelength;
  for (double r : {0.5e-3, 1e-3, 2e-3}) {
    WrinkleParams params;
    params.k_r4 = bending_constant_k_r4(1e9, r);
    SmoothInfill infill(p.fine, p.grid, params);
    infill.hold(p.held());
    std::vector<Vec3> x = p.fine.rest_positions();
    infill.fill(p.corners, x, nullptr);
    ASSERT_TRUE(infill.last_report().converged) << r;
    EXPECT_LE(link_strain(p.fine, x).max, kBand + kProjectionTolerance) << r;
    const int m = p.half_waves(x);
    // The count the balance picks for the row's slack on its surface.
    EXPECT_EQ(m, half_wave_count(kChord, 1.5 - kChord, 192, params)) << r;
    radius.push_back(std::log(r));
    wavelength.push_back(std::log(2.0 * kChord / m));
  }
  // Least-squares slope of log wavelength against log r: 2 +- 0.5 (m is rounded).
  const double mr = (radius[0] + radius[1] + radius[2]) / 3,
               mw = (wavelength[0] + wavelength[1] + wavelength[2]) / 3;
  double sxy = 0, sxx = 0;
  for (int i = 0; i < 3; ++i) {
    sxy += (radius[i] - mr) * (wavelength[i] - mw);
    sxx += (radius[i] - mr) * (radius[i] - mr);
  }
  EXPECT_NEAR(sxy / sxx, 2.0, test::kWavelengthSlopeTol);
}

TEST(SmoothInfillWrinkles, AWrinkleStaysWhereItIsWhileTheCornersAreHeld) {
  const Pushed p;
  WrinkleParams params;
  params.k_r4 = bending_constant_k_r4(1e9, 1e-3);
  SmoothInfill infill(p.fine, p.grid, params);
  infill.hold(p.held());
  std::vector<Vec3> x = p.fine.rest_positions();
  infill.fill(p.corners, x, nullptr);
  const std::vector<Vec3> formed = x;
  for (int frame = 0; frame < 20; ++frame) infill.fill(p.corners, x, nullptr);
  double moved = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) moved = std::max(moved, (x[i] - formed[i]).norm());
  EXPECT_LT(moved, 1e-3);  // 1 mm over 20 held frames
}

}  // namespace
}  // namespace flagsim::infill

namespace flagsim::infill {
namespace {

// A coarse cloth folded back on itself: a hairpin at coarse column 3 of 7
// (dense column 24), the folded-back layer 30 mm above the other. Returns the
// infill's dense lattice.
std::vector<Vec3> infill_of_a_hairpin(double fold_limit_rad, std::vector<Vec3>* flat) {
  const Lattice fine = Lattice::rectangle(33, 49, 1.2, 0.8, Vec3::Zero());
  const CellGrid grid = CellGrid::of(fine, 5, 7);
  std::vector<Vec3> coarse(grid.coarse_count());
  for (int jc = 0; jc < 5; ++jc)
    for (int kc = 0; kc < 7; ++kc) {
      const double u = (kc - 3) * 0.2, y = -0.2 * jc;
      coarse[grid.coarse_index(jc, kc)] = u <= 0.0 ? Vec3(u, y, 0.0) : Vec3(-u, y, 0.03);
    }
  SmoothInfill infill(fine, grid, std::nullopt, std::nullopt, fold_limit_rad);
  std::vector<Vec3> dense(fine.node_count(), Vec3::Zero());
  infill.fill(coarse, dense, nullptr);
  if (flat) {
    flat->resize(fine.node_count());
    grid.coarse_surface(fine, coarse, *flat);
  }
  return dense;
}

// Largest distance of `dense` from the coarse triangles over dense columns
// 16-32 (the cells on either side of the fold), m.
double off_the_triangles_by_the_fold(const std::vector<Vec3>& dense,
                                     const std::vector<Vec3>& flat) {
  const Lattice fine = Lattice::rectangle(33, 49, 1.2, 0.8, Vec3::Zero());
  double off = 0.0;
  for (int j = 0; j < fine.rows; ++j)
    for (int k = 16; k <= 32; ++k)
      off = std::max(off, (dense[fine.index(j, k)] - flat[fine.index(j, k)]).norm());
  return off;
}

TEST(SmoothInfill, WithAFoldLimitTheSurfaceStaysCloserToAHairpinOfTheCoarseCloth) {
  // The spline rounds the fold with an overshoot: its lattice lies 8.4 mm off
  // the coarse triangles there (9.2-10.3 mm with the degree-7 natural spline
  // before 2026-12-08), over a quarter of the 30 mm between the layers (on
  // pole_wrap, pressed against the pole, 57-69 mm: through the other layer).
  // With the hybrid [contact]'s limit: 3.9 mm (4.8-5.6 before).
  std::vector<Vec3> flat;
  const std::vector<Vec3> spline = infill_of_a_hairpin(0.0, &flat);
  const std::vector<Vec3> limited = infill_of_a_hairpin(kContactFoldLimitRad, nullptr);
  EXPECT_GT(off_the_triangles_by_the_fold(spline, flat), 0.0075);
  EXPECT_LT(off_the_triangles_by_the_fold(limited, flat), 0.0048);
}

TEST(SmoothInfill, AFoldLimitLeavesAClothThatFoldsLessToTheBit) {
  // A cloth bent along its rows by 0.5 rad per coarse link (under the 1 rad
  // limit): the same lattice with the limit as without.
  const Lattice fine = Lattice::rectangle(33, 49, 1.2, 0.8, Vec3::Zero());
  const CellGrid grid = CellGrid::of(fine, 5, 7);
  std::vector<Vec3> coarse(grid.coarse_count());
  for (int jc = 0; jc < 5; ++jc)
    for (int kc = 0; kc < 7; ++kc) {
      const double angle = 0.5 * kc, radius = 0.2 / 0.5;
      coarse[grid.coarse_index(jc, kc)] =
          Vec3(radius * std::sin(angle), -0.2 * jc, radius * (1.0 - std::cos(angle)));
    }
  std::vector<Vec3> plain(fine.node_count(), Vec3::Zero()), limited = plain;
  SmoothInfill(fine, grid).fill(coarse, plain, nullptr);
  SmoothInfill(fine, grid, std::nullopt, std::nullopt, kContactFoldLimitRad)
      .fill(coarse, limited, nullptr);
  EXPECT_EQ(plain, limited);
}

}  // namespace
}  // namespace flagsim::infill
