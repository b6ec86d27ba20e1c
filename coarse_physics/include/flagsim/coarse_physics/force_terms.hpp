#pragma once
// The pipeline of force terms a scene calls for, shared by every backend: a
// term is constructed only when the scene has its effect.
#include <memory>
#include <string>
#include <vector>

#include "flagsim/coarse_physics/cloth_model.hpp"
#include "flagsim/coarse_physics/force_term.hpp"
#include "flagsim/coarse_physics/pin_motion.hpp"
#include "flagsim/core/scene.hpp"

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
                                                         const PinMotion& pins,
                                                         TermSelection selection = {});

/// Effects of the scene's physics in pipeline order (root attribute `effects`):
/// stretch, bending, gravity, wind, gusts, turbulence, damping, pole.
std::vector<std::string> physics_effects(const Scene& scene, const ClothModel& model);

/// Largest stable substep of explicit integration under `terms`, s: 2 / omega_max
/// with omega_max^2 the largest block Gershgorin row sum over mass of a free
/// node, and at most 1 / rate for velocity-dependent terms; infinity if none bounds it.
double explicit_stability_limit(const ClothModel& model,
                                const std::vector<std::unique_ptr<ForceTerm>>& terms);

/// Substeps per frame of `frame_s`: enough for each to be at most
/// kStabilitySafety of `stable_substep_s`, and at least `minimum` (solver.substeps).
int substeps_per_frame(double frame_s, double stable_substep_s, int minimum);

}  // namespace flagsim::physics
