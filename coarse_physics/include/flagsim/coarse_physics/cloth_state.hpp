#pragma once
// The mutable state of a cloth, and the start every backend and the infill
// share.
#include <vector>

#include "flagsim/coarse_physics/cloth_model.hpp"
#include "flagsim/core/scene.hpp"
#include "flagsim/core/vec3.hpp"

namespace flagsim::physics {

/// Positions [J*K] m, velocities [J*K] m/s, time s.
struct ClothState {
  std::vector<Vec3> x_m;
  std::vector<Vec3> v_m_s;
  double time_s = 0.0;
};

/// The state at t = 0 of the cloth `model` of `scene` (its lattice may be the
/// scene's fine or coarse one): rest positions plus the scene's seeded
/// perturbation (smooth_perturbation, free nodes only), at rest but for the
/// pinned nodes, which move with the pole.
ClothState initial_state(const Scene& scene, const ClothModel& model);

}  // namespace flagsim::physics
