#include "flagsim/infill/crease_ridges.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tolerances.hpp"

namespace flagsim::infill {
namespace {

// A 1.2 x 0.8 m cloth: 17 x 25 dense nodes (5 cm links), 5 x 7 coarse (cells of 4 x 4).
const Lattice kFine = Lattice::rectangle(17, 25, 1.2, 0.8, Vec3::Zero());
const CellGrid kGrid = CellGrid::of(kFine, 5, 7);
constexpr int kRowTriples = 5 * 5, kColTriples = 3 * 7;

// The coarse nodes flat, rows stretched by `strain` (the tension along them: Y strain).
std::vector<Vec3> coarse_flat(double strain) {
  std::vector<Vec3> coarse;
  for (int jc = 0; jc < 5; ++jc)
    for (int kc = 0; kc < 7; ++kc) coarse.emplace_back(0.2 * kc * (1.0 + strain), -0.2 * jc, 0.0);
  return coarse;
}

// Coarse rest angles of a fold along a column at coarse place 2.25 (dense
// column 9): 0.75 of `angle` on the row triples centred at kc = 2, 0.25 at kc = 3.
std::vector<double> fold_at_2_25(double angle) {
  std::vector<double> rest(kRowTriples + kColTriples, 0.0);
  for (int jc = 0; jc < 5; ++jc) {
    rest[std::size_t(jc) * 5 + 1] = 0.75 * angle;
    rest[std::size_t(jc) * 5 + 2] = 0.25 * angle;
  }
  return rest;
}

TEST(CreaseRidges, AFlattenedCreaseLeavesARidgeOnItsLineAsTheHingeAndTheTensionSay) {
  // D = 1e-4 N m, w = 1 mm, Y = 2e4 N/m; rows stretched by 0.5%: T = 100 N/m,
  // lambda = sqrt(D / T) = 1 mm (under the 5 cm link), kink min(0.4, 0.3 / 1.5) = 0.2 rad.
  const CreaseRidgeParams params{1.0e-4, 1.0e-3, 2.0e4};
  CreaseRidges ridges(kFine, kGrid, params);
  ridges.set_rest(fold_at_2_25(0.3));
  ASSERT_TRUE(ridges.any());
  const std::vector<double>& offsets = ridges.offsets(coarse_flat(0.005));
  const double lambda = 1e-3, kink = 0.3 / (1.0 + 1e-3 / (2.0 * lambda));
  for (int j = 0; j < 17; ++j) {
    // On the line (dense column 9 = 2.25 x 4), height kink lambda / 2; a link
    // away, e^(-50) of it: the ridge is the line's alone.
    EXPECT_NEAR(offsets[kFine.index(j, 9)], 0.5 * kink * lambda, test::kRoundOff) << j;
    for (int k = 0; k < 25; ++k) {
      if (k != 9) {
        EXPECT_LT(offsets[kFine.index(j, k)], 1e-20) << j << " " << k;
      }
    }
  }
  // Less tension, a wider and taller ridge: at 0.05% (T = 10 N/m), lambda = 3.2 mm.
  const std::vector<double>& slack = ridges.offsets(coarse_flat(0.0005));
  const double wide = std::sqrt(1e-4 / 10.0), wide_kink = 0.3 / (1.0 + 1e-3 / (2.0 * wide));
  EXPECT_NEAR(slack[kFine.index(3, 9)], 0.5 * wide_kink * wide, 1e-12);
  // No tension, a crease of 2 rad: lambda is the dense link, the kink capped at 0.4 rad.
  ridges.set_rest(fold_at_2_25(2.0));
  const std::vector<double>& capped = ridges.offsets(coarse_flat(0.0));
  EXPECT_NEAR(capped[kFine.index(3, 9)], 0.5 * 0.4 * 0.05, 1e-12);
  EXPECT_NEAR(capped[kFine.index(3, 10)], 0.5 * 0.4 * 0.05 * std::exp(-1.0), 1e-12);
}

TEST(CreaseRidges, AFoldTheCoarseClothShowsNeedsNoRidgeAndNoCreaseMakesNone) {
  const CreaseRidgeParams params{1.0e-4, 1.0e-3, 2.0e4};
  CreaseRidges ridges(kFine, kGrid, params);
  // The coarse rows turning by the crease's 0.3 rad across kc = 2..3 (the run):
  // everything it holds is shown, nothing is left for a ridge.
  std::vector<Vec3> coarse = coarse_flat(0.005);
  for (int jc = 0; jc < 5; ++jc)
    for (int kc = 3; kc < 7; ++kc) {
      const double along = 0.2 * 1.005 * (kc - 2);
      Vec3& p = coarse[std::size_t(jc) * 7 + std::size_t(kc)];
      p.x() = 0.2 * 1.005 * 2 + along * std::cos(0.3);
      p.z() = along * std::sin(0.3);
    }
  ridges.set_rest(fold_at_2_25(0.3));
  for (const double offset : ridges.offsets(coarse)) EXPECT_LT(std::abs(offset), 1e-12);
  // No crease: none anywhere, and any() says so.
  ridges.set_rest(std::vector<double>(kRowTriples + kColTriples, 0.0));
  EXPECT_FALSE(ridges.any());
  for (const double offset : ridges.offsets(coarse_flat(0.005))) EXPECT_EQ(offset, 0.0);
}

TEST(CreaseRidges, BetweenCoarseFibersTheirRidgesAreSharedByNearness) {
  // A crease on coarse row 1 only: full on dense row 4 (on it), fading to
  // rows 0 and 8 (coarse rows 0 and 2), none from there on.
  const CreaseRidgeParams params{1.0e-4, 1.0e-3, 2.0e4};
  CreaseRidges ridges(kFine, kGrid, params);
  std::vector<double> rest(kRowTriples + kColTriples, 0.0);
  rest[1 * 5 + 1] = 0.3;  // coarse row 1, centred at kc = 2: dense column 8
  ridges.set_rest(rest);
  const std::vector<double>& offsets = ridges.offsets(coarse_flat(0.005));
  const double full = offsets[kFine.index(4, 8)];
  EXPECT_GT(full, 0.0);
  for (int j = 0; j <= 8; ++j) {
    const double weight = j <= 4 ? j / 4.0 : (8 - j) / 4.0;
    EXPECT_NEAR(offsets[kFine.index(j, 8)], weight * full, test::kRoundOff) << j;
  }
  for (int j = 9; j < 17; ++j) EXPECT_EQ(offsets[kFine.index(j, 8)], 0.0) << j;
}

}  // namespace
}  // namespace flagsim::infill
