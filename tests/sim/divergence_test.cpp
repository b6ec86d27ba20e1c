#include "flagsim/sim/divergence.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "flagsim/scene/scene_parser.hpp"

namespace flagsim {
namespace {

using Cause = Divergence::Cause;

TEST(Divergence, HealthyStatePasses) {
  const std::vector<Vec3> x(4, Vec3(1, 2, 3)), v(4, Vec3(0.5, 0, 0));
  EXPECT_FALSE(find_divergence(x, v, {0.01, 0.005}, Limits{}).has_value());
}

TEST(Divergence, FindsANonFiniteValueAndTheFastestNodeInTheLanesAndTheirTail) {
  // Five vectors: 15 coordinates, four lanes of four and a tail of three.
  std::vector<Vec3> x(5, Vec3(1, 2, 3)), v(5, Vec3(0.5, 0, 0));
  for (int at = 0; at < 15; ++at) {
    for (std::vector<Vec3>* field : {&x, &v}) {
      const Vec3 kept = (*field)[std::size_t(at / 3)];
      (*field)[std::size_t(at / 3)][at % 3] = at % 2 ? INFINITY : std::nan("");
      const std::optional<Divergence> found = find_divergence(x, v, {}, Limits{});
      ASSERT_TRUE(found) << at;
      EXPECT_EQ(found->cause, field == &x ? Cause::kPositionNotFinite : Cause::kVelocityNotFinite)
          << at;
      (*field)[std::size_t(at / 3)] = kept;
    }
  }
  Limits limits;
  limits.max_speed_m_s = 50.0;
  for (std::size_t fastest = 0; fastest < v.size(); ++fastest) {
    v[fastest] = Vec3(36.0, -48.0, 0.0);  // 60 m/s
    const std::optional<Divergence> found = find_divergence(x, v, {}, limits);
    ASSERT_TRUE(found) << fastest;
    EXPECT_EQ(found->cause, Cause::kSpeed);
    EXPECT_EQ(found->value, 60.0);
    v[fastest] = Vec3(0.5, 0, 0);
  }
}

TEST(Divergence, NamesEachCauseWithItsNumbersAndWordsThatSayWhatToChange) {
  std::vector<Vec3> x(4, Vec3::Zero()), v(4, Vec3::Zero());
  Scene scene = parse_scene(default_scene_toml(), kDefaultSceneName, std::vector<std::string>{});
  scene.limits.max_strain = 0.1;
  scene.limits.max_speed_m_s = 50.0;
  const Limits& limits = scene.limits;
  const auto words = [&](const Divergence& d) { return describe(d, scene); };
  x[2].z() = INFINITY;
  std::optional<Divergence> found = find_divergence(x, v, {}, limits);
  ASSERT_TRUE(found);
  EXPECT_EQ(found->cause, Cause::kPositionNotFinite);
  EXPECT_EQ(words(*found), "a node position became NaN or infinite");
  x[2].z() = 0.0;
  v[1].x() = std::nan("");
  found = find_divergence(x, v, {}, limits);
  ASSERT_TRUE(found);
  EXPECT_EQ(found->cause, Cause::kVelocityNotFinite);
  EXPECT_EQ(words(*found), "a node velocity became NaN or infinite");
  v[1].x() = 60.0;
  found = find_divergence(x, v, {}, limits);
  ASSERT_TRUE(found);
  EXPECT_EQ(found->cause, Cause::kSpeed);
  EXPECT_EQ(found->value, 60.0);
  EXPECT_EQ(found->limit, 50.0);
  EXPECT_EQ(words(*found),
            "a node moves at 60 m/s, above limits.max_speed = 50 m/s (energy blow-up); raise "
            "solver.substeps or flag.damping");
  v[1].x() = 0.0;
  found = find_divergence(x, v, {0.2, 0.1}, limits);
  ASSERT_TRUE(found);
  EXPECT_EQ(found->cause, Cause::kStrain);
  EXPECT_EQ(found->value, 0.2);
  EXPECT_EQ(words(*found),
            "max link strain 0.2 exceeds limits.max_strain = 0.1; raise flag.stretch_modulus, "
            "lower the loads, or raise the limit if this much stretch is intended");
  // A strain that is not a number is past any limit.
  found = find_divergence(x, v, {std::nan(""), 0.0}, limits);
  ASSERT_TRUE(found);
  EXPECT_EQ(found->cause, Cause::kStrain);
  // What the physics backend adds follows its cause, worded from its numbers;
  // its own failure is its words alone.
  using Note = physics::SolverNote;
  found->solver = Note{.kind = Note::Kind::kXpbdSubstep, .substeps = 7, .iterations = 1};
  EXPECT_NE(
      words(*found).find("intended; XPBD's links stretch more the longer its substep: "
                         "raise solver.substeps (now 7 a frame) or solver.iterations (now 1)"),
      std::string::npos);
  found->solver = Note{.kind = Note::Kind::kImplicitLinearization, .substeps = 3, .iterations = 2};
  EXPECT_NE(words(*found).find("implicit Euler linearizes each step once per Newton iteration: "
                               "raise solver.substeps (now 3) or solver.iterations (now 2)"),
            std::string::npos);
  EXPECT_EQ(words({Cause::kPhysicsFailure, 0.0, 0.0,
                   Note{.kind = Note::Kind::kCgNotConverged,
                        .substeps = 1,
                        .cg_iterations = 400,
                        .time_s = 2.0,
                        .step_s = 0.03125,
                        .residual = 0.012,
                        .tolerance = 1e-6}}),
            "implicit Euler: the linear solve did not converge at t = 2 s in a step of 0.0312 s "
            "(relative residual 0.012 after 400 conjugate-gradient iterations, tolerance 1e-06): "
            "raise solver.substeps (now 1) for shorter steps, which it solves in fewer iterations");
  EXPECT_EQ(words({Cause::kPhysicsFailure, 0.0, 0.0,
                   Note{.kind = Note::Kind::kCholeskyFailed, .substeps = 4, .time_s = 0.5}}),
            "implicit Euler: the sparse Cholesky factorisation failed at t = 0.5 s (the system is "
            "not positive definite: a non-finite state?); use solver.linear = \"cg\" or raise "
            "solver.substeps (now 4)");
  // The infill's failure names the solver and its knob.
  EXPECT_NE(words({Cause::kInfillUnconverged, 0.2, 0.1, {}})
                .find("the infill (smooth solver) did not reach its tolerance"),
            std::string::npos);
  scene.infill = InfillSettings{};
  scene.infill->solver = InfillSolverKind::kPaper;
  EXPECT_NE(words({Cause::kInfillUnconverged, 0.2, 0.1, {}}).find("raise infill.relax_iterations"),
            std::string::npos);
}

}  // namespace
}  // namespace flagsim
