#include "flagsim/coarse_physics/creased_bending.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "finite_difference.hpp"
#include "scene_fixtures.hpp"
#include "tolerances.hpp"

namespace flagsim::physics {
namespace {

// Rest angles of 0 to 2.5 rad, seeded, on every triple of `lattice`.
std::vector<double> random_rest(const Lattice& lattice, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::vector<double> rest(bending_triples(lattice, 1.0).size());
  for (double& angle : rest) angle = 2.5 * double(rng() >> 11) * 0x1.0p-53;
  return rest;
}

// Rest angles `rest`, nothing held yet; frames of 0.1 s.
CreasedBending creased(const ClothModel& model, double rigidity, std::vector<double> rest,
                       Creases creases = {}) {
  rest.resize(2 * rest.size(), 0.0);
  return {model, rigidity, creases, 0.1, std::move(rest)};
}

TEST(CreasedBending, ForceIsMinusEnergyGradient) {
  const ClothModel model = make_cloth_model(test::small_cloth(5, 6));
  const CreasedBending bending = creased(model, 0.01, random_rest(model.lattice, 1));
  // Jiggled by 5 cm (links of 20-25 cm): every triple bent, some less than
  // its crease and some more, a few within the rounding.
  test::expect_force_is_minus_energy_gradient(bending, test::jiggled(model.lattice, 0.05, 3));
  test::expect_force_is_minus_energy_gradient(bending, test::jiggled(model.lattice, 0.005, 4));
}

TEST(CreasedBending, HessianIsMinusForceJacobian) {
  const ClothModel model = make_cloth_model(test::small_cloth(4, 5));
  CreasedBending bending = creased(model, 0.02, random_rest(model.lattice, 2));
  for (const double amplitude : {0.05, 0.005}) {
    const std::vector<Vec3> x = test::jiggled(model.lattice, amplitude, 5);
    test::expect_derivative_is_minus_force_jacobian(bending, x, std::vector<Vec3>(x.size()),
                                                    test::Wrt::kPosition);
  }
}

TEST(CreasedBending, TheCreasesPartAloneIsTheWholeLessThePlainBending) {
  // XPBD's form (plain = false): its bending is a constraint, the crease a force.
  const ClothModel model = make_cloth_model(test::small_cloth(4, 5));
  std::vector<double> memory = random_rest(model.lattice, 2);
  memory.resize(2 * memory.size(), 0.0);
  CreasedBending alone(model, 0.02, Creases{}, 0.1, memory, /*plain=*/false);
  const CreasedBending whole(model, 0.02, Creases{}, 0.1, memory);
  const BendingSprings plain(model, 0.02);
  EXPECT_EQ(alone.name(), "creases");
  for (const double amplitude : {0.05, 0.005}) {
    const std::vector<Vec3> x = test::jiggled(model.lattice, amplitude, 5);
    test::expect_force_is_minus_energy_gradient(alone, x);
    test::expect_derivative_is_minus_force_jacobian(alone, x, std::vector<Vec3>(x.size()),
                                                    test::Wrt::kPosition);
    EXPECT_NEAR(alone.energy(x) + plain.energy(x), whole.energy(x),
                test::kRoundOff * std::abs(whole.energy(x)) + 1e-15);
  }
}

TEST(CreasedBending, WithoutACreaseItIsTheBendingOfBendingSprings) {
  const ClothModel model = make_cloth_model(test::small_cloth(5, 6));
  const CreasedBending bending =
      creased(model, 0.01, std::vector<double>(bending_triples(model.lattice, 1.0).size(), 0.0));
  const BendingSprings plain(model, 0.01);
  const std::vector<Vec3> x = test::jiggled(model.lattice, 0.05, 3);
  std::vector<Vec3> f(x.size(), Vec3::Zero()), g(x.size(), Vec3::Zero());
  bending.add_forces(x, {}, f);
  plain.add_forces(x, {}, g);
  for (std::size_t i = 0; i < x.size(); ++i) EXPECT_EQ(f[i], g[i]) << i;  // same bits
  EXPECT_NEAR(bending.energy(x), plain.energy(x), test::kRoundOff * plain.energy(x));
}

// One row of nodes folded by `angle` at node `centre`: two straight halves.
std::vector<Vec3> folded_row(const Lattice& lattice, int centre, double angle) {
  std::vector<Vec3> x = lattice.rest_positions();
  for (int j = 0; j < lattice.rows; ++j)
    for (int k = centre + 1; k < lattice.cols; ++k) {
      const double along = (k - centre) * lattice.spacing_x_m;
      Vec3& p = x[lattice.index(j, k)];
      p.x() = centre * lattice.spacing_x_m + along * std::cos(angle);
      p.z() = along * std::sin(angle);
    }
  return x;
}

TEST(CreasedBending, ACreaseRestsFoldedAtItsAngleAboutEitherSide) {
  // A 3 x 9 cloth creased by theta_r on its middle column's row triples: the
  // rows folded there by the angle where |q| = sqrt(c^2 - eps^2) feel no
  // force, to round-off, folded up or down; the rest angle differs from
  // theta_r by about eps^2 / (2 s c) (the rounding: under 0.01 rad from 1 to 3 rad).
  const ClothModel model = make_cloth_model(test::small_cloth(3, 9));
  const Lattice& lattice = model.lattice;
  const double s = lattice.spacing_x_m, eps = kCreaseRounding * s;
  for (const double rest_angle : {1.0, 2.0, 3.0}) {
    const Fold fold{FoldAxis::kCol, 0.5, rest_angle};
    const CreasedBending bending = creased(model, 0.01, fold_rest_angles({&fold, 1}, lattice));
    const double c = 2.0 * s * std::sin(0.5 * rest_angle);
    const double at_rest = 2.0 * std::asin(std::sqrt(c * c - eps * eps) / (2.0 * s));
    EXPECT_LT(rest_angle - at_rest, 0.01) << rest_angle;
    for (const double side : {1.0, -1.0}) {
      const std::vector<Vec3> x = folded_row(lattice, 4, side * at_rest);
      std::vector<Vec3> f(x.size(), Vec3::Zero());
      bending.add_forces(x, {}, f);
      for (const Vec3& fi : f) EXPECT_LT(fi.norm(), test::kRoundOff) << rest_angle;
      // And folded further or less, the crease pushes back toward its angle.
      for (const double off : {-0.1, 0.1}) {
        const std::vector<Vec3> y = folded_row(lattice, 4, side * (at_rest + off));
        EXPECT_GT(bending.energy(y), bending.energy(x)) << rest_angle << " " << off;
      }
    }
    // Flat, the crease is a smooth unstable equilibrium: no force, and a small fold costs less.
    const std::vector<Vec3> flat = lattice.rest_positions();
    std::vector<Vec3> f(flat.size(), Vec3::Zero());
    bending.add_forces(flat, {}, f);
    for (const Vec3& fi : f) EXPECT_LT(fi.norm(), test::kRoundOff);
    EXPECT_LT(bending.energy(folded_row(lattice, 4, 0.05)), bending.energy(flat));
  }
}

TEST(CreasedBending, AFoldLineLiesWhereItIsAndTurnsByItsAngle) {
  // 11 columns (10 links): at = 0.3 is node 3, every row's triple centred there
  // takes the whole angle; at = 0.35 is halfway between nodes 3 and 4.
  const Lattice lattice = make_cloth_model(test::small_cloth(4, 11)).lattice;
  const std::size_t row_triples = std::size_t(4) * 9;
  const auto row_angle = [&](const std::vector<double>& rest, int j, int centre) {
    return rest[std::size_t(j) * 9 + std::size_t(centre - 1)];
  };
  Fold fold{FoldAxis::kCol, 0.3, 1.2};
  std::vector<double> rest = fold_rest_angles({&fold, 1}, lattice);
  for (int j = 0; j < 4; ++j) {
    EXPECT_DOUBLE_EQ(row_angle(rest, j, 3), 1.2);
    EXPECT_EQ(row_angle(rest, j, 4), 0.0);
  }
  fold.at = 0.35;
  rest = fold_rest_angles({&fold, 1}, lattice);
  for (int j = 0; j < 4; ++j) {
    EXPECT_NEAR(row_angle(rest, j, 3), 0.6, test::kRoundOff);
    EXPECT_NEAR(row_angle(rest, j, 4), 0.6, test::kRoundOff);
  }
  double total = 0.0;
  for (const double angle : rest) total += angle;
  EXPECT_NEAR(total, 4 * 1.2, test::kRoundOff);
  // The columns are not bent by it; a row fold bends the columns only.
  for (std::size_t t = row_triples; t < rest.size(); ++t) EXPECT_EQ(rest[t], 0.0);
  const Fold across{FoldAxis::kRow, 0.5, 3.5};  // past pi: capped
  rest = fold_rest_angles({&across, 1}, lattice);
  for (std::size_t t = 0; t < row_triples; ++t) EXPECT_EQ(rest[t], 0.0);
  // 4 rows: at 0.5 is between rows 1 and 2 (3 links: 1.5).
  for (std::size_t t = row_triples; t < rest.size(); ++t) EXPECT_NEAR(rest[t], 1.75, 1e-12);
}

TEST(CreasedBending, AFoldHeldPastTheYieldSetsAndACreaseHeldFlatAndPulledRelaxes) {
  const ClothModel model = make_cloth_model(test::small_cloth(3, 9));
  const Lattice& lattice = model.lattice;
  // D = 0.01 N m, w = 1 cm: T_c = D / w^2 = 100 N/m.
  const Creases creases{
      .yield_angle_rad = 0.5, .set_time_s = 1.0, .relax_time_s = 10.0, .width_m = 0.01};
  const std::size_t triples = bending_triples(lattice, 1.0).size();
  const auto middle = [&](const CreasedBending& b) { return b.memory()[4 - 1]; };  // row 0, node 4
  // Folded by 1 rad, past the yield: the held angle follows with time
  // constant 1 s, and once past the yield the rest angle follows it.
  CreasedBending bending = creased(model, 0.01, std::vector<double>(triples, 0.0), creases);
  const std::vector<Vec3> folded = folded_row(lattice, 4, 1.0);
  const std::vector<Vec3> flat = lattice.rest_positions();
  const double theta = bending.angles(folded)[4 - 1];
  EXPECT_NEAR(theta, 1.0, test::kRoundOff);
  const auto held = [&](const CreasedBending& b) { return b.memory()[triples + 4 - 1]; };
  bending.begin_frame(0.0, folded);  // t = 0: nothing was held before
  EXPECT_EQ(held(bending), 0.0);
  // Folded for 0.3 s and let go (a flapping cloth's kink): nothing sets.
  for (int frame = 1; frame <= 30; ++frame)
    bending.begin_frame(0.1 * frame, frame <= 3 ? folded : flat);
  for (std::size_t t = 0; t < triples; ++t) EXPECT_EQ(bending.memory()[t], 0.0);
  // Held for 3 s: held 1 - e^-3 of the fold; the rest angle behind it.
  bending = creased(model, 0.01, std::vector<double>(triples, 0.0), creases);
  for (int frame = 1; frame <= 30; ++frame) bending.begin_frame(0.1 * frame, folded);
  EXPECT_NEAR(held(bending), theta * (1.0 - std::exp(-3.0)), test::kRoundOff);
  EXPECT_GT(middle(bending), 0.5 * theta);
  EXPECT_LT(middle(bending), held(bending));
  // Held for 10 s: the rest angle is the fold's (cascaded: 1 - e^-10 (1 + 10)).
  for (int frame = 31; frame <= 100; ++frame) bending.begin_frame(0.1 * frame, folded);
  EXPECT_NEAR(middle(bending), theta, 0.01);
  const double set = middle(bending);
  std::vector<double> memory(bending.memory().begin(), bending.memory().end());
  std::fill(memory.begin() + std::ptrdiff_t(triples), memory.end(), 0.0);  // let go long ago
  bending.set_memory(memory);
  // Held flat and slack, it stays.
  for (int frame = 1; frame <= 10; ++frame) bending.begin_frame(10.0 + 0.1 * frame, flat);
  EXPECT_EQ(middle(bending), set);
  // Held flat and pulled along the rows (Y = 1000 N/m), it relaxes with time
  // constant relax_time / phi, phi = 1 / (1 + sqrt(T_c / T)): faster the harder it is pulled.
  double relaxed_at[2] = {};
  for (const int pull : {0, 1}) {
    const double strain = pull ? 0.04 : 0.01, tension = 1000.0 * strain;
    std::vector<Vec3> pulled = flat;
    for (Vec3& p : pulled) p.x() *= 1.0 + strain;
    bending.set_memory(memory);
    for (int frame = 1; frame <= 10; ++frame) bending.begin_frame(10.0 + 0.1 * frame, pulled);
    const double phi = 1.0 / (1.0 + std::sqrt(100.0 / tension));
    EXPECT_NEAR(middle(bending), set * std::exp(-phi * 0.1), 1e-9) << strain;
    relaxed_at[pull] = middle(bending);
  }
  EXPECT_LT(relaxed_at[1], relaxed_at[0]);
  // A fold under the yield, however long held, leaves nothing.
  CreasedBending below = creased(model, 0.01, std::vector<double>(triples, 0.0), creases);
  const std::vector<Vec3> slight = folded_row(lattice, 4, 0.49);
  for (int frame = 1; frame <= 100; ++frame) below.begin_frame(0.1 * frame, slight);
  for (std::size_t t = 0; t < triples; ++t) EXPECT_EQ(below.memory()[t], 0.0);
  EXPECT_NEAR(held(below), 0.49, 0.001);
}

}  // namespace
}  // namespace flagsim::physics
