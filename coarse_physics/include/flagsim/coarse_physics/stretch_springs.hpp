#pragma once
// Structural (row, column) and shear (diagonal) springs of the cloth model.
// Energy per link: 1/2 k (|x_b - x_a| - S)^2; force on b: -k (|d| - S) d/|d|.
#include "flagsim/coarse_physics/cloth_model.hpp"
#include "flagsim/coarse_physics/force_term.hpp"

namespace flagsim::physics {

class StretchSprings final : public ForceTerm {
 public:
  explicit StretchSprings(const ClothModel& model) : model_(model) {}
  std::string_view name() const override { return "stretch"; }
  void add_forces(std::span<const Vec3> x_m, std::span<const Vec3> v_m_s,
                  std::span<Vec3> forces_n) const override;
  double energy(std::span<const Vec3> x_m) const override;
  void add_stiffness_bound(std::span<double> row_sum_n_m) const override;

 private:
  const ClothModel& model_;
};

}  // namespace flagsim::physics
