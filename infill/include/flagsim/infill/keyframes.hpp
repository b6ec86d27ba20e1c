#pragma once
// Corner motion of the infill mode (paper Figs. 9-10): [[keyframe]] corner
// positions, linear in time between keyframes, held before the first and after
// the last.
#include <array>
#include <span>

#include "flagsim/scene/scene.hpp"

namespace flagsim::infill {

/// The four corners at time t, in the contract's order. keyframes: non-empty,
/// increasing in time (checked by the scene).
std::array<Vec3, 4> corners_at(std::span<const Keyframe> keyframes, double time_s);

}  // namespace flagsim::infill
