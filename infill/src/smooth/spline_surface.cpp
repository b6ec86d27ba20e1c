#include "flagsim/infill/smooth/spline_surface.hpp"

#include <Eigen/SparseCore>
#include <Eigen/SparseQR>
#include <algorithm>
#include <cassert>
#include <vector>

namespace flagsim::infill {

Eigen::MatrixXd spline_interpolation_matrix(int coarse_nodes, int dense_nodes) {
  assert(coarse_nodes >= 2 && (dense_nodes - 1) % (coarse_nodes - 1) == 0);
  const int n = dense_nodes, m = coarse_nodes, stride = (n - 1) / (m - 1);
  if (m == n) return Eigen::MatrixXd::Identity(n, n);
  // The order-th difference operator on the dense samples, as a sparse matrix:
  // row r holds the signed binomial coefficients at columns r .. r + order.
  const int order = std::min(kSplineOrder, m);
  // Polynomials of degree < order have no order-th difference: with fewer
  // than kSplineOrder coarse nodes the order drops to their count, so the
  // interpolant stays unique (two nodes: the line; three: the parabola).
  std::vector<double> binomial(std::size_t(order) + 1, 0.0);
  binomial[0] = 1.0;
  for (int o = 0; o < order; ++o)  // coefficients of (x - 1)^order, highest power last
    for (int k = o + 1; k >= 0; --k)
      binomial[std::size_t(k)] =
          (k > 0 ? binomial[std::size_t(k) - 1] : 0.0) - (k <= o ? binomial[std::size_t(k)] : 0.0);
  // minimise |D f|^2 subject to f[i stride] = y_i, by the null-space method:
  // f = P y + N z with P the piecewise-linear interpolant (exact at the knots)
  // and N the dense nodes between knots, so z minimises |D N z + D P y|, a
  // least-squares problem solved by Householder QR of D N. (The KKT system of
  // the same problem holds D^T D, whose condition number grows as n^8: at
  // 769 nodes, 1e23, and its solution left a flat flag 0.6% strained.) QR on
  // D N works with the square root of a per-interval condition, ~stride^4.
  // D N is banded (order + 1 entries a row), so its QR is sparse: O(n), where
  // a dense one took 50 s at 8193 nodes.
  Eigen::MatrixXd p = Eigen::MatrixXd::Zero(n, m);
  for (int i = 0; i + 1 < m; ++i)
    for (int s = 0; s <= stride; ++s) {
      const double t = double(s) / stride;
      p(i * stride + s, i) = 1.0 - t;
      p(i * stride + s, i + 1) = t;
    }
  const int free_count = n - m;
  std::vector<int> free_nodes, free_index(std::size_t(n), -1);
  free_nodes.reserve(std::size_t(free_count));
  for (int node = 0; node < n; ++node)
    if (node % stride != 0) {
      free_index[std::size_t(node)] = int(free_nodes.size());
      free_nodes.push_back(node);
    }
  const int rows = n - order;
  std::vector<Eigen::Triplet<double>> d_entries, dn_entries;
  for (int r = 0; r < rows; ++r)
    for (int k = 0; k <= order; ++k) {
      const double value = binomial[std::size_t(k)];
      const int column = r + k;
      d_entries.emplace_back(r, column, value);
      if (const int c = free_index[std::size_t(column)]; c >= 0)
        dn_entries.emplace_back(r, c, value);
    }
  Eigen::SparseMatrix<double> d(rows, n), dn(rows, free_count);
  d.setFromTriplets(d_entries.begin(), d_entries.end());
  dn.setFromTriplets(dn_entries.begin(), dn_entries.end());
  dn.makeCompressed();
  Eigen::SparseQR<Eigen::SparseMatrix<double>, Eigen::NaturalOrdering<int>> qr(dn);
  assert(qr.info() == Eigen::Success);  // D N has full column rank: no free node is unconstrained
  const Eigen::MatrixXd rhs = -(d * p);
  const Eigen::MatrixXd z = qr.solve(rhs);
  Eigen::MatrixXd matrix = p;
  for (int c = 0; c < free_count; ++c) matrix.row(free_nodes[std::size_t(c)]) += z.row(c);
  return matrix;
}

SplineSurface::SplineSurface(const Lattice& fine, const CellGrid& grid)
    : rows_(spline_interpolation_matrix(grid.coarse_rows, fine.rows)),
      cols_t_(spline_interpolation_matrix(grid.coarse_cols, fine.cols).transpose()),
      coarse_(grid.coarse_rows, grid.coarse_cols),
      half_(grid.coarse_rows, fine.cols),
      dense_(fine.rows, fine.cols) {}

void SplineSurface::evaluate(std::span<const Vec3> coarse_m, std::span<Vec3> dense_m) {
  assert(coarse_m.size() == std::size_t(coarse_.size()) &&
         dense_m.size() == std::size_t(dense_.size()));
  for (int d = 0; d < 3; ++d) {
    for (Eigen::Index i = 0; i < coarse_.size(); ++i)
      coarse_.data()[i] = coarse_m[std::size_t(i)][d];
    half_.noalias() = coarse_ * cols_t_;
    dense_.noalias() = rows_ * half_;
    for (Eigen::Index i = 0; i < dense_.size(); ++i) dense_m[std::size_t(i)][d] = dense_.data()[i];
  }
}

}  // namespace flagsim::infill
