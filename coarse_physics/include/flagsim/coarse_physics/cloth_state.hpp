#pragma once
// The mutable state of a cloth, and the start every backend and the infill
// share.
#include <memory>
#include <vector>

#include "flagsim/coarse_physics/cloth_model.hpp"
#include "flagsim/coarse_physics/force_term.hpp"
#include "flagsim/core/stop_request.hpp"
#include "flagsim/core/vec3.hpp"
#include "flagsim/scene/scene.hpp"

namespace flagsim::physics {

/// Positions [J*K] m, velocities [J*K] m/s, time s, and the force terms' memory.
struct ClothState {
  std::vector<Vec3> x_m;
  std::vector<Vec3> v_m_s;
  double time_s = 0.0;
  /// Every force term's memory (ForceTerm::memory), in pipeline order: the
  /// crease rest angles, rad, with [creases]; empty otherwise.
  std::vector<double> memory = {};
};

/// The state at t = 0 of the cloth `model` of `scene` (its lattice may be the
/// scene's fine or coarse one): rest positions plus the scene's seeded
/// perturbation (smooth_perturbation, free nodes only), at rest but for the
/// pinned nodes, which move with the pole.
ClothState initial_state(const Scene& scene, const ClothModel& model);

/// The frame's start every stepper shares: the terms' memory set from the
/// state's, their begin_frame (which may move the memory: a crease's plastic
/// step), and the memory copied back into the state.
void begin_frame(const std::vector<std::unique_ptr<ForceTerm>>& terms, ClothState& state);

/// One output frame of `substeps` substeps of `dt_s`, the loop every stepper
/// shares: begin_frame (above) at the frame's start, then step(dt_s) while
/// it returns true and no stop was requested (stop_request.hpp); the time is
/// start + (s + 1) dt after substep s, so frames land exactly on t = n / fps.
template <typename Step>
void advance_substeps(const std::vector<std::unique_ptr<ForceTerm>>& terms, ClothState& state,
                      int substeps, double dt_s, Step&& step);

template <typename Step>
void advance_substeps(const std::vector<std::unique_ptr<ForceTerm>>& terms, ClothState& state,
                      int substeps, double dt_s, Step&& step) {
  const double start = state.time_s;
  begin_frame(terms, state);
  for (int s = 0; s < substeps && !stop_requested(); ++s) {
    const bool go_on = step(dt_s);
    state.time_s = start + (s + 1) * dt_s;
    if (!go_on) break;
  }
}

}  // namespace flagsim::physics
