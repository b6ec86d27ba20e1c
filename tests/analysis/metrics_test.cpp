// Each metric on a constructed case whose answer is known.
#include "flagsim/analysis/metrics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tolerances.hpp"

namespace flagsim::analysis {
namespace {

const Lattice kLattice = Lattice::rectangle(9, 13, 1.5, 1.0, Vec3(0.0, 2.0, 0.0));

// A run: the rest lattice bobbing in z as sin(2 pi f t), 30 fps.
Frames bobbing(int frames, double hz, double amplitude = 0.05) {
  Frames out;
  for (int t = 0; t < frames; ++t) {
    std::vector<Vec3> x = kLattice.rest_positions();
    for (int j = 0; j < kLattice.rows; ++j)
      for (int k = 0; k < kLattice.cols; ++k)
        x[kLattice.index(j, k)].z() +=
            amplitude * (k / 12.0) * std::sin(2.0 * std::numbers::pi * hz * t / 30.0);
    out.push_back(x);
  }
  return out;
}

Frames shifted(Frames frames, const Vec3& by) {
  for (auto& x : frames)
    for (Vec3& p : x) p += by;
  return frames;
}

TEST(Metrics, IdenticalRunsHaveNoError) {
  const Frames a = bobbing(60, 1.3);
  EXPECT_EQ(short_horizon_rms(a, a, 15), 0.0);
  EXPECT_EQ(mean_shape_rms(a, a, 0), 0.0);
  EXPECT_EQ(rms_distance(a[7], a[7]), 0.0);
}

TEST(Metrics, AKnownShiftGivesThatShift) {
  const Frames a = bobbing(60, 1.3);
  const Frames b = shifted(a, Vec3(0.003, -0.004, 0.0));  // 5 mm
  EXPECT_NEAR(short_horizon_rms(a, b, 15), 0.005, test::kRoundOff);
  EXPECT_NEAR(mean_shape_rms(a, b, 30), 0.005, test::kRoundOff);
  // Only the nodes kept count.
  std::vector<std::uint8_t> keep(a[0].size(), 0);
  std::vector<Vec3> c = a[5];
  c[3] += Vec3(0.0, 0.0, 0.02);
  keep[3] = 1;
  EXPECT_NEAR(rms_distance(a[5], c, keep), 0.02, test::kRoundOff);
}

TEST(Metrics, ASineDrivenFlyEndGivesItsFrequency) {
  for (double hz : {0.7, 1.3, 2.9, 6.1}) {
    std::vector<double> z;
    z.reserve(300);
    for (int t = 0; t < 300; ++t)
      z.push_back(0.2 + 0.1 * std::sin(2.0 * std::numbers::pi * hz * t / 30.0 + 0.4));
    EXPECT_NEAR(flap_frequency_hz(z, 30.0), hz, test::kSpectralRelTol * hz) << hz;
    const FlapFrequency both = flap_frequency(z, 30.0);
    EXPECT_NEAR(both.spectral_hz, hz, test::kSpectralRelTol * hz) << hz;
    EXPECT_GE(both.crossings, 2 * int(hz * 300.0 / 30.0) - 1) << hz;
  }
  EXPECT_EQ(flap_frequency_hz(std::vector<double>(100, 1.0), 30.0), 0.0);  // no flapping
}

TEST(Metrics, AFlapFrequencyCountsTurnsOfAnyShape) {
  // A 3 Hz flap of a skewed shape (the fly end snapping back, every other
  // half period short) with a slow drift: its crossings still come 6 a second.
  std::vector<double> z;
  const double fps = 30.0;
  for (int t = 0; t < 160; ++t) {
    const double time = t / fps, phase = 2.0 * std::numbers::pi * 3.0 * time;
    z.push_back(0.3 * std::sin(phase + 0.8 * std::sin(phase)) + 0.01 * time);
  }
  const FlapFrequency f = flap_frequency(z, fps);
  EXPECT_NEAR(f.hz, 3.0, test::kSpectralRelTol * 3.0);
  EXPECT_GE(f.crossings, 30);
}

TEST(Metrics, StrainDistributionFindsTheStretchedLink) {
  std::vector<Vec3> x = kLattice.rest_positions();
  for (int k = 0; k < kLattice.cols; ++k) x[kLattice.index(8, k)].y() -= 0.1 * kLattice.spacing_y_m;
  const StrainDistribution s = strain_distribution(kLattice, Frames{x});
  EXPECT_NEAR(s.max, 0.1,
              test::kFloat32);  // (kept as float32) the last row's 13 column links, of 212
  EXPECT_NEAR(s.p99, 0.1, test::kFloat32);  // 13/212 > 1%
  const StrainDistribution rest = strain_distribution(kLattice, Frames{kLattice.rest_positions()});
  EXPECT_NEAR(rest.max, 0.0, test::kRoundOff);
}

TEST(Metrics, WrinkleWavelengthOfASineWrinkledSheet) {
  const Lattice fine = Lattice::rectangle(17, 97, 1.5, 1.0, Vec3::Zero());
  for (double wavelength : {0.25, 0.5}) {
    std::vector<Vec3> x = fine.rest_positions();
    for (Vec3& p : x) p.z() = 0.004 * std::sin(2.0 * std::numbers::pi * p.x() / wavelength);
    EXPECT_NEAR(wrinkle_wavelength_m(fine, Frames{x}, 0), wavelength,
                test::kWavelengthRelTol * wavelength);
  }
}

// A cap curved alike both ways (z = -(x^2 + y^2) / 2R over the rest
// rectangle), with a straight V-fold of `fold` rad a side along dense row `row`
// when fold > 0.
std::vector<Vec3> cap(const Lattice& lattice, double radius_m, int row, double fold) {
  std::vector<Vec3> x = lattice.rest_positions();
  const Vec3 centre = 0.5 * (x.front() + x.back());
  for (int j = 0; j < lattice.rows; ++j)
    for (int k = 0; k < lattice.cols; ++k) {
      Vec3& p = x[lattice.index(j, k)];
      const Vec3 d = p - centre;
      p.z() = -(d.x() * d.x() + d.y() * d.y()) / (2.0 * radius_m) +
              fold * std::abs(j - row) * lattice.spacing_y_m;
    }
  return x;
}

TEST(Metrics, CreaseLineRatioIsOneOnACapAndFindsAStraightFold) {
  // Every fiber of the cap turns by about h / R, so no line stands out. A
  // valley of 0.02 rad a side along one row turns the column fibers there by
  // 0.04 rad less the cap's own h / R (the cap bends the other way), against
  // h / R = 0.0052 elsewhere: 6.7x.
  const Lattice lattice = Lattice::rectangle(65, 97, 1.5, 1.0, Vec3::Zero());
  const double h_over_r = lattice.spacing_x_m / 3.0;
  const double smooth = crease_line_ratio(lattice, cap(lattice, 3.0, 32, 0.0));
  EXPECT_NEAR(smooth, 1.0, 0.05);
  const double folded = crease_line_ratio(lattice, cap(lattice, 3.0, 32, 0.02));
  const double expected = (0.04 - h_over_r) / h_over_r;
  EXPECT_NEAR(folded, expected, 0.02 * expected);
  // A fold within the margin (8 links) of the border is not a crease line here.
  EXPECT_NEAR(crease_line_ratio(lattice, cap(lattice, 3.0, 4, 0.02)), 1.0, 0.05);
}

}  // namespace
}  // namespace flagsim::analysis
