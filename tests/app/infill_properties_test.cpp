// The paper's four cloth properties (section 1) as numbers on the output of
// the corner-driven infill mode, end to end through build/flag-sim.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

#include "flagsim/core/lattice.hpp"
#include "flagsim/data/output_reader.hpp"
#include "process.hpp"
#include "temp_dir.hpp"
#include "tolerances.hpp"

namespace flagsim::test {
namespace {

// A 1.5 x 1.0 m flag on 33 x 49 nodes whose corners move to `end_corners`
// (TOML) by t = 1.5 s, then follow `later_keyframes`; wrinkles from fiber radius r.
std::string scene(const std::string& end_corners, double radius_m, double duration_s,
                  const std::string& later_keyframes = "") {
  return "[scene]\nmode = \"infill\"\nduration = " + std::to_string(duration_s) +
         "\nfps = 30.0\nseed = 1\n[flag]\nsize = [1.5, 1.0]\nfine = [33, 49]\n"
         "initial_perturbation = 0.005\n[wrinkles]\nfiber_radius = " +
         std::to_string(radius_m) +
         "\nfiber_modulus = 1.0e9\nk_prime = 0.1\n"
         "[[keyframe]]\ntime = 0.0\ncorners = [[0.0, 2.0, 0.0], [1.5, 2.0, 0.0], [0.0, 1.0, 0.0], "
         "[1.5, 1.0, 0.0]]\n"
         "[[keyframe]]\ntime = 1.5\ncorners = " +
         end_corners + "\n" + later_keyframes;
}

// Corners pushed toward each other along the rows by `fraction` of the width.
std::string pushed(double fraction) {
  const double d = 0.75 * fraction;
  auto num = [](double v) { return std::to_string(v); };
  return "[[" + num(d) + ", 2.0, 0.0], [" + num(1.5 - d) + ", 2.0, 0.0], [" + num(d) +
         ", 1.0, 0.0], [" + num(1.5 - d) + ", 1.0, 0.0]]";
}

struct Run {
  TempDir dir;
  std::unique_ptr<data::OutputReader> reader;
};

std::unique_ptr<Run> run(const std::string& scene_text) {
  auto result = std::make_unique<Run>();
  result->dir.write("s.toml", scene_text);
  const ProcessResult process =
      run_flag_sim({"run", "s.toml", "-o", "r.h5", "--quiet"}, result->dir.path());
  EXPECT_EQ(process.exit_code, 0) << process.err;
  result->reader = std::make_unique<data::OutputReader>(result->dir.file("r.h5"));
  return result;
}

// Out-of-plane offset of every node from the straight line between its row's ends, [J][K].
std::vector<std::vector<double>> row_offsets(const std::vector<Vec3>& positions, int rows,
                                             int cols) {
  const NodeView x(rows, cols, positions);
  std::vector<std::vector<double>> offsets(static_cast<std::size_t>(rows),
                                           std::vector<double>(static_cast<std::size_t>(cols)));
  for (int j = 0; j < rows; ++j) {
    const Vec3 &a = x.at(j, 0), &b = x.at(j, cols - 1);
    for (int k = 0; k < cols; ++k)
      offsets[j][k] = x.at(j, k).z() - (a.z() + (b.z() - a.z()) * k / (cols - 1));
  }
  return offsets;
}

// Dominant wrinkle wavelength along the rows, m: 2 x chord / (half-waves), the
// half-waves counted as sign changes of the offset, median over the inner rows.
double wavelength_m(const std::vector<Vec3>& positions, int rows, int cols) {
  const NodeView x(rows, cols, positions);
  const auto offsets = row_offsets(positions, rows, cols);
  std::vector<double> lengths;
  for (int j = 1; j + 1 < rows; ++j) {
    int changes = 0;
    for (int k = 2; k + 1 < cols; ++k) changes += (offsets[j][k] > 0) != (offsets[j][k - 1] > 0);
    const double chord = (x.at(j, cols - 1) - x.at(j, 0)).norm();
    lengths.push_back(2.0 * chord / (changes + 1));
  }
  std::nth_element(lengths.begin(), lengths.begin() + long(lengths.size() / 2), lengths.end());
  return lengths[lengths.size() / 2];
}

TEST(InfillProperties, Two_FormedWrinklesPersistWhileTheCornersAreHeld) {
  // Pushed 30% by t = 1.5 s (frame 45), then held for 100 frames.
  const auto r = run(scene(pushed(0.3), 1e-3, 4.9));
  ASSERT_EQ(r->reader->frame_count(), 148);
  const auto formed = r->reader->positions(46), later = r->reader->positions(146);
  double largest = 0.0;
  for (std::size_t i = 0; i < formed.size(); ++i)
    largest = std::max(largest, (later[i] - formed[i]).norm());
  EXPECT_LT(largest, 0.005 * 1.0);  // 0.5% of the flag height; measured 0
}

TEST(InfillProperties, Two_SmallCornerJitterKeepsTheWrinklePattern) {
  // After forming, the corners jitter by up to 5 mm for 1.5 s.
  std::string jitter;
  const double offsets[] = {0.004, -0.005, 0.003, -0.002, 0.005, 0.0};
  for (int n = 0; n < 6; ++n) {
    const double t = 1.75 + 0.25 * n, e = offsets[n];
    jitter += "[[keyframe]]\ntime = " + std::to_string(t) + "\ncorners = [[" +
              std::to_string(0.225 + e) + ", 2.0, " + std::to_string(e) + "], [1.275, " +
              std::to_string(2.0 - e) + ", 0.0], [0.225, 1.0, " + std::to_string(-e) + "], [" +
              std::to_string(1.275 - e) + ", 1.0, 0.0]]\n";
  }
  const auto r = run(scene(pushed(0.3), 1e-3, 3.5, jitter));
  const int rows = r->reader->rows(), cols = r->reader->cols();
  const auto before = row_offsets(r->reader->positions(46), rows, cols);
  const auto after = row_offsets(r->reader->positions(r->reader->frame_count() - 1), rows, cols);
  // Pearson correlation of the two height fields.
  std::vector<double> a, b;
  for (int j = 0; j < rows; ++j)
    for (int k = 0; k < cols; ++k) {
      a.push_back(before[j][k]);
      b.push_back(after[j][k]);
    }
  const double ma = std::accumulate(a.begin(), a.end(), 0.0) / double(a.size());
  const double mb = std::accumulate(b.begin(), b.end(), 0.0) / double(b.size());
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  ASSERT_GT(saa, 0.0);
  EXPECT_GT(sab / std::sqrt(saa * sbb), 0.9);  // measured 0.99998
}

TEST(InfillProperties, Three_WrinkleWavelengthGrowsAsTheFiberRadiusSquared) {
  // The balance E = e of eq. (13) gives wavelength ~ r^2 (property 3), while
  // the lattice resolves the waves: radii 0.5 to 1 mm give several half-waves
  // across the ~1 m chord (at 2 mm a single half-wave spans the flag, and the
  // wavelength cannot grow further). Least-squares slope on log-log, 2 +- 0.5
  // (measured 1.73 on 2026-12-02).
  std::vector<double> log_r, log_wavelength;
  for (double radius : {0.5e-3, 0.7e-3, 1.0e-3}) {
    const auto r = run(scene(pushed(0.3), radius, 1.6));
    const auto x = r->reader->positions(r->reader->frame_count() - 1);
    const double wavelength = wavelength_m(x, r->reader->rows(), r->reader->cols());
    log_r.push_back(std::log(radius));
    log_wavelength.push_back(std::log(wavelength));
  }
  const double n = double(log_r.size());
  const double mr = std::accumulate(log_r.begin(), log_r.end(), 0.0) / n;
  const double mw = std::accumulate(log_wavelength.begin(), log_wavelength.end(), 0.0) / n;
  double srw = 0.0, srr = 0.0;
  for (std::size_t i = 0; i < log_r.size(); ++i) {
    srw += (log_r[i] - mr) * (log_wavelength[i] - mw);
    srr += (log_r[i] - mr) * (log_r[i] - mr);
  }
  const double slope = srw / srr;
  EXPECT_NEAR(slope, 2.0, test::kWavelengthSlopeTol)
      << "wavelengths " << std::exp(log_wavelength[0]) << ", " << std::exp(log_wavelength[1])
      << ", " << std::exp(log_wavelength[2]) << " m";
  RecordProperty("slope", std::to_string(slope));
}

// Bending energy per node, sum of theta^2 of its row and column turning angles.
std::vector<double> bending_per_node(const std::vector<Vec3>& positions, int rows, int cols) {
  const NodeView x(rows, cols, positions);
  const auto at = [&](int j, int k) -> const Vec3& { return x.at(j, k); };
  auto turn = [](const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 u = b - a, v = c - b;
    return std::atan2(u.cross(v).norm(), u.dot(v));
  };
  std::vector<double> energy(std::size_t(rows) * std::size_t(cols), 0.0);
  const NodeView energy_at(rows, cols, energy);
  for (int j = 0; j < rows; ++j)
    for (int k = 0; k < cols; ++k) {
      double& e = energy_at.at(j, k);
      if (k > 0 && k + 1 < cols) e += std::pow(turn(at(j, k - 1), at(j, k), at(j, k + 1)), 2);
      if (j > 0 && j + 1 < rows) e += std::pow(turn(at(j - 1, k), at(j, k), at(j + 1, k)), 2);
    }
  return energy;
}

TEST(InfillProperties, Four_LooseConstraintsGiveBroadGentleWrinkles) {
  // Corners 10% closer. Measure: the share of all bending energy (sum of
  // theta^2) held by the most-bent 5% of the nodes. One sharp fold would put
  // most of it there; bending spread over the cloth puts little more than 5%.
  // Threshold 0.25 (measured 0.14).
  const auto r = run(scene(pushed(0.1), 1e-3, 1.6));
  std::vector<double> energy = bending_per_node(r->reader->positions(r->reader->frame_count() - 1),
                                                r->reader->rows(), r->reader->cols());
  const double total = std::accumulate(energy.begin(), energy.end(), 0.0);
  ASSERT_GT(total, 0.0);
  std::sort(energy.begin(), energy.end(), std::greater<>());
  const std::size_t top = energy.size() / 20;
  const double share = std::accumulate(energy.begin(), energy.begin() + long(top), 0.0) / total;
  EXPECT_LT(share, 0.25);
  // And the cloth did bend out of its plane: broad wrinkles, not an in-plane crumple.
  double height = 0.0;
  for (const Vec3& p : r->reader->positions(r->reader->frame_count() - 1))
    height = std::max(height, std::abs(p.z()));
  EXPECT_GT(height, 0.05);
}

}  // namespace
}  // namespace flagsim::test
