#include "flagsim/sim/model.hpp"

namespace flagsim::sim {

std::shared_ptr<const Model> Model::compile(const Scene& scene) {
  check_scene(scene);
  std::shared_ptr<Model> model(new Model());
  model->scene_ = scene;
  model->material_ = material_of(scene);
  const Material& material = model->material_;
  model->dense_ = std::make_shared<const physics::ClothModel>(
      physics::make_cloth_model(material, scene.fine_lattice(), scene.flag.pin, scene.pole));
  if (scene.mode == Mode::kHybrid)
    model->physics_ = std::make_shared<const physics::ClothModel>(physics::make_cloth_model(
        material, on_coarse_lattice(scene).fine_lattice(), scene.flag.pin, scene.pole));
  else if (is_full_lattice(scene.mode))
    model->physics_ = model->dense_;
  return model;
}

}  // namespace flagsim::sim
