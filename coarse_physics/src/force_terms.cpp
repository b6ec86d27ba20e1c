#include "flagsim/coarse_physics/force_terms.hpp"

#include "flagsim/coarse_physics/aero_force.hpp"
#include "flagsim/coarse_physics/bending_springs.hpp"
#include "flagsim/coarse_physics/creased_bending.hpp"
#include "flagsim/coarse_physics/gravity_force.hpp"
#include "flagsim/coarse_physics/stretch_springs.hpp"

namespace flagsim::physics {

namespace {

using TermPtr = std::unique_ptr<ForceTerm>;

// Every effect of the physics, in pipeline order: the one place an effect is
// registered here (its keys are the scene's: scene_parser.cpp, scene_keys.cpp).
// `present` says whether a scene has it; `term` makes its force term (null:
// the effect is part of another's, or applied by every backend itself:
// gusts and turbulence ride on the wind, damping and pole motion on the model);
// `selected` is the TermSelection flag a backend can clear.
struct Effect {
  const char* name;
  bool (*present)(const Scene&, const ClothModel&);
  TermPtr (*term)(const Scene&, const ClothModel&);
  bool TermSelection::*selected;
};

// The wind's term. Speed bound for the stability estimate: the pole's speed plus
// the wind speed again for a flapping fly end (it can move about as fast as the
// wind). With the vortex lattice (vortex_wake.hpp, the spring-damper solver's
// own) the lift is the vortex lattice's; drag and friction stay here.
TermPtr wind_term(const Scene& scene, const ClothModel& model) {
  const double cloth_speed = model.pin_motion.max_speed_m_s() + scene.wind->velocity_m_s.norm();
  Wind wind = *scene.wind;
  if (wind.model == AirModel::kVortex) wind.lift = 0.0;
  return std::make_unique<AeroForce>(model, wind, scene.seed, model.material.areal_density_kg_m2,
                                     cloth_speed);
}

constexpr Effect kEffects[] = {
    {"stretch", [](const Scene&, const ClothModel&) { return true; },
     [](const Scene&, const ClothModel& model) -> TermPtr {
       return std::make_unique<StretchSprings>(model);
     },
     &TermSelection::stretch},
    {"bending",
     [](const Scene&, const ClothModel& model) {
       return model.material.bending_rigidity_j.has_value();
     },
     [](const Scene& scene, const ClothModel& model) -> TermPtr {
       if (TermPtr creased = make_creased_bending(scene, model)) return creased;
       return std::make_unique<BendingSprings>(model, *model.material.bending_rigidity_j);
     },
     &TermSelection::bending},
    // Part of the bending's term (creased_bending.hpp).
    {"creases", [](const Scene&, const ClothModel& model) { return model.material.creased(); },
     nullptr, nullptr},
    {"gravity", [](const Scene& scene, const ClothModel&) { return scene.gravity.has_value(); },
     [](const Scene& scene, const ClothModel& model) -> TermPtr {
       return std::make_unique<GravityForce>(model.mass_kg, scene.gravity->acceleration_m_s2);
     },
     &TermSelection::gravity},
    {"wind", [](const Scene& scene, const ClothModel&) { return scene.wind.has_value(); },
     wind_term, nullptr},
    {"gusts", [](const Scene& scene, const ClothModel&) { return scene.wind && scene.wind->gusts; },
     nullptr, nullptr},
    {"turbulence",
     [](const Scene& scene, const ClothModel&) { return scene.wind && scene.wind->turbulence; },
     nullptr, nullptr},
    {"damping",
     [](const Scene&, const ClothModel& model) { return model.material.damping_per_s > 0.0; },
     nullptr, nullptr},
    {"pole", [](const Scene& scene, const ClothModel&) { return scene.pole.has_value(); }, nullptr,
     nullptr},
    // Self-contact (self_contact.hpp): a projection after each step, not a force.
    {"contact", [](const Scene& scene, const ClothModel&) { return scene.contact.has_value(); },
     nullptr, nullptr},
};

}  // namespace

std::vector<std::unique_ptr<ForceTerm>> make_force_terms(const Scene& scene,
                                                         const ClothModel& model,
                                                         TermSelection selection) {
  std::vector<TermPtr> terms;
  for (const Effect& effect : kEffects)
    if (effect.term && (!effect.selected || selection.*effect.selected) &&
        effect.present(scene, model))
      terms.push_back(effect.term(scene, model));
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
  std::vector<std::string> effects;
  for (const Effect& effect : kEffects)
    if (effect.present(scene, model)) effects.emplace_back(effect.name);
  return effects;
}

}  // namespace flagsim::physics
