#pragma once
// Gravity: f_i = m_i g, energy -sum_i m_i g . x_i.
#include <vector>

#include "flagsim/coarse_physics/force_term.hpp"

namespace flagsim::physics {

class GravityForce final : public ForceTerm {
 public:
  /// @param mass_kg   [J*K] node masses
  /// @param g_m_s2    acceleration of gravity
  GravityForce(const std::vector<double>& mass_kg, const Vec3& g_m_s2)
      : mass_kg_(mass_kg), g_m_s2_(g_m_s2) {}
  std::string_view name() const override { return "gravity"; }
  void add_forces(std::span<const Vec3> x_m, std::span<const Vec3> v_m_s,
                  std::span<Vec3> forces_n) const override;
  double energy(std::span<const Vec3> x_m) const override;
  ForceTiming timing() const override { return ForceTiming::kConstant; }

 private:
  const std::vector<double>& mass_kg_;
  Vec3 g_m_s2_;
};

}  // namespace flagsim::physics
