#pragma once
// The pipeline of force terms a scene calls for, shared by every backend: a
// term is constructed only when the scene has its effect.
#include <memory>
#include <string>
#include <vector>

#include "flagsim/coarse_physics/cloth_model.hpp"
#include "flagsim/coarse_physics/force_term.hpp"
#include "flagsim/coarse_physics/pin_motion.hpp"
#include "flagsim/coarse_physics/stability.hpp"
#include "flagsim/core/stage_times.hpp"
#include "flagsim/scene/scene.hpp"

namespace flagsim::physics {

/// Which terms the caller applies as forces; a backend that models an effect
/// itself (Bullet's links for stretch, its world gravity) leaves it out.
struct TermSelection {
  bool stretch = true;
  bool bending = true;
  bool gravity = true;
};

/// Stretch, bending, gravity, wind, in that order, as far as selected and called for.
std::vector<std::unique_ptr<ForceTerm>> make_force_terms(const Scene& scene,
                                                         const ClothModel& model,
                                                         TermSelection selection = {});

/// One timing column per term, named after it, in pipeline order; returns their indices.
std::vector<int> register_term_stages(const std::vector<std::unique_ptr<ForceTerm>>& terms,
                                      StageTimes& times);

/// Effects of the scene's physics in pipeline order (root attribute `effects`):
/// stretch, bending, gravity, wind, gusts, turbulence, damping, pole.
std::vector<std::string> physics_effects(const Scene& scene, const ClothModel& model);

}  // namespace flagsim::physics
