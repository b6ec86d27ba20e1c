#include "flagsim/coarse_physics/bending_springs.hpp"

namespace flagsim::physics {

BendingSprings::BendingSprings(const ClothModel& model, double rigidity_j)
    : lattice_(model.lattice) {
  const double dx = lattice_.spacing_x_m, dy = lattice_.spacing_y_m;
  k_row_ = rigidity_j * dy / (dx * dx * dx);
  k_col_ = rigidity_j * dx / (dy * dy * dy);
}

// Calls visit(a, b, c, k_b) for every row and column triple.
template <typename Visit>
void BendingSprings::for_each_triple(Visit&& visit) const {
  const int rows = lattice_.rows, cols = lattice_.cols;
  for (int j = 0; j < rows; ++j) {
    const double k = (j == 0 || j == rows - 1) ? 0.5 * k_row_ : k_row_;
    for (int m = 1; m + 1 < cols; ++m)
      visit(lattice_.index(j, m - 1), lattice_.index(j, m), lattice_.index(j, m + 1), k);
  }
  for (int j = 1; j + 1 < rows; ++j) {
    for (int m = 0; m < cols; ++m) {
      const double k = (m == 0 || m == cols - 1) ? 0.5 * k_col_ : k_col_;
      visit(lattice_.index(j - 1, m), lattice_.index(j, m), lattice_.index(j + 1, m), k);
    }
  }
}

void BendingSprings::add_forces(std::span<const Vec3> x_m, std::span<const Vec3>,
                                std::span<Vec3> forces_n) const {
  for_each_triple([&](std::size_t a, std::size_t b, std::size_t c, double k) {
    // -dE/dx with E = 1/2 k |q|^2, q = x_a - 2 x_b + x_c.
    const Vec3 kq = k * (x_m[a] - 2.0 * x_m[b] + x_m[c]);
    forces_n[a] -= kq;
    forces_n[b] += 2.0 * kq;
    forces_n[c] -= kq;
  });
}

double BendingSprings::energy(std::span<const Vec3> x_m) const {
  double total = 0.0;
  for_each_triple([&](std::size_t a, std::size_t b, std::size_t c, double k) {
    total += 0.5 * k * (x_m[a] - 2.0 * x_m[b] + x_m[c]).squaredNorm();
  });
  return total;
}

void BendingSprings::add_stiffness_bound(std::span<double> row_sum_n_m) const {
  // Hessian k g g^T (x) I with g = (1, -2, 1): row sums 4k, 8k, 4k.
  for_each_triple([&](std::size_t a, std::size_t b, std::size_t c, double k) {
    row_sum_n_m[a] += 4.0 * k;
    row_sum_n_m[b] += 8.0 * k;
    row_sum_n_m[c] += 4.0 * k;
  });
}

}  // namespace flagsim::physics
