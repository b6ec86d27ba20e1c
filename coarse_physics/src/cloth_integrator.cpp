#include "flagsim/coarse_physics/cloth_integrator.hpp"

#include "flagsim/coarse_physics/bullet_cloth.hpp"
#include "flagsim/coarse_physics/implicit_euler.hpp"
#include "flagsim/coarse_physics/xpbd.hpp"

namespace flagsim::physics {

double ClothIntegrator::kinetic_energy() const {
  return kinetic_energy_j(model().mass_kg, state().v_m_s);
}

std::optional<WindField::Drift> ClothIntegrator::wind_drift() const {
  for (const std::unique_ptr<ForceTerm>& term : force_terms())
    if (const WindField* field = term->wind_field()) return field->drift();
  return std::nullopt;
}

bool ClothIntegrator::set_wind_drift(const WindField::Drift& drift) {
  const ClothState& s = state();
  for (const std::unique_ptr<ForceTerm>& term : force_terms())
    if (term->set_wind_drift(drift, s.time_s, s.x_m)) return true;
  return false;
}

std::unique_ptr<ClothIntegrator> make_integrator(const Scene& scene,
                                                 std::shared_ptr<const ClothModel> model) {
  switch (scene.solver.backend) {
    case Backend::kBullet:
      return std::make_unique<BulletCloth>(scene, std::move(model));
    case Backend::kImplicit:
      return std::make_unique<ImplicitEuler>(scene, std::move(model));
    case Backend::kXpbd:
      return std::make_unique<Xpbd>(scene, std::move(model));
    case Backend::kSpringDamper:
      break;
  }
  return std::make_unique<SpringDamperIntegrator>(scene, std::move(model));
}

std::unique_ptr<ClothIntegrator> make_integrator(const Scene& scene) {
  return make_integrator(scene, std::make_shared<const ClothModel>(make_cloth_model(scene)));
}

}  // namespace flagsim::physics
