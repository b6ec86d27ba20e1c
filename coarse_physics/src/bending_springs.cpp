#include "flagsim/coarse_physics/bending_springs.hpp"

namespace flagsim::physics {

std::vector<BendingTriple> bending_triples(const Lattice& lattice, double rigidity_j) {
  const double dx = lattice.spacing_x_m, dy = lattice.spacing_y_m;
  const double k_row = rigidity_j * dy / (dx * dx * dx);
  const double k_col = rigidity_j * dx / (dy * dy * dy);
  const int rows = lattice.rows, cols = lattice.cols;
  auto at = [&](int j, int k) { return std::uint32_t(lattice.index(j, k)); };
  std::vector<BendingTriple> triples;
  for (int j = 0; j < rows; ++j) {
    const double k = (j == 0 || j == rows - 1) ? 0.5 * k_row : k_row;
    for (int m = 1; m + 1 < cols; ++m) triples.push_back({at(j, m - 1), at(j, m), at(j, m + 1), k});
  }
  for (int j = 1; j + 1 < rows; ++j) {
    for (int m = 0; m < cols; ++m) {
      const double k = (m == 0 || m == cols - 1) ? 0.5 * k_col : k_col;
      triples.push_back({at(j - 1, m), at(j, m), at(j + 1, m), k});
    }
  }
  return triples;
}

BendingSprings::BendingSprings(const ClothModel& model, double rigidity_j)
    : triples_(bending_triples(model.lattice, rigidity_j)) {}

void BendingSprings::add_forces(std::span<const Vec3> x_m, std::span<const Vec3>,
                                std::span<Vec3> forces_n) const {
  for (const auto [a, b, c, k] : triples_) {
    // -dE/dx with E = 1/2 k |q|^2, q = x_a - 2 x_b + x_c.
    const Vec3 kq = k * (x_m[a] - 2.0 * x_m[b] + x_m[c]);
    forces_n[a] -= kq;
    forces_n[b] += 2.0 * kq;
    forces_n[c] -= kq;
  }
}

double BendingSprings::energy(std::span<const Vec3> x_m) const {
  double total = 0.0;
  for (const auto [a, b, c, k] : triples_) {
    total += 0.5 * k * (x_m[a] - 2.0 * x_m[b] + x_m[c]).squaredNorm();
  }
  return total;
}

void BendingSprings::add_stiffness_bound(std::span<double> row_sum_n_m) const {
  // Hessian k g g^T (x) I with g = (1, -2, 1): row sums 4k, 8k, 4k.
  for (const auto [a, b, c, k] : triples_) {
    row_sum_n_m[a] += 4.0 * k;
    row_sum_n_m[b] += 8.0 * k;
    row_sum_n_m[c] += 4.0 * k;
  }
}

void BendingSprings::add_stiffness_product(std::span<const Vec3> dx_m,
                                           std::span<Vec3> out_n) const {
  for (const auto [a, b, c, k] : triples_) {
    const Vec3 kq = k * (dx_m[a] - 2.0 * dx_m[b] + dx_m[c]);
    out_n[a] += kq;
    out_n[b] -= 2.0 * kq;
    out_n[c] += kq;
  }
}

void BendingSprings::add_stiffness_diagonal(std::span<Mat3> diagonal_n_m) const {
  for (const auto [a, b, c, k] : triples_) {
    diagonal_n_m[a].diagonal().array() += k;
    diagonal_n_m[b].diagonal().array() += 4.0 * k;
    diagonal_n_m[c].diagonal().array() += k;
  }
}

}  // namespace flagsim::physics
