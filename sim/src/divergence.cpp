#include "flagsim/sim/divergence.hpp"

#include <fmt/format.h>

#include <cmath>

namespace flagsim {

std::optional<Divergence> find_divergence(std::span<const Vec3> positions_m,
                                          std::span<const Vec3> velocities_m_s,
                                          const StrainStats& strain, const Limits& limits) {
  using Cause = Divergence::Cause;
  double max_speed2 = 0.0;
  for (const Vec3& x : positions_m)
    if (!x.allFinite()) return Divergence{Cause::kPositionNotFinite, 0.0, 0.0, {}};
  for (const Vec3& v : velocities_m_s) {
    if (!v.allFinite()) return Divergence{Cause::kVelocityNotFinite, 0.0, 0.0, {}};
    max_speed2 = std::max(max_speed2, v.squaredNorm());
  }
  if (!(strain.max <= limits.max_strain))
    return Divergence{Cause::kStrain, strain.max, limits.max_strain, {}};
  const double max_speed = std::sqrt(max_speed2);
  if (max_speed > limits.max_speed_m_s)
    return Divergence{Cause::kSpeed, max_speed, limits.max_speed_m_s, {}};
  return std::nullopt;
}

std::string describe(const physics::SolverNote& note) {
  using Kind = physics::SolverNote::Kind;
  switch (note.kind) {
    case Kind::kCgNotConverged:
      return fmt::format(
          "implicit Euler: the linear solve did not converge at t = {:.4g} s in a step of {:.3g} s "
          "(relative residual {:.2g} after {} conjugate-gradient iterations, tolerance {:.0e}): "
          "raise solver.substeps (now {}) for shorter steps, which it solves in fewer iterations",
          note.time_s, note.step_s, note.residual, note.cg_iterations, note.tolerance,
          note.substeps);
    case Kind::kCholeskyFailed:
      return fmt::format(
          "implicit Euler: the sparse Cholesky factorisation failed at t = {:.4g} s (the system "
          "is not positive definite: a non-finite state?); use solver.linear = \"cg\" or raise "
          "solver.substeps (now {})",
          note.time_s, note.substeps);
    case Kind::kXpbdSubstep:
      return fmt::format(
          "XPBD's links stretch more the longer its substep: raise solver.substeps (now {} a "
          "frame) or solver.iterations (now {})",
          note.substeps, note.iterations);
    case Kind::kImplicitLinearization:
      return fmt::format(
          "implicit Euler linearizes each step once per Newton iteration: raise solver.substeps "
          "(now {}) or solver.iterations (now {})",
          note.substeps, note.iterations);
  }
  return {};
}

std::string describe(const Divergence& divergence, const Scene& scene) {
  using Cause = Divergence::Cause;
  // What the physics backend adds to the causes it can be behind.
  const auto with_advice = [&](std::string text) {
    if (divergence.solver) text += "; " + describe(*divergence.solver);
    return text;
  };
  switch (divergence.cause) {
    case Cause::kPhysicsFailure:
      return divergence.solver ? describe(*divergence.solver) : std::string("the physics failed");
    case Cause::kPositionNotFinite:
      return with_advice("a node position became NaN or infinite");
    case Cause::kVelocityNotFinite:
      return with_advice("a node velocity became NaN or infinite");
    case Cause::kStrain:
      return with_advice(fmt::format(
          "max link strain {:.3g} exceeds limits.max_strain = {:.3g}; raise flag.stretch_modulus, "
          "lower the loads, or raise the limit if this much stretch is intended",
          divergence.value, divergence.limit));
    case Cause::kSpeed:
      return with_advice(fmt::format(
          "a node moves at {:.3g} m/s, above limits.max_speed = {:.3g} m/s (energy blow-up); "
          "raise solver.substeps or flag.damping",
          divergence.value, divergence.limit));
    case Cause::kKeyframeSpeed:
      return fmt::format(
          "a node moves at {:.3g} m/s, above limits.max_speed = {:.3g} m/s: the keyframes move "
          "the corners that fast; space them further apart in time or raise limits.max_speed",
          divergence.value, divergence.limit);
    case Cause::kInfillUnconverged: {
      const bool paper = infill_solver_of(scene) == InfillSolverKind::kPaper;
      return fmt::format(
          "max link strain {:.3g} exceeds limits.max_strain = {:.3g}, and the infill ({} solver) "
          "did not reach its tolerance in this frame: the infill failed, not the cloth; {}",
          divergence.value, divergence.limit, paper ? "paper" : "smooth",
          paper ? fmt::format("raise infill.relax_iterations (now {}), use [infill] solver = "
                              "\"smooth\", or give it smaller cells (flag.coarse)",
                              paper_relax_sweeps_of(scene))
                : std::string("give it smaller cells (flag.coarse) or a gentler coarse motion"));
    }
  }
  return {};
}

}  // namespace flagsim
