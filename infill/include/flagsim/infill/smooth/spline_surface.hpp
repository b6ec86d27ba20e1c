#pragma once
// Step 3.1 of the smooth infill: the mean surface through the coarse nodes.
//
// Reading of the paper for many coarse nodes (the flag of section 4): the
// paper gives the edge points of a cell "directly (or computed by something
// else)" and fills the inside. Laying every cell edge on its own curve makes
// every coarse line a crease (measured: turning angles on coarse lines 7x those
// between them). Here the coarse nodes instead define one smooth surface over
// the whole cloth, and every dense node starts on it: a tensor product of 1D
// interpolants along the rows and the columns, so row j of the dense lattice is
// the same curve through the coarse nodes whatever cell it is in.
//
// The 1D interpolant is a discrete natural spline of degree 7: among all dense
// sequences through the coarse values it minimises the sum of squared fourth
// differences (the continuous one minimises the integral of f''''^2). Why so
// smooth: an interpolant of rough data (the 9 x 13 physics folds its links by
// 10-40 degrees) bends most where it is pinned to the data, and how much more
// depends on the degree. Median turning angle on the coarse lines over the
// median between them, default scene, per frame after 1 s (median / worst of
// 271 frames): cubic (second differences) 1.45 / -, quintic (third) 1.18 /
// 1.72, degree 7 (fourth) 1.03 / 1.48, for 15% more projection work than the
// quintic (its overshoots are larger).
// The surface is linear in the coarse nodes: dense_d = R X_d C^T for each
// coordinate d, with R [J x Jc] and C [K x Kc] built once. Evaluated as two
// passes of scaled row sums on the xyz of a row side by side (the dense
// output's own layout), four at a time (core/lanes.hpp): each dense value is
// sum_a R_ja (sum_b C_kb X_ab) summed in order of a and b, the same bits on
// every machine; a dense node on a coarse node is that node exactly.
#include <Eigen/Core>
#include <span>
#include <vector>

#include "flagsim/core/lattice.hpp"
#include "flagsim/infill/cell_grid.hpp"

namespace flagsim::infill {

/// Order of the differences the interpolant minimises (4: degree 7).
inline constexpr int kSplineOrder = 4;

/// [dense_nodes x coarse_nodes]: the dense samples of the discrete natural
/// spline through coarse values at every `stride`-th dense node, stride =
/// (dense_nodes - 1) / (coarse_nodes - 1). Reproduces cubics exactly (with
/// fewer than 4 coarse nodes: the polynomial through them); the identity when
/// coarse_nodes == dense_nodes.
Eigen::MatrixXd spline_interpolation_matrix(int coarse_nodes, int dense_nodes);

class SplineSurface {
 public:
  SplineSurface(const Lattice& fine, const CellGrid& grid);

  /// @param coarse_m  coarse node positions [Jc*Kc] row-major, m
  /// @param dense_m   out: the surface at every dense node [J*K] row-major, m
  void evaluate(std::span<const Vec3> coarse_m, std::span<Vec3> dense_m);

 private:
  int rows_ = 0, cols_ = 0, coarse_rows_ = 0, coarse_cols_ = 0;  ///< J, K, Jc, Kc
  std::vector<double> row_weights_;                              ///< R [J x Jc] row-major
  /// C^T with each column weight three times over [Kc x 3K]: C_kb at 3k + d.
  std::vector<double> col_weights_;
  std::vector<double> half_;  ///< X C^T [Jc x 3K]: coarse row a's curve along the dense columns
};

}  // namespace flagsim::infill
