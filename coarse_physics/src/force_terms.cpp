#include "flagsim/coarse_physics/force_terms.hpp"

#include "flagsim/coarse_physics/aero_force.hpp"
#include "flagsim/coarse_physics/bending_springs.hpp"
#include "flagsim/coarse_physics/gravity_force.hpp"
#include "flagsim/coarse_physics/stretch_springs.hpp"

namespace flagsim::physics {

std::vector<std::unique_ptr<ForceTerm>> make_force_terms(const Scene& scene,
                                                         const ClothModel& model,
                                                         const PinMotion& pins,
                                                         TermSelection selection) {
  std::vector<std::unique_ptr<ForceTerm>> terms;
  if (selection.stretch) terms.push_back(std::make_unique<StretchSprings>(model));
  if (model.material.bending_rigidity_j && selection.bending)
    terms.push_back(std::make_unique<BendingSprings>(model, *model.material.bending_rigidity_j));
  if (scene.gravity && selection.gravity)
    terms.push_back(
        std::make_unique<GravityForce>(model.mass_kg, scene.gravity->acceleration_m_s2));
  if (scene.wind) {
    // Speed bound for the stability estimate: the pole's speed plus the wind
    // speed again for a flapping fly end (it can move about as fast as the wind).
    const double cloth_speed = pins.max_speed_m_s() + scene.wind->velocity_m_s.norm();
    // With the vortex lattice (vortex_wake.hpp, the spring-damper solver's own)
    // the lift is the vortex lattice's; drag and friction stay here.
    Wind wind = *scene.wind;
    if (wind.model == AirModel::kVortex) wind.lift = 0.0;
    terms.push_back(std::make_unique<AeroForce>(model, wind, scene.seed,
                                                model.material.areal_density_kg_m2, cloth_speed));
  }
  return terms;
}

std::vector<int> register_term_stages(const std::vector<std::unique_ptr<ForceTerm>>& terms,
                                      StageTimes& times) {
  std::vector<int> stages;
  stages.reserve(terms.size());
  for (const auto& term : terms) stages.push_back(times.add(std::string(term->name())));
  return stages;
}

std::vector<std::string> physics_effects(const Scene& scene, const ClothModel& model) {
  std::vector<std::string> effects = {"stretch"};
  if (model.material.bending_rigidity_j) effects.emplace_back("bending");
  if (scene.gravity) effects.emplace_back("gravity");
  if (scene.wind) effects.emplace_back("wind");
  if (scene.wind && scene.wind->gusts) effects.emplace_back("gusts");
  if (scene.wind && scene.wind->turbulence) effects.emplace_back("turbulence");
  if (model.material.damping_per_s > 0.0) effects.emplace_back("damping");
  if (scene.pole) effects.emplace_back("pole");
  return effects;
}

}  // namespace flagsim::physics
