#pragma once
// Divergence detection: a blown-up simulation is a result (status "diverged"),
// reported with the reason and what to change, never garbage in the output.
#include <optional>
#include <span>
#include <string>

#include "flagsim/core/strain.hpp"
#include "flagsim/scene/scene.hpp"

namespace flagsim {

/// Why the state of a frame cannot be trusted, or nullopt when it can:
/// a non-finite position or velocity, a link strain above limits.max_strain,
/// or a node faster than limits.max_speed (an energy blow-up).
/// positions_m, velocities_m_s: [J*K]; strain: link_strain() of the positions.
std::optional<std::string> divergence_reason(std::span<const Vec3> positions_m,
                                             std::span<const Vec3> velocities_m_s,
                                             const StrainStats& strain, const Limits& limits);

}  // namespace flagsim
