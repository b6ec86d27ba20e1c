#pragma once
// Bending of the coarse physics ([bending] stiffness = D, N m), on every three
// consecutive nodes (a, b, c) of a row or a column:
//
//   E = 1/2 k_b |x_a - 2 x_b + x_c|^2,   k_b = D * w / s^3
//
// where s is the spacing along the fiber and w the width of cloth the fiber
// stands for (the other spacing, halved on the border). For small angles
// |x_a - 2 x_b + x_c| = curvature * s^2, so E = 1/2 D curvature^2 * (s w): the
// continuum bending energy of the cloth the triple covers, at any resolution.
// The energy is quadratic in x, so its stiffness is exact and constant.
#include "flagsim/coarse_physics/cloth_model.hpp"
#include "flagsim/coarse_physics/force_term.hpp"

namespace flagsim::physics {

class BendingSprings final : public ForceTerm {
 public:
  /// @param rigidity_j  D, N m (= J): moment per unit width per unit curvature ([bending]
  /// stiffness)
  BendingSprings(const ClothModel& model, double rigidity_j);
  std::string_view name() const override { return "bending"; }
  void add_forces(std::span<const Vec3> x_m, std::span<const Vec3> v_m_s,
                  std::span<Vec3> forces_n) const override;
  double energy(std::span<const Vec3> x_m) const override;
  void add_stiffness_bound(std::span<double> row_sum_n_m) const override;

 private:
  template <typename Visit>
  void for_each_triple(Visit&& visit) const;

  const Lattice& lattice_;
  double k_row_ = 0.0;  ///< k_b of an interior row triple, N/m
  double k_col_ = 0.0;  ///< k_b of an interior column triple, N/m
};

}  // namespace flagsim::physics
