#pragma once
// Divergence detection: a blown-up simulation is a result (status "diverged"),
// reported with the reason and what to change, never garbage in the output.
// The reason is data (Divergence: a cause and its numbers), which a program
// branches on; describe() turns it into the words the command line and Python
// print.
#include <optional>
#include <span>
#include <string>

#include "flagsim/coarse_physics/solver_note.hpp"
#include "flagsim/core/strain.hpp"
#include "flagsim/scene/scene.hpp"

namespace flagsim {

/// Why the state of a frame cannot be trusted.
struct Divergence {
  enum class Cause {
    kPhysicsFailure,     ///< the physics backend gave up (solver: its account)
    kPositionNotFinite,  ///< a node position became NaN or infinite
    kVelocityNotFinite,  ///< a node velocity became NaN or infinite
    kStrain,             ///< value: the largest link strain, over limit (limits.max_strain)
    kSpeed,              ///< value: the fastest node, m/s, over limit (limits.max_speed)
    kKeyframeSpeed,      ///< infill mode: the keyframes move a node faster than limit, m/s
    kInfillUnconverged,  ///< value: the strain over limit in a frame the infill did not converge
  };
  Cause cause = Cause::kStrain;
  double value = 0.0;
  double limit = 0.0;
  /// kPhysicsFailure: the backend's account; otherwise what the physics backend
  /// adds for the causes it can be behind (ClothIntegrator::divergence_advice), or nullopt.
  std::optional<physics::SolverNote> solver;
};

/// Why the state of a frame cannot be trusted, or nullopt when it can: a
/// non-finite position or velocity, a link strain above limits.max_strain, or a
/// node faster than limits.max_speed (an energy blow-up), in that order.
/// positions_m, velocities_m_s: [J*K]; strain: link_strain() of the positions.
std::optional<Divergence> find_divergence(std::span<const Vec3> positions_m,
                                          std::span<const Vec3> velocities_m_s,
                                          const StrainStats& strain, const Limits& limits);

/// The words for a backend's note: what happened or helps, and what to change.
std::string describe(const physics::SolverNote& note);

/// The words for `divergence` of a run of `scene` (one clause, what happened
/// and what to change), as `flag-sim run` prints them after "diverged at t = ...".
std::string describe(const Divergence& divergence, const Scene& scene);

}  // namespace flagsim
