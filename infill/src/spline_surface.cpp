#include "flagsim/infill/spline_surface.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cassert>

namespace flagsim::infill {

Eigen::MatrixXd spline_interpolation_matrix(int coarse_nodes, int dense_nodes) {
  assert(coarse_nodes >= 2 && (dense_nodes - 1) % (coarse_nodes - 1) == 0);
  const int n = dense_nodes, m = coarse_nodes, stride = (n - 1) / (m - 1);
  if (m == n) return Eigen::MatrixXd::Identity(n, n);
  // Third and second difference operators on the dense samples.
  const auto differences = [n](int order) {
    Eigen::MatrixXd d = Eigen::MatrixXd::Identity(n, n);
    for (int o = 0; o < order; ++o)
      d = (d.bottomRows(d.rows() - 1) - d.topRows(d.rows() - 1)).eval();
    return d;
  };
  // Polynomials of degree < order have no order-th difference: with fewer
  // than kSplineOrder coarse nodes the order drops to their count, so the
  // interpolant stays unique (two nodes: the line; three: the parabola).
  const Eigen::MatrixXd d = differences(std::min(kSplineOrder, m));
  // KKT system of: minimise |D f|^2 subject to f[i stride] = y_i.
  Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(n + m, n + m);
  kkt.topLeftCorner(n, n) = 2.0 * d.transpose() * d;
  for (int i = 0; i < m; ++i) {
    kkt(i * stride, n + i) = 1.0;
    kkt(n + i, i * stride) = 1.0;
  }
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n + m, m);
  rhs.bottomRows(m) = Eigen::MatrixXd::Identity(m, m);
  Eigen::MatrixXd solution = kkt.partialPivLu().solve(rhs);
  Eigen::MatrixXd matrix = solution.topRows(n);
  // The knots are exact (the solve leaves ~1e-15).
  for (int i = 0; i < m; ++i) {
    matrix.row(i * stride).setZero();
    matrix(i * stride, i) = 1.0;
  }
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
