#include "flagsim/sim/divergence.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "flagsim/core/lanes.hpp"

// Lanes (core/lanes.hpp) are passed by value only between inlined helpers of this
// file, never across an ABI boundary.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace flagsim {
namespace {

using lanes::Lanes;

// Whether every coordinate of `vectors` is finite: x * 0 is 0 for a finite
// x, NaN for an infinite or NaN one; four coordinates at a time, no branch.
FLAGSIM_LANES_CLONES bool all_finite(std::span<const Vec3> vectors) {
  constexpr int L = lanes::kWidth;
  if (vectors.empty()) return true;
  const double* values = vectors.data()->data();
  const std::size_t n = 3 * vectors.size();
  const Lanes zero = lanes::splat(0.0);
  auto bad = zero != zero;  // all false
  std::size_t i = 0;
  for (; i + L <= n; i += L) bad |= (lanes::load(values + i) * zero) != zero;
  bool any = false;
  for (int l = 0; l < L; ++l) any = any || bad[l] != 0;
  for (; i < n; ++i) any = any || !std::isfinite(values[i]);
  return !any;
}

// The largest |v|^2 (Vec3::squaredNorm's operations), four vectors at a time.
FLAGSIM_LANES_CLONES double largest_squared_norm(std::span<const Vec3> vectors) {
  constexpr int L = lanes::kWidth;
  const std::size_t n = vectors.size();
  Lanes largest = lanes::splat(0.0);
  std::size_t i = 0;
  for (; i + L <= n; i += L) {
    const Lanes norm2 = lanes::squared_norms(vectors.data() + i);
    largest = norm2 > largest ? norm2 : largest;
  }
  double result = 0.0;
  for (int l = 0; l < L; ++l) result = std::max(result, largest[l]);
  for (; i < n; ++i) result = std::max(result, vectors[i].squaredNorm());
  return result;
}

}  // namespace

std::optional<Divergence> find_divergence(std::span<const Vec3> positions_m,
                                          std::span<const Vec3> velocities_m_s,
                                          const StrainStats& strain, const Limits& limits) {
  using Cause = Divergence::Cause;
  if (!all_finite(positions_m)) return Divergence{Cause::kPositionNotFinite, 0.0, 0.0, {}};
  if (!all_finite(velocities_m_s)) return Divergence{Cause::kVelocityNotFinite, 0.0, 0.0, {}};
  const double max_speed2 = largest_squared_norm(velocities_m_s);
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
