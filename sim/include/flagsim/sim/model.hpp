#pragma once
// A scene compiled once into what every simulation of it reads and none
// changes, as MuJoCo's mjModel is to its mjData: the validated scene, the
// cloth's material, and the cloth of each lattice a simulation of it steps or
// writes. The state (sim::SimulationState) is what changes; the model never
// does, so simulations, threads and a restored state can share one.
//
//   const std::shared_ptr<const Model> model = Model::compile(scene);
//   std::unique_ptr<Simulation> a = make_simulation(model), b = make_simulation(model);
#include <memory>

#include "flagsim/coarse_physics/cloth_model.hpp"
#include "flagsim/scene/material.hpp"
#include "flagsim/scene/scene.hpp"

namespace flagsim::sim {

class Model {
 public:
  /// Checks `scene` as a file's is (check_scene: a Scene built in code is
  /// refused for what a file would be) and compiles it. Throws UserError.
  static std::shared_ptr<const Model> compile(const Scene& scene);

  /// The scene as compiled (a copy: the caller's may go first).
  const Scene& scene() const { return scene_; }
  /// The cloth's material (material_of(scene)), shared by the physics and the infill.
  const Material& material() const { return material_; }
  /// The cloth the physics integrates: flag.coarse's in hybrid mode, flag.fine's
  /// in the full-lattice modes; null in infill mode (no physics).
  const std::shared_ptr<const physics::ClothModel>& physics_cloth() const { return physics_; }
  /// The cloth of the lattice a run writes (flag.fine): its nodes' masses give
  /// the kinetic energy of every mode. The same object as physics_cloth() in the
  /// full-lattice modes.
  const physics::ClothModel& dense_cloth() const { return *dense_; }

 private:
  Model() = default;

  Scene scene_;
  Material material_;
  std::shared_ptr<const physics::ClothModel> physics_, dense_;
};

}  // namespace flagsim::sim
