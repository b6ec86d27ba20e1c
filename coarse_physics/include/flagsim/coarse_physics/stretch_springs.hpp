#pragma once
// Structural (row, column) and shear (diagonal) springs of the cloth model.
// Energy per link: 1/2 k (|x_b - x_a| - S)^2; force on b: -k (|d| - S) d/|d|.
//
// Hessian of one link, with d = x_b - x_a, l = |d|, n = d/l:
//   H = k [ n n^T + (1 - S/l) (I - n n^T) ],   d^2E/dx_a^2 = d^2E/dx_b^2 = H,
//   d^2E/dx_a dx_b = -H.
// A compressed link (l < S) has a negative transverse part (it buckles);
// Definiteness::kProjected drops it.
#include <cstdint>
#include <vector>

#include "flagsim/coarse_physics/cloth_model.hpp"
#include "flagsim/coarse_physics/force_term.hpp"

namespace flagsim::physics {

class StretchSprings final : public ForceTerm {
 public:
  explicit StretchSprings(const ClothModel& model);
  std::string_view name() const override { return "stretch"; }
  void add_forces(std::span<const Vec3> x_m, std::span<const Vec3> v_m_s,
                  std::span<Vec3> forces_n) const override;
  double energy(std::span<const Vec3> x_m) const override;
  void add_stiffness_bound(std::span<double> row_sum_n_m) const override;
  void linearize(std::span<const Vec3> x_m, std::span<const Vec3> v_m_s, Definiteness how) override;
  void add_stiffness_product(std::span<const Vec3> dx_m, std::span<Vec3> out_n) const override;
  void add_stiffness_diagonal(std::span<Mat3> diagonal_n_m) const override;

 private:
  const ClothModel& model_;
  struct Link {
    std::uint32_t a = 0, b = 0;
  };
  std::vector<Link> links_;    ///< every link of every family, in for_each_link order
  std::vector<Mat3> hessian_;  ///< [links] H at the last linearization, N/m
};

}  // namespace flagsim::physics
