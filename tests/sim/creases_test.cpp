// Creases (issue 32) through whole simulations: fold lines a cloth starts
// with, kept where nothing pulls them out, relaxed by the wind's pull, carried
// by the state.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "flagsim/core/errors.hpp"
#include "flagsim/scene/scene_parser.hpp"
#include "flagsim/sim/simulation.hpp"

namespace flagsim::sim {
namespace {

// The default scene on a 17 x 25 full lattice (mass-spring), 2 s, creased in
// four (a fold line along the middle column, 2.5 rad toward the front, and
// one along the middle row, 2.5 rad toward the front on the pole's half and
// toward the back on the fly's: folded in half, then in half again), with
// [bending] D = 1e-4 N m; `more` overrides.
Scene folded_in_four(std::vector<std::string> more = {}) {
  std::vector<std::string> sets = {
      "scene.mode=\"mass-spring\"",
      "flag.fine=[17,25]",
      "scene.duration=2.0",
      std::string("flag.folds=[{axis=\"col\",at=0.5,angle=2.5},") +
          "{axis=\"row\",at=0.5,angle=2.5,to=0.5},{axis=\"row\",at=0.5,angle=-2.5,from=0.5}]",
      "bending.stiffness=1e-4",
      "creases.set_time=1.0",
      "creases.relax_time=30.0"};
  sets.insert(sets.end(), more.begin(), more.end());
  return parse_scene(default_scene_toml(), kDefaultSceneName, sets);
}

// Turning angle at node (j, k) along its row (`row`) or column, rad.
double turning(std::span<const Vec3> x, int cols, int j, int k, bool row) {
  const auto at = [&](int jj, int kk) { return x[std::size_t(jj) * std::size_t(cols) + kk]; };
  const Vec3 a = row ? at(j, k - 1) : at(j - 1, k), b = at(j, k),
             c = row ? at(j, k + 1) : at(j + 1, k);
  const Vec3 e1 = b - a, e2 = c - b;
  return std::atan2(e1.cross(e2).norm(), e1.dot(e2));
}

double median(std::vector<double> values) {
  std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(values.size() / 2),
                   values.end());
  return values[values.size() / 2];
}

// Median turning angle across the middle column's fold line (the rows' at k =
// 12), and over every interior node of the cloth, rad.
std::pair<double, double> fold_and_cloth_turning(std::span<const Vec3> x) {
  std::vector<double> line, cloth;
  for (int j = 0; j < 17; ++j) {
    line.push_back(turning(x, 25, j, 12, true));
    for (int k = 1; k < 24; ++k) cloth.push_back(turning(x, 25, j, k, true));
  }
  for (int j = 1; j < 16; ++j)
    for (int k = 0; k < 25; ++k) cloth.push_back(turning(x, 25, j, k, false));
  return {median(line), median(cloth)};
}

// The mean rest angle on the middle column's fold line (row triples centred
// at k = 12), rad, from a state's memory.
double fold_rest_angle(const SimulationState& state) {
  double sum = 0.0;
  for (int j = 0; j < 17; ++j) sum += state.physics.memory[std::size_t(j) * 23 + 11];
  return sum / 17;
}

TEST(Creases, AFoldedClothKeepsItsFoldLinesWhereNothingPullsThemOut) {
  // No wind, no gravity, nothing pinned: the crease pops out of the flat start
  // (pushed to each crease's side) and stays. Over 2 s the fold line's median
  // turning angle stays at least 20x the cloth's (measured: 38x and more from
  // 0.2 s on); without the fold lines the same start stays flat.
  const std::vector<std::string> calm = {"scene.mode=\"mass-spring\"", "flag.pin=\"none\"",
                                         "wind.velocity=[0,0,0]", "gravity.acceleration=[0,0,0]"};
  const auto creased = make_simulation(folded_in_four(calm));
  for (int frame = 1; frame <= 60; ++frame) {
    creased->advance_frame(nullptr);
    if (frame < 6) continue;  // 0.2 s to pop out
    const auto [line, cloth] = fold_and_cloth_turning(creased->positions());
    EXPECT_GT(line, 20.0 * cloth) << "frame " << frame;  // the goal: 3x
  }
  // Little tension (the two fold lines cross and hold each other at about 1.1
  // rad): the creases barely relax.
  EXPECT_NEAR(fold_rest_angle(creased->state()), 2.5, 0.01);
  // The other backends keep them too: at least 15x the cloth's turning from
  // 0.5 s on (measured, lowest over 0.5-2 s: implicit 70x, xpbd 50x, bullet 44x).
  for (const char* mode : {"implicit", "xpbd", "bullet"}) {
    std::vector<std::string> sets = calm;
    sets.emplace_back(std::string("scene.mode=\"") + mode + "\"");
    const auto other = make_simulation(folded_in_four(sets));
    for (int frame = 1; frame <= 60; ++frame) {
      other->advance_frame(nullptr);
      if (frame < 15) continue;
      const auto [line, cloth] = fold_and_cloth_turning(other->positions());
      EXPECT_GT(line, 15.0 * cloth) << mode << " frame " << frame;
    }
  }
}

TEST(Creases, AFoldHeldPastTheYieldSetsAndOneBelowItLeavesNothing) {
  // A stiffer cloth (D = 0.01 N m), 17 x 25, calm, nothing pinned, held
  // folded about its middle column (the rows bent by `angle` at k = 12) for
  // 1 s and let go. With [creases] (yield 1 rad, set_time 0.2 s) a fold of 2
  // rad sets and stays; one of 0.8 rad, under the yield, opens exactly as
  // without [creases] (the same bits: no rest angle was ever set, and the
  // creased bending with none is the plain one).
  const auto run = [](double angle, bool creases) {
    std::vector<std::string> sets = {"scene.mode=\"mass-spring\"",
                                     "flag.fine=[17,25]",
                                     "scene.duration=2.0",
                                     "flag.pin=\"none\"",
                                     "wind.velocity=[0,0,0]",
                                     "gravity.acceleration=[0,0,0]",
                                     "flag.initial_perturbation=0.0",
                                     "bending.stiffness=0.01"};
    if (creases) {
      sets.emplace_back("creases.set_time=0.2");
      sets.emplace_back("creases.yield_angle=1.0");
    }
    const auto cloth = make_simulation(parse_scene(default_scene_toml(), kDefaultSceneName, sets));
    SimulationState folded = cloth->state();
    const double link = 1.5 / 24;
    for (int j = 0; j < 17; ++j)
      for (int k = 13; k < 25; ++k) {
        Vec3& p = folded.physics.x_m[std::size_t(j) * 25 + std::size_t(k)];
        const double along = (k - 12) * link;
        p.x() = 12 * link + along * std::cos(angle);
        p.z() = along * std::sin(angle);
      }
    // Held folded for 1 s (each frame's positions put back: a hand pressing
    // the fold), then let go for 1 s.
    std::vector<double> line;  // the fold line's median turning, every frame let go
    for (int frame = 1; frame <= 60; ++frame) {
      if (frame <= 30) {
        SimulationState held = cloth->state();
        held.physics.x_m = folded.physics.x_m;
        std::fill(held.physics.v_m_s.begin(), held.physics.v_m_s.end(), Vec3::Zero());
        cloth->set_state(held);
      }
      cloth->advance_frame(nullptr);
      if (frame > 30) line.push_back(fold_and_cloth_turning(cloth->positions()).first);
    }
    return line;
  };
  const std::vector<double> set = run(2.0, true), open = run(2.0, false);
  // 1 s after letting go (measured): 1.94 rad set, 0.147 rad without creases (13x).
  EXPECT_GT(set.back(), 1.5);
  EXPECT_GT(set.back(), 10.0 * open.back());
  // Under the yield nothing sets, and the fold opens as without [creases]
  // (within 10% was the goal; measured 1e-5: the stability limit
  // allows for creases that may set, so the substeps differ a little).
  const std::vector<double> under = run(0.8, true), plain = run(0.8, false);
  ASSERT_EQ(under.size(), plain.size());
  for (std::size_t f = 0; f < under.size(); ++f)
    EXPECT_NEAR(under[f], plain[f], 1e-3 * plain[f] + 1e-9) << f;
}

TEST(Creases, TheWindPullsTheFoldLinesOutFasterTheStrongerItBlows) {
  // The default flag, creased in four, hoisted into 5 and 15 m/s for 2 s: the
  // fold line's rest angle falls in both (the wind's pull relaxes it), more in
  // the stronger. Measured (17 x 25, relax_time 30 s): 2.5 -> 2.471 (5 m/s), 2.464 (15 m/s).
  double relaxed[2] = {};
  for (const int fast : {0, 1}) {
    const auto flag = make_simulation(
        folded_in_four({fast ? "wind.velocity=[15.0,0,0]" : "wind.velocity=[5.0,0,0]"}));
    for (int frame = 1; frame <= 60; ++frame) flag->advance_frame(nullptr);
    relaxed[fast] = fold_rest_angle(flag->state());

    EXPECT_LT(relaxed[fast], 2.49);
  }
  // More than 1.1x the relaxation (measured 0.0328 / 0.0287 rad = 1.14x with
  // the wind held over substeps, 0.0355 / 0.0287 = 1.24x evaluated every
  // substep: the 15 m/s flap is chaotic, and the pull it relaxes the fold by
  // is its history's, 2026-12-07).
  EXPECT_GT(2.5 - relaxed[1], 1.1 * (2.5 - relaxed[0]));
}

// Per frame, each dense column's median turning angle along the rows (columns
// 1..K-2), rad.
std::vector<double> column_turning(std::span<const Vec3> x, int rows, int cols) {
  std::vector<double> medians;
  for (int k = 1; k + 1 < cols; ++k) {
    std::vector<double> column(std::size_t(rows), 0.0);
    for (int j = 0; j < rows; ++j) column[std::size_t(j)] = turning(x, cols, j, k, true);
    medians.push_back(median(column));
  }
  return medians;
}

TEST(Creases, TheHybridDrawsAFoldLineWhereItLiesAtDenseResolution) {
  // The default hybrid on 65 x 97 (coarse 9 x 13: coarse columns every 8
  // dense ones) in its 10 m/s wind for 2 s, with one fold line at 0.3 of the
  // width (1.2 rad): dense column 28.8, between the coarse columns 24 and 32.
  // The physics holds it as two coarse rest angles (at coarse columns 3 and 4);
  // the infill draws it as a ridge on its own line (crease_ridges.hpp).
  const auto run = [](bool folded) {
    std::vector<std::string> sets = {"flag.fine=[65,97]", "scene.duration=2.0",
                                     "bending.stiffness=1e-4", "creases.yield_angle=1.0"};
    if (folded) sets.emplace_back("flag.folds=[{axis=\"col\",at=0.3,angle=1.2}]");
    const auto flag = make_simulation(parse_scene(default_scene_toml(), kDefaultSceneName, sets));
    std::vector<std::vector<double>> frames;  // from frame 6 (0.2 s) on
    for (int frame = 1; frame <= 60; ++frame) {
      flag->advance_frame(nullptr);
      if (frame >= 6) frames.push_back(column_turning(flag->positions(), 65, 97));
    }
    return frames;
  };
  // Each column's median over frames [from, to) of its median turning, over the cloth's.
  const auto ratios = [](const std::vector<std::vector<double>>& frames, std::size_t from,
                         std::size_t to) {
    std::vector<double> per_column, all;
    for (std::size_t k = 0; k < frames[0].size(); ++k) {
      std::vector<double> over_time;
      for (std::size_t f = from; f < to; ++f) over_time.push_back(frames[f][k]);
      per_column.push_back(median(over_time));
    }
    const double cloth = median(per_column);
    for (double& r : per_column) r /= cloth;
    return per_column;
  };
  const std::vector<std::vector<double>> creased = run(true), plain = run(false);
  const std::vector<double> whole = ratios(creased, 0, creased.size());
  // The strongest line between the coarse columns 16 and 40 is the fold's
  // (columns 27-30: within 2 dense links), not a coarse column. Measured: 29, 2.3x the cloth.
  const auto strongest = std::max_element(whole.begin() + 15, whole.begin() + 40);
  const int column = int(strongest - whole.begin()) + 1;
  EXPECT_GE(column, 27);
  EXPECT_LE(column, 30);
  EXPECT_GT(*strongest, 2.0);
  // Most marked at first (0.2-0.7 s: 4.6x), less as the wind pulls (2.1x later:
  // the crease keeps its side, so the wind only flattens it). Measured
  // 2026-12-07; with the wind evaluated every substep 4.5x and 2.4x (the flap
  // is chaotic from about 0.5 s).
  const double early = ratios(creased, 0, 15)[28], late = ratios(creased, 15, creased.size())[28];
  EXPECT_GT(early, 4.0);
  EXPECT_LT(late, 0.8 * early);
  EXPECT_GT(late, 1.9);
  // Without the fold, nothing marks that column (measured 1.03x).
  EXPECT_LT(ratios(plain, 0, plain.size())[28], 1.3);
}

// scenes/infill/folded.toml: a 33 x 49 cloth folded in half by its corners in
// 1 s (the fold along the middle column, dense column 24), held 1.5 s,
// unfolded in 1 s, 5 s in all; `sets` override.
Scene folded_by_corners(std::vector<std::string> sets = {}) {
  return load_scene_file(std::string(FLAGSIM_SOURCE_DIR) + "/scenes/infill/folded.toml", sets);
}

TEST(Creases, InInfillModeAFoldTheCornersHoldSetsAndTheUnfoldedClothKeepsItsLine) {
  // The fold turns the rows by about 2.9 rad at column 24 while held; held
  // past the yield for 1.5 s (set_time 0.5 s) it sets. Unfolded (from 3.5 s),
  // the cloth is flat but for the crease: its line turns 0.24 rad (measured)
  // where the cloth's median turning is under 1e-4 rad, and it stays (nothing
  // pulls an infill-mode cloth flat). With the yield above the fold nothing
  // sets, and the frames are those of a cloth without [creases].
  const auto run = [](std::vector<std::string> sets) {
    const auto cloth = make_simulation(folded_by_corners(std::move(sets)));
    std::vector<std::vector<Vec3>> frames;
    for (int frame = 1; frame <= 150; ++frame) {
      cloth->advance_frame(nullptr);
      frames.emplace_back(cloth->positions().begin(), cloth->positions().end());
    }
    return std::pair{std::move(frames), cloth->state()};
  };
  const auto [creased, state] = run({});
  for (int frame = 106; frame <= 150; ++frame) {  // 3.53 s on: unfolded
    const std::vector<Vec3>& x = creased[std::size_t(frame - 1)];
    std::vector<double> per_column;
    std::vector<double> cloth;
    for (int k = 1; k < 48; ++k) {
      std::vector<double> column(33);
      for (int j = 0; j < 33; ++j) column[std::size_t(j)] = turning(x, 49, j, k, true);
      per_column.push_back(median(column));
      cloth.insert(cloth.end(), column.begin(), column.end());
    }
    const auto strongest = std::max_element(per_column.begin(), per_column.end());
    EXPECT_EQ(int(strongest - per_column.begin()) + 1, 24) << "frame " << frame;
    EXPECT_GT(*strongest, 0.2) << "frame " << frame;
    EXPECT_LT(median(cloth), 1e-3) << "frame " << frame;
  }
  // The crease the cloth keeps: the rows' rest angle at column 24, most of the
  // 2.89 rad fold (1.5 s held at set_time 0.5 s: 1 - e^-3 (1 + 3) of it, cascaded;
  // measured 2.43 rad).
  const std::size_t at = std::size_t(16) * 47 + 23;  // row 16's triple centred at column 24
  EXPECT_GT(std::abs(state.physics.memory[at]), 2.2);
  // With the yield above the fold: nothing sets, the same frames as without creases.
  const auto [under, under_state] = run({"creases.yield_angle=3.1"});
  for (std::size_t t = 0; t < state.physics.memory.size() / 2; ++t)
    EXPECT_EQ(under_state.physics.memory[t], 0.0) << t;
  const Scene without = [] {
    Scene scene = folded_by_corners();
    scene.creases.reset();
    scene.bending.reset();
    return scene;
  }();
  const auto cloth = make_simulation(without);
  for (int frame = 1; frame <= 150; ++frame) {
    cloth->advance_frame(nullptr);
    ASSERT_TRUE(std::equal(cloth->positions().begin(), cloth->positions().end(),
                           under[std::size_t(frame - 1)].begin()))
        << "frame " << frame;
  }
  // The state carries the creases and the lattice before its ridges: a run
  // continued from frame 120 goes on bit for bit.
  const auto first = make_simulation(folded_by_corners());
  for (int frame = 1; frame <= 120; ++frame) first->advance_frame(nullptr);
  const SimulationState at120 = first->state();
  const auto second = make_simulation(folded_by_corners());
  second->set_state(at120);
  for (int frame = 121; frame <= 130; ++frame) {
    first->advance_frame(nullptr);
    second->advance_frame(nullptr);
  }
  EXPECT_TRUE(std::equal(first->positions().begin(), first->positions().end(),
                         second->positions().begin()));
  EXPECT_EQ(first->state().physics.memory, second->state().physics.memory);
}

TEST(Creases, AStateCarriesTheCreasesAndGoesOnBitForBit) {
  for (const char* mode : {"mass-spring", "implicit", "xpbd", "bullet", "hybrid"}) {
    const Scene scene =
        folded_in_four({std::string("scene.mode=\"") + mode + "\"", "flag.coarse=[9,13]"});
    const auto first = make_simulation(scene);
    for (int f = 0; f < 3; ++f) first->advance_frame(nullptr);
    const SimulationState at3 = first->state();
    // Rest and held angles of every bending triple of the physics' lattice.
    const std::size_t rows = scene.mode == Mode::kHybrid ? 9 : 17,
                      cols = scene.mode == Mode::kHybrid ? 13 : 25;
    EXPECT_EQ(at3.physics.memory.size(), 2 * (rows * (cols - 2) + (rows - 2) * cols)) << mode;
    first->advance_frame(nullptr);
    const auto second = make_simulation(scene);
    second->set_state(at3);
    second->advance_frame(nullptr);
    EXPECT_TRUE(std::equal(first->positions().begin(), first->positions().end(),
                           second->positions().begin()))
        << mode;
    EXPECT_EQ(first->state().physics.memory, second->state().physics.memory) << mode;
    SimulationState wrong = at3;
    wrong.physics.memory.pop_back();
    EXPECT_THROW(second->set_state(wrong), UserError) << mode;
  }
}

}  // namespace
}  // namespace flagsim::sim
