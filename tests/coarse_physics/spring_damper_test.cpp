#include "flagsim/coarse_physics/spring_damper.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "finite_difference.hpp"
#include "flagsim/core/strain.hpp"
#include "flagsim/scene/scene_parser.hpp"
#include "scene_fixtures.hpp"
#include "tolerances.hpp"

namespace flagsim::physics {
namespace {

TEST(SpringDamper, EnergyIsConservedWithoutDampingOrWind) {
  // Released from a stretched, jiggled shape with gravity on: the energy that
  // moves (elastic -> kinetic -> gravitational) must stay within 1%.
  // Symplectic Euler is the staggered leapfrog: v is known at half steps, so
  // the energy at x_n is U(x_n) + 1/2 m v_{n-1/2} . v_{n+1/2}, which this
  // integrator keeps (exactly, for linear forces); 1/2 m v^2 with the
  // half-step v alone would wobble by O(omega dt) near the stability limit.
  Scene scene = test::small_cloth(7, 9);
  scene.gravity = Gravity{};
  SpringDamperSolver solver(scene);
  ClothState state = solver.initial_state();
  state.x_m = test::jiggled(solver.model().lattice, 0.005, 5);
  for (std::size_t i = 0; i < state.x_m.size(); ++i)
    if (solver.model().pinned[i]) state.x_m[i] = solver.model().lattice.rest_positions()[i];
  const std::vector<double>& mass = solver.model().mass_kg;
  double e0 = 0.0, largest_drift = 0.0, largest_kinetic = 0.0;
  for (int s = 0; s < 1000; ++s) {
    const double potential = solver.potential_energy(state);
    const std::vector<Vec3> v_before = state.v_m_s;
    solver.step(state, solver.substep_s(), nullptr);
    double kinetic = 0.0;
    for (std::size_t i = 0; i < mass.size(); ++i)
      kinetic += 0.5 * mass[i] * v_before[i].dot(state.v_m_s[i]);
    const double energy = potential + kinetic;
    if (s == 0) e0 = energy;
    largest_drift = std::max(largest_drift, std::abs(energy - e0));
    largest_kinetic = std::max(largest_kinetic, solver.kinetic_energy(state));
  }
  ASSERT_GT(largest_kinetic, 0.0);
  EXPECT_LT(largest_drift, test::kEnergyDriftRelTol * largest_kinetic)
      << "drift " << largest_drift << " J, kinetic up to " << largest_kinetic << " J";
}

TEST(SpringDamper, HangingClothComesToRest) {
  Scene scene = test::small_cloth(5, 7);
  scene.flag.pin = PinSet::kTop;
  scene.flag.damping_per_s = 2.0;
  scene.gravity = Gravity{};
  scene.fps = 10.0;
  SpringDamperSolver solver(scene);
  ClothState state = solver.initial_state();
  for (int frame = 0; frame < 200; ++frame) solver.advance_frame(state, nullptr);  // 20 s
  double fastest = 0.0;
  for (const Vec3& v : state.v_m_s) fastest = std::max(fastest, v.norm());
  EXPECT_LT(fastest, test::kRestSpeed_m_s);
  // At rest under its own weight: stretched a little, downward.
  const StrainStats strain = link_strain(solver.model().lattice, state.x_m);
  EXPECT_GT(strain.max, 0.0);
  EXPECT_LT(strain.max, 0.01);
  EXPECT_LT(state.x_m.back().y(), solver.model().lattice.rest_positions().back().y());
}

// Largest eigenvalue of M^-1 K at rest, by power iteration with K v from
// central differences of the forces (free nodes only).
double largest_omega2(SpringDamperSolver& solver) {
  const ClothModel& model = solver.model();
  const std::vector<Vec3> rest = model.lattice.rest_positions();
  std::vector<Vec3> v(rest.size(), Vec3::Zero()), dir = test::jiggled(model.lattice, 1.0, 9);
  for (std::size_t i = 0; i < dir.size(); ++i)
    dir[i] = model.pinned[i] ? Vec3::Zero() : Vec3(dir[i] - rest[i]);
  double lambda = 0.0;
  const double h = 1e-7;
  for (int it = 0; it < 400; ++it) {
    double norm = 0.0;
    for (const Vec3& d : dir) norm += d.squaredNorm();
    norm = std::sqrt(norm);
    for (Vec3& d : dir) d /= norm;
    std::vector<Vec3> plus = rest, minus = rest, fp(rest.size(), Vec3::Zero()), fm = fp;
    for (std::size_t i = 0; i < rest.size(); ++i) {
      plus[i] += h * dir[i];
      minus[i] -= h * dir[i];
    }
    for (const auto& term : solver.terms()) {
      term->add_forces(plus, v, fp);
      term->add_forces(minus, v, fm);
    }
    double rayleigh = 0.0;
    for (std::size_t i = 0; i < rest.size(); ++i) {
      const Vec3 kd =
          model.pinned[i] ? Vec3::Zero() : Vec3(-(fp[i] - fm[i]) / (2 * h) / model.mass_kg[i]);
      rayleigh += kd.dot(dir[i]);
      dir[i] = kd;
    }
    lambda = rayleigh;
  }
  return lambda;
}

TEST(SpringDamper, StabilityBoundHoldsAndIsNotFarOff) {
  Scene scene = test::small_cloth(6, 8);
  scene.bending = Bending{1e-3};
  SpringDamperSolver solver(scene);
  const double omega = std::sqrt(largest_omega2(solver));
  const double true_limit = 2.0 / omega;
  EXPECT_LE(solver.stable_substep_s(), true_limit * (1.0 + 1e-6));  // a bound: never above
  EXPECT_GT(solver.stable_substep_s(), 0.4 * true_limit);           // and not needlessly small
  EXPECT_LE(solver.substep_s(), kStabilitySafety * solver.stable_substep_s() * (1.0 + 1e-12));
}

TEST(SpringDamper, PastTheLimitItBlowsUp) {
  // The limit is real: stepping at 1.2x the true limit diverges, which the run
  // loop reports as "diverged" (tested end to end in app_tests).
  Scene scene = test::small_cloth(6, 8);
  SpringDamperSolver solver(scene);
  const double dt = 1.2 * 2.0 / std::sqrt(largest_omega2(solver));
  ClothState state = solver.initial_state();
  state.x_m = test::jiggled(solver.model().lattice, 1e-4, 11);
  for (int s = 0; s < 2000; ++s) solver.step(state, dt, nullptr);
  EXPECT_FALSE(link_strain(solver.model().lattice, state.x_m).max <= 1.0);  // > 100%, or NaN
}

TEST(SpringDamper, SubstepsIsAMinimum) {
  Scene scene = test::small_cloth(3, 3);
  scene.flag.stretch_modulus_n_m = 1.0;  // very soft: the limit alone would allow 1 substep
  scene.solver.substeps = 17;
  EXPECT_EQ(SpringDamperSolver(scene).substeps_per_frame(), 17);
}

TEST(SpringDamper, OnlyTheEffectsTheSceneCallsFor) {
  Scene scene = test::small_cloth(3, 3);
  EXPECT_EQ(SpringDamperSolver(scene).effects(), std::vector<std::string>{"stretch"});
  scene.wind = Wind{};
  scene.gravity = Gravity{};
  scene.bending = Bending{1e-4};
  scene.flag.damping_per_s = 0.5;
  scene.pole = PoleMotion{};
  const std::vector<std::string> all = {"stretch", "bending", "gravity", "wind", "damping", "pole"};
  EXPECT_EQ(SpringDamperSolver(scene).effects(), all);
}

// The default flag on the hybrid's 9 x 13 coarse lattice, in mass-spring mode.
Scene default_coarse_flag(const std::vector<std::string>& overrides) {
  std::vector<std::string> sets = {"scene.mode=\"mass-spring\"", "flag.fine=[9,13]"};
  sets.insert(sets.end(), overrides.begin(), overrides.end());
  return parse_scene(default_scene_toml(), kDefaultSceneName, sets);
}

double wind_rate_bound(const SpringDamperSolver& solver) {
  for (const auto& term : solver.terms())
    if (term->name() == "wind") return term->velocity_rate_bound();
  return 0.0;
}

TEST(SpringDamper, HoldsTheWindForATenthOfItsFastestResponse) {
  const SpringDamperSolver solver(default_coarse_flag({}));
  // 1.225 kg/m^3 (1.0 + 0.5 + 0.015) (10 + 10 m/s) / 0.2 kg/m^2 = 185.6 /s: 0.54 ms, and
  // the substep is 1 / (30 x 251) s.
  const double rate = wind_rate_bound(solver);
  EXPECT_NEAR(rate, 1.225 * 1.515 * 20.0 / 0.2, 1e-9);
  EXPECT_EQ(solver.hold_substeps(), int(std::floor(0.1 / rate / solver.substep_s())));
  EXPECT_EQ(solver.hold_substeps(), 4);
  EXPECT_EQ(SpringDamperSolver(default_coarse_flag({"solver.wind_hold=0.05"})).hold_substeps(), 2);
  EXPECT_EQ(SpringDamperSolver(default_coarse_flag({"solver.wind_hold=0"})).hold_substeps(), 1);
  // Twice the wind, half the hold; at 65 x 97 the substep is an eighth as long.
  EXPECT_EQ(
      SpringDamperSolver(default_coarse_flag({"wind.velocity=[20.0,0.0,0.0]"})).hold_substeps(), 2);
  const SpringDamperSolver fine(default_coarse_flag({"flag.fine=[65,97]"}));
  EXPECT_EQ(fine.hold_substeps(), int(std::floor(0.1 / rate / fine.substep_s())));
  EXPECT_GE(fine.hold_substeps(), 32);
  // A projection (a ground here) changes velocities within a substep: nothing held.
  EXPECT_EQ(SpringDamperSolver(default_coarse_flag({"ground.height=-2.0"})).hold_substeps(), 1);
  // Still air has no rate to hold the wind by, and gravity alone is not held.
  EXPECT_EQ(
      SpringDamperSolver(default_coarse_flag({"wind.velocity=[0.0,0.0,0.0]"})).hold_substeps(), 1);
}

// Positions after `frames` frames of `scene`.
std::vector<Vec3> positions_after(const Scene& scene, int frames) {
  SpringDamperSolver solver(scene);
  ClothState state = solver.initial_state();
  for (int frame = 0; frame < frames; ++frame) solver.advance_frame(state, nullptr);
  return state.x_m;
}

double rms_distance(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += (a[i] - b[i]).squaredNorm();
  return std::sqrt(sum / double(a.size()));
}

// Measured 2026-12-07: 0.57 um held over 4 substeps, 0.094 um over 2,
// against 6.6 mm RMS moved (9e-5); log2 of the ratio 2.6. The extrapolated
// hold is of second order (held plain, without the extrapolation: 11.5 and
// 3.8 um, order 1.6); a hold that is never refreshed, or refreshed every
// substep, fails one of the bounds.
constexpr double kHeldWindError = 1.5e-4, kHeldWindOrderLow = 1.8, kHeldWindOrderHigh = 3.4;

TEST(SpringDamper, TheHeldWindConvergesToTheWindOfEverySubstep) {
  // 0.2 s of the default flag blown out from its seeded start: the held
  // wind's run differs from every substep's by an error of second order in
  // the hold (4, then 2 substeps), small against how far the cloth moved.
  const int frames = 6;
  const std::vector<Vec3> start = SpringDamperSolver(default_coarse_flag({})).initial_state().x_m;
  const std::vector<Vec3> every =
      positions_after(default_coarse_flag({"solver.wind_hold=0"}), frames);
  const double d4 = rms_distance(positions_after(default_coarse_flag({}), frames), every);
  const double d2 =
      rms_distance(positions_after(default_coarse_flag({"solver.wind_hold=0.05"}), frames), every);
  const double moved = rms_distance(every, start);
  RecordProperty("d4_um", std::to_string(1e6 * d4));
  RecordProperty("d2_um", std::to_string(1e6 * d2));
  RecordProperty("moved_mm", std::to_string(1e3 * moved));
  EXPECT_GT(d4, 0.0);
  EXPECT_LT(d4, kHeldWindError * moved) << d4 << " m against " << moved << " m moved";
  const double order = std::log2(d4 / d2);
  EXPECT_GT(order, kHeldWindOrderLow) << d4 << " " << d2;
  EXPECT_LT(order, kHeldWindOrderHigh) << d4 << " " << d2;
}

TEST(SpringDamper, PinsFollowThePole) {
  Scene scene = test::small_cloth(3, 4);
  scene.pole = PoleMotion{Vec3::UnitY(), 0.1, 2.0};
  scene.fps = 8.0;  // t = 1/8 s: a quarter period of 2 Hz, the crest
  SpringDamperSolver solver(scene);
  ClothState state = solver.initial_state();
  solver.advance_frame(state, nullptr);
  const Lattice& lattice = solver.model().lattice;
  EXPECT_NEAR(state.x_m[lattice.index(1, 0)].y(), lattice.rest_position(1, 0).y() + 0.1,
              test::kRoundOff);
  EXPECT_NEAR(state.time_s, 1.0 / 8.0, test::kExact);
}

}  // namespace
}  // namespace flagsim::physics

namespace flagsim::physics {
namespace {

TEST(SpringDamper, DrivenNodesFollowTheirPath) {
  Scene scene = test::small_cloth(3, 4);
  scene.fps = 10.0;
  SpringDamperSolver solver(scene);
  ClothState state = solver.initial_state();
  const Vec3 start = state.x_m[5];
  solver.drive({5}, [&](std::size_t, double t) { return Vec3(start + Vec3(0.0, 0.0, 0.3 * t)); });
  solver.advance_frame(state, nullptr);
  EXPECT_NEAR((state.x_m[5] - (start + Vec3(0.0, 0.0, 0.03))).norm(), 0.0, test::kRoundOff);
  EXPECT_NEAR(state.v_m_s[5].z(), 0.3, test::kAccumulatedRoundOff);
  EXPECT_GT(std::abs(state.x_m[6].z()), 0.0);  // and pulls its neighbours along
}

}  // namespace
}  // namespace flagsim::physics
