#include "flagsim/infill/smooth/spline_surface.hpp"

#include <Eigen/SparseCore>
#include <Eigen/SparseQR>
#include <algorithm>
#include <cassert>
#include <vector>

#include "flagsim/core/lanes.hpp"

// Lanes are passed by value only between inlined helpers of this file (core/lanes.hpp).
#pragma GCC diagnostic ignored "-Wpsabi"

namespace flagsim::infill {

Eigen::MatrixXd natural_spline_matrix(int coarse_nodes, int dense_nodes) {
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

Eigen::MatrixXd spline_interpolation_matrix(int coarse_nodes, int dense_nodes) {
  assert(coarse_nodes >= 2 && (dense_nodes - 1) % (coarse_nodes - 1) == 0);
  const int m = coarse_nodes, n = dense_nodes, stride = (n - 1) / (m - 1);
  constexpr int kDegree = kEndExtrapolationDegree, kGhosts = kEndGhostNodes;
  if (m == n || m <= kDegree) return natural_spline_matrix(m, n);
  // The coarse values continued kGhosts nodes past each end by the polynomial
  // of degree kDegree through the last kDegree + 1 of them: ghost g (1, 2, ...)
  // beyond node 0 is sum_a L_a(-g) y_a, L_a the Lagrange basis on nodes
  // 0 .. kDegree (g = 1: 3 y0 - 3 y1 + y2, a constant second difference; g =
  // 2: 6 y0 - 8 y1 + 3 y2), and the mirror image at the other end.
  Eigen::MatrixXd extend = Eigen::MatrixXd::Zero(m + 2 * kGhosts, m);
  for (int i = 0; i < m; ++i) extend(kGhosts + i, i) = 1.0;
  for (int g = 1; g <= kGhosts; ++g)
    for (int a = 0; a <= kDegree; ++a) {
      double lagrange = 1.0;
      for (int b = 0; b <= kDegree; ++b)
        if (b != a) lagrange *= double(-g - b) / double(a - b);
      extend(kGhosts - g, a) = lagrange;
      extend(kGhosts + m - 1 + g, m - 1 - a) = lagrange;
    }
  const Eigen::MatrixXd spline = natural_spline_matrix(m + 2 * kGhosts, n + 2 * kGhosts * stride);
  Eigen::MatrixXd matrix = (spline * extend).middleRows(Eigen::Index(kGhosts) * stride, n);
  for (int i = 0; i < m; ++i) {  // knots exact, not 1 - 1e-15
    matrix.row(Eigen::Index(i) * stride).setZero();
    matrix(Eigen::Index(i) * stride, i) = 1.0;
  }
  return matrix;
}

SplineSurface::SplineSurface(const Lattice& fine, const CellGrid& grid)
    : rows_(fine.rows),
      cols_(fine.cols),
      coarse_rows_(grid.coarse_rows),
      coarse_cols_(grid.coarse_cols),
      row_weights_(std::size_t(fine.rows) * std::size_t(grid.coarse_rows)),
      col_weights_(std::size_t(grid.coarse_cols) * 3 * std::size_t(fine.cols)),
      half_(std::size_t(grid.coarse_rows) * 3 * std::size_t(fine.cols)) {
  const Eigen::MatrixXd r = spline_interpolation_matrix(grid.coarse_rows, fine.rows);
  const Eigen::MatrixXd c = spline_interpolation_matrix(grid.coarse_cols, fine.cols);
  for (int j = 0; j < rows_; ++j)
    for (int a = 0; a < coarse_rows_; ++a)
      row_weights_[std::size_t(j) * std::size_t(coarse_rows_) + std::size_t(a)] = r(j, a);
  for (int b = 0; b < coarse_cols_; ++b)
    for (int k = 0; k < cols_; ++k)
      for (int d = 0; d < 3; ++d)
        col_weights_[(std::size_t(b) * std::size_t(cols_) + std::size_t(k)) * 3 + std::size_t(d)] =
            c(k, b);
}

namespace {

// out[i] = sum_m weight[m] * rows[m][i] for i < n, m < count (rows[m] = from +
// m * stride), summed in order of m, four values at a time.
FLAGSIM_LANES_CLONES void weighted_rows(const double* weight, int count, const double* from,
                                        std::size_t stride, std::size_t n, double* out) {
  constexpr std::size_t L = lanes::kWidth;
  std::size_t i = 0;
  for (; i + L <= n; i += L) {
    lanes::Lanes sum = lanes::splat(weight[0]) * lanes::load(from + i);
    for (int m = 1; m < count; ++m)
      sum += lanes::splat(weight[m]) * lanes::load(from + std::size_t(m) * stride + i);
    lanes::store(out + i, sum);
  }
  for (; i < n; ++i) {
    double sum = weight[0] * from[i];
    for (int m = 1; m < count; ++m) sum += weight[m] * from[std::size_t(m) * stride + i];
    out[i] = sum;
  }
}

// The three lane vectors of one period of 12 values from `w` on, times the
// coordinates of `p` they stand for (x y z x, y z x y, z x y z).
[[gnu::always_inline]] inline void period_terms(const double* w, const Vec3& p, lanes::Lanes& t0,
                                                lanes::Lanes& t1, lanes::Lanes& t2) {
  constexpr std::size_t L = lanes::kWidth;
  const double px = p.x(), py = p.y(), pz = p.z();
  t0 = lanes::load(w) * lanes::Lanes{px, py, pz, px};
  t1 = lanes::load(w + L) * lanes::Lanes{py, pz, px, py};
  t2 = lanes::load(w + 2 * L) * lanes::Lanes{pz, px, py, pz};
}

// out[3k + d] = sum_b weights[b][3k + d] * x[b][d] for 3k + d < n, b < count
// (weights[b] = weights + b * n), summed in order of b: the coordinates of
// the row's nodes side by side, four values at a time (the coordinate of a
// lane repeats every 12 values).
FLAGSIM_LANES_CLONES void weighted_nodes(const double* weights, const Vec3* x, int count,
                                         std::size_t n, double* out) {
  constexpr std::size_t L = lanes::kWidth;
  constexpr std::size_t kPeriod = 3 * L;
  std::size_t i = 0;
  for (; i + kPeriod <= n; i += kPeriod) {
    lanes::Lanes s0, s1, s2;
    period_terms(weights + i, x[0], s0, s1, s2);
    for (int b = 1; b < count; ++b) {
      lanes::Lanes t0, t1, t2;
      period_terms(weights + std::size_t(b) * n + i, x[b], t0, t1, t2);
      s0 += t0, s1 += t1, s2 += t2;
    }
    lanes::store(out + i, s0);
    lanes::store(out + i + L, s1);
    lanes::store(out + i + 2 * L, s2);
  }
  for (; i < n; ++i) {
    const std::size_t d = i % 3;
    double sum = weights[i] * x[0][int(d)];
    for (int b = 1; b < count; ++b) sum += weights[std::size_t(b) * n + i] * x[b][int(d)];
    out[i] = sum;
  }
}

}  // namespace

void SplineSurface::evaluate(std::span<const Vec3> coarse_m, std::span<Vec3> dense_m) {
  assert(coarse_m.size() == std::size_t(coarse_rows_) * std::size_t(coarse_cols_) &&
         dense_m.size() == std::size_t(rows_) * std::size_t(cols_));
  static_assert(sizeof(Vec3) == 3 * sizeof(double));
  const std::size_t row_values = 3 * std::size_t(cols_);
  // X C^T: coarse row a's curve along the dense columns, xyz side by side.
  for (int a = 0; a < coarse_rows_; ++a)
    weighted_nodes(col_weights_.data(), &coarse_m[std::size_t(a) * std::size_t(coarse_cols_)],
                   coarse_cols_, row_values, half_.data() + std::size_t(a) * row_values);
  // R (X C^T): every dense row, written in place as its nodes' xyz.
  double* const dense = dense_m.front().data();
  for (int j = 0; j < rows_; ++j)
    weighted_rows(row_weights_.data() + std::size_t(j) * std::size_t(coarse_rows_), coarse_rows_,
                  half_.data(), row_values, row_values, dense + std::size_t(j) * row_values);
}

}  // namespace flagsim::infill
