#include "flagsim/coarse_physics/gravity_force.hpp"

namespace flagsim::physics {

void GravityForce::add_forces(std::span<const Vec3>, std::span<const Vec3>,
                              std::span<Vec3> forces_n) const {
  for (std::size_t i = 0; i < forces_n.size(); ++i) forces_n[i] += mass_kg_[i] * g_m_s2_;
}

double GravityForce::energy(std::span<const Vec3> x_m) const {
  double total = 0.0;
  for (std::size_t i = 0; i < x_m.size(); ++i) total -= mass_kg_[i] * g_m_s2_.dot(x_m[i]);
  return total;
}

}  // namespace flagsim::physics
