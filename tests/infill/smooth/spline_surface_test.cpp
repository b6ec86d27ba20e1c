#include "flagsim/infill/smooth/spline_surface.hpp"

#include <gtest/gtest.h>

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "tolerances.hpp"

namespace flagsim::infill {
namespace {

TEST(SplineInterpolation, PassesThroughTheCoarseValuesAndReproducesCubics) {
  const Eigen::MatrixXd m = natural_spline_matrix(5, 33);
  ASSERT_EQ(m.rows(), 33);
  ASSERT_EQ(m.cols(), 5);
  Eigen::VectorXd coarse(5);
  for (int i = 0; i < 5; ++i) coarse[i] = 0.3 - 1.2 * i + 0.7 * i * i - 0.2 * i * i * i;
  const Eigen::VectorXd dense = m * coarse;
  for (int n = 0; n < 33; ++n) {
    const double u = n / 8.0;  // coarse index of dense node n
    EXPECT_NEAR(dense[n], 0.3 - 1.2 * u + 0.7 * u * u - 0.2 * u * u * u, test::kSplineSolve) << n;
  }
  for (int i = 0; i < 5; ++i)
    EXPECT_EQ(m(Eigen::Index(8) * i, i), 1.0);  // knots exact, not 1 - 1e-15
}

// The same minimisation as a dense least-squares problem: min |D f| with the
// knots fixed, D the 4th (or fewer) differences, solved by dense Householder QR.
Eigen::MatrixXd dense_reference(int m, int n) {
  const int stride = (n - 1) / (m - 1), order = std::min(kSplineOrder, m);
  Eigen::MatrixXd d = Eigen::MatrixXd::Identity(n, n);
  for (int o = 0; o < order; ++o) d = (d.bottomRows(d.rows() - 1) - d.topRows(d.rows() - 1)).eval();
  Eigen::MatrixXd p = Eigen::MatrixXd::Zero(n, m);
  for (int i = 0; i + 1 < m; ++i)
    for (int s = 0; s <= stride; ++s) {
      p(i * stride + s, i) = 1.0 - double(s) / stride;
      p(i * stride + s, i + 1) = double(s) / stride;
    }
  std::vector<int> free;
  for (int node = 0; node < n; ++node)
    if (node % stride != 0) free.push_back(node);
  Eigen::MatrixXd dn(d.rows(), Eigen::Index(free.size()));
  for (std::size_t c = 0; c < free.size(); ++c) dn.col(Eigen::Index(c)) = d.col(free[c]);
  const Eigen::MatrixXd z = dn.householderQr().solve(-(d * p));
  for (std::size_t c = 0; c < free.size(); ++c) p.row(free[c]) += z.row(Eigen::Index(c));
  return p;
}

TEST(SplineInterpolation, TheSparseSolveIsTheDenseOne) {
  // The banded QR (O(n): 0.1 s at 8193 nodes, where the dense one took 50 s)
  // gives the dense solution's matrix to round-off times the condition.
  for (const auto& [m, n] : {std::pair{2, 9}, {3, 9}, {5, 33}, {9, 129}, {13, 193}}) {
    const Eigen::MatrixXd difference = natural_spline_matrix(m, n) - dense_reference(m, n);
    EXPECT_LT(difference.cwiseAbs().maxCoeff(), test::kSplineQrAgreement) << m << " x " << n;
  }
}

TEST(SplineInterpolation, TheSurfacesInterpolantPassesThroughTheKnotsAndReproducesQuadratics) {
  // Continued past the ends by a constant second difference, the data of a
  // quadratic stay that quadratic, and the natural spline reproduces it.
  for (const auto& [m, n] : {std::pair{3, 9}, {5, 33}, {9, 129}, {13, 193}, {13, 769}}) {
    const Eigen::MatrixXd matrix = spline_interpolation_matrix(m, n);
    const int stride = (n - 1) / (m - 1);
    Eigen::VectorXd coarse(m);
    for (int i = 0; i < m; ++i) coarse[i] = 0.3 - 1.2 * i + 0.07 * i * i;
    const Eigen::VectorXd dense = matrix * coarse;
    for (int k = 0; k < n; ++k) {
      const double u = double(k) / stride;
      EXPECT_NEAR(dense[k], 0.3 - 1.2 * u + 0.07 * u * u, test::kSplineSolve) << m << " x " << n;
    }
    for (int i = 0; i < m; ++i) EXPECT_EQ(matrix(Eigen::Index(stride) * i, i), 1.0) << i;
  }
}

// Mean |second difference| of f over the dense nodes of coarse cell `cell`.
double cell_bend(const Eigen::VectorXd& f, int cell, int stride) {
  double sum = 0.0;
  int count = 0;
  for (int n = std::max(1, cell * stride); n <= std::min(int(f.size()) - 2, (cell + 1) * stride);
       ++n, ++count)
    sum += std::abs(f[n - 1] - 2 * f[n] + f[n + 1]);
  return sum / count;
}

TEST(SplineInterpolation, TheEndCellsBendLikeTheirNeighbours) {
  // Folded data like the coarse physics' (a gentle arc with seeded kinks):
  // the natural spline leaves f'' free at its ends and bends its end cells
  // most, so the surface's free edges curled. Continued past the ends, the
  // end cells bend like the cells inside. Measured over 200 seeded profiles,
  // the mean end-cell bend over the mean inner-cell bend: natural 5.44 (2.17
  // with the fourth differences of before 2026-12-08), the surface's
  // interpolant 1.32 (two ghost nodes a side, a constant second difference).
  // Bounds near each.
  const int coarse = 13, dense = 193, stride = 16;
  const Eigen::MatrixXd natural = natural_spline_matrix(coarse, dense);
  const Eigen::MatrixXd surface = spline_interpolation_matrix(coarse, dense);
  std::mt19937 rng(7);
  std::normal_distribution<double> kink(0.0, 0.02);
  double end_natural = 0.0, end_surface = 0.0, inner_natural = 0.0, inner_surface = 0.0;
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::VectorXd y(coarse);
    for (int i = 0; i < coarse; ++i) y[i] = 0.01 * (i - 6.0) * (i - 6.0) / 6.0 + kink(rng);
    const Eigen::VectorXd a = natural * y, b = surface * y;
    end_natural += cell_bend(a, 0, stride) + cell_bend(a, coarse - 2, stride);
    end_surface += cell_bend(b, 0, stride) + cell_bend(b, coarse - 2, stride);
    for (int cell = 1; cell + 2 < coarse; ++cell) {
      inner_natural += cell_bend(a, cell, stride) * 2.0 / (coarse - 3);
      inner_surface += cell_bend(b, cell, stride) * 2.0 / (coarse - 3);
    }
  }
  EXPECT_GT(end_natural / inner_natural, 4.5);
  EXPECT_LT(end_surface / inner_surface, 1.45);
}

TEST(SplineInterpolation, FewNodesGiveTheirPolynomialAndEqualSizesTheIdentity) {
  const Eigen::MatrixXd line = spline_interpolation_matrix(2, 9);
  const Eigen::MatrixXd parabola = spline_interpolation_matrix(3, 9);
  for (int n = 0; n < 9; ++n) {
    EXPECT_NEAR(line(n, 0), 1.0 - n / 8.0, test::kRoundOff) << n;
    EXPECT_NEAR(line(n, 1), n / 8.0, test::kRoundOff) << n;
    const double u = n / 4.0;  // y = u^2 through (0, 0), (1, 1), (2, 4)
    EXPECT_NEAR(parabola(n, 1) + 4 * parabola(n, 2), u * u, test::kRoundOff) << n;
  }
  EXPECT_TRUE(spline_interpolation_matrix(7, 7).isIdentity());
}

TEST(SplineInterpolation, HasNoPreferenceForTheKnots) {
  // Rough data (alternating signs: the hardest case for an interpolant): the
  // largest second difference must not sit on the knots, as a cubic's does.
  const int coarse = 9, dense = 129, stride = 16;
  const Eigen::MatrixXd m = spline_interpolation_matrix(coarse, dense);
  Eigen::VectorXd y(coarse);
  for (int i = 0; i < coarse; ++i) y[i] = (i % 2 ? 1.0 : -1.0) * (1.0 + 0.1 * i);
  const Eigen::VectorXd f = m * y;
  double on_knots = 0.0, elsewhere = 0.0;
  for (int n = 1; n + 1 < dense; ++n) {
    const double bend = std::abs(f[n - 1] - 2 * f[n] + f[n + 1]);
    (n % stride == 0 ? on_knots : elsewhere) += bend;
  }
  const double knots = coarse - 2, others = dense - 2 - knots;
  EXPECT_LT(on_knots / knots, 1.3 * elsewhere / others);
}

TEST(SplineSurface, IsTheTensorProductAndCarriesAPlaneExactly) {
  const Lattice fine = Lattice::rectangle(17, 25, 1.5, 1.0, Vec3(0, 2, 0));
  const CellGrid grid = CellGrid::of(fine, 5, 7);
  SplineSurface surface(fine, grid);
  // Coarse nodes of a tilted, stretched plane: the surface is that plane.
  const auto plane = [](const Vec3& rest) {
    return Vec3(0.9 * rest.x() + 0.1 * rest.y(), rest.y(), 0.3 * rest.x() - 0.2 * rest.y() + 1.0);
  };
  std::vector<Vec3> coarse(grid.coarse_count()), dense(fine.node_count());
  for (int jc = 0; jc < 5; ++jc)
    for (int kc = 0; kc < 7; ++kc)
      coarse[grid.coarse_index(jc, kc)] = plane(fine.rest_position(4 * jc, 4 * kc));
  surface.evaluate(coarse, dense);
  for (int j = 0; j < 17; ++j)
    for (int k = 0; k < 25; ++k)
      EXPECT_LT((dense[fine.index(j, k)] - plane(fine.rest_position(j, k))).norm(), 1e-9);
}

// evaluate() is the tensor product R X C^T of the two matrices, whatever the
// coarse nodes (random ones here), on an odd number of dense columns (the
// last values of a row outside the four-wide passes), and a dense node on a
// coarse node is that node to the bit.
TEST(SplineSurface, EvaluatesTheTensorProductAndPassesThroughTheCoarseNodes) {
  const Lattice fine = Lattice::rectangle(33, 49, 1.5, 1.0, Vec3(0, 2, 0));
  const CellGrid grid = CellGrid::of(fine, 9, 13);
  SplineSurface surface(fine, grid);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<Vec3> coarse(grid.coarse_count()), dense(fine.node_count());
  for (Vec3& p : coarse) p = Vec3(value(random), value(random), value(random));
  surface.evaluate(coarse, dense);
  const Eigen::MatrixXd r = spline_interpolation_matrix(9, 33);
  const Eigen::MatrixXd c = spline_interpolation_matrix(13, 49);
  for (int d = 0; d < 3; ++d) {
    Eigen::MatrixXd x(9, 13);
    for (int a = 0; a < 9; ++a)
      for (int b = 0; b < 13; ++b) x(a, b) = coarse[grid.coarse_index(a, b)][d];
    const Eigen::MatrixXd expected = r * x * c.transpose();
    double worst = 0.0;
    for (int j = 0; j < 33; ++j)
      for (int k = 0; k < 49; ++k)
        worst = std::max(worst, std::abs(dense[fine.index(j, k)][d] - expected(j, k)));
    EXPECT_LT(worst, 1e-13) << "coordinate " << d;  // rounding of sums of 9 x 13 terms
  }
  for (int a = 0; a < 9; ++a)
    for (int b = 0; b < 13; ++b)
      EXPECT_EQ(dense[fine.index(4 * a, 4 * b)], coarse[grid.coarse_index(a, b)]);
}

// The largest lattice a flag carries from 13 coarse columns (stride 64): a
// flat flag stays flat. Built from the KKT system of the same problem (whose
// D^T D has condition ~n^8, 1e23 here) the matrix left a flat flag 0.6%
// strained, and the finest level of the infill could not converge.
TEST(SplineInterpolation, IsAccurateAtStride64) {
  const Eigen::MatrixXd m = natural_spline_matrix(13, 769);
  const Eigen::MatrixXd surface = spline_interpolation_matrix(13, 769);
  Eigen::VectorXd line(13), cubic(13);
  for (int i = 0; i < 13; ++i) {
    line[i] = 0.125 * i;
    cubic[i] = 0.01 * i * i * i - 0.1 * i * i + 0.125 * i;
  }
  const Eigen::VectorXd flat = m * line, curved = m * cubic, surface_flat = surface * line;
  for (int n = 0; n < 769; ++n) {
    const double u = n / 64.0;
    EXPECT_NEAR(flat[n], 0.125 * u, test::kSplineSolve) << n;
    EXPECT_NEAR(surface_flat[n], 0.125 * u, test::kSplineSolve) << n;
    EXPECT_NEAR(curved[n], 0.01 * u * u * u - 0.1 * u * u + 0.125 * u, test::kSplineSolve) << n;
  }
}

}  // namespace
}  // namespace flagsim::infill
