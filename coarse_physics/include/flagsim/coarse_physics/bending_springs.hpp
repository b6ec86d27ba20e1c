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
#include <cstdint>
#include <vector>

#include "flagsim/coarse_physics/cloth_model.hpp"
#include "flagsim/coarse_physics/force_term.hpp"

namespace flagsim::physics {

/// One bending triple (a, b, c) of consecutive nodes of a row or column, and its k_b, N/m.
struct BendingTriple {
  std::uint32_t a = 0, b = 0, c = 0;
  double k_n_m = 0.0;
};

/// Every row triple (row by row), then every column triple, of `lattice` for
/// rigidity D = `rigidity_j` N m (k_b as above, halved on the border fibers).
std::vector<BendingTriple> bending_triples(const Lattice& lattice, double rigidity_j);

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
  /// The Hessian is constant: k (1, -2, 1)^T (1, -2, 1) (x) I per triple.
  void add_stiffness_product(std::span<const Vec3> dx_m, std::span<Vec3> out_n) const override;
  void add_stiffness_diagonal(std::span<Mat3> diagonal_n_m) const override;

 private:
  std::vector<BendingTriple> triples_;
};

}  // namespace flagsim::physics
