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
// The 1D interpolant is a discrete natural spline of degree 11: among all
// dense sequences through the coarse values it minimises the sum of squared
// sixth differences (the continuous one minimises the integral of
// (d^6 f / dx^6)^2), laid through the coarse values continued two nodes past
// each border (below). Why so smooth: an interpolant of rough data (the 9 x 13
// physics folds its links by 10-40 degrees) bends most where it is pinned to
// the data, and how much more depends on the degree. Median turning angle on
// the coarse lines over the median between them (cloth_checks.py imprint),
// default scene, per frame after 1 s, median / worst frame: with natural ends,
// cubic (second differences) 1.45 / -, quintic (third) 1.18 / 1.72, degree 7
// (fourth) 1.03 / 1.48 (2026-12-03); with the ends continued (2026-12-08, all
// 10 s), degree 7 1.13 / 1.32, degree 11 1.06 / 1.20. Degree 7's figure rose
// when the ends were continued because its curled end cells (below), off the
// coarse lines, had raised the median between them.
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

/// Order of the differences the interpolant minimises (6: degree 11).
inline constexpr int kSplineOrder = 6;

/// [dense_nodes x coarse_nodes]: the dense samples of the discrete natural
/// spline through coarse values at every `stride`-th dense node, stride =
/// (dense_nodes - 1) / (coarse_nodes - 1). Reproduces polynomials of degree
/// below kSplineOrder exactly (with fewer coarse nodes: the polynomial through
/// them); the identity when coarse_nodes == dense_nodes.
Eigen::MatrixXd natural_spline_matrix(int coarse_nodes, int dense_nodes);

/// How the surface ends at the cloth's borders: the coarse values are continued
/// kEndGhostNodes nodes past each end by the parabola through the last three
/// (a constant second difference: 3 y0 - 3 y1 + y2, then 6 y0 - 8 y1 + 3 y2),
/// and the natural spline is laid through them all. Why: a natural spline
/// leaves the low derivatives free at its ends, and on the physics' folded data
/// it bent its end cells 2-4x as much as the inside of the cloth (degree 7 on
/// the default scene's coarse frames after 1 s: the rows' median turning 3.8x
/// the cloth's median at the fly end, 3.7x at the pole, where the coarse
/// curvature is like the inside's; degree 11, 6-8x); every free edge curled,
/// and the crease-line measure found its worst line by an edge in most frames.
/// Continued, the end cells bend like their neighbours (degree 11: 0.8-1.8x,
/// the inside 0.8-1.5x). At degree 7 a cubic continuation (constant third
/// difference) still bent them 1.9-2.0x and a linear one flattened them (f'' =
/// 0, 0.1x). docs/dense_surface.md.
inline constexpr int kEndExtrapolationDegree = 2;
inline constexpr int kEndGhostNodes = 2;

/// [dense_nodes x coarse_nodes]: the dense samples of the surface's 1D
/// interpolant, natural_spline_matrix() through the coarse values continued
/// past the ends as said above. Passes through the coarse values; reproduces
/// quadratics exactly (with 2 coarse nodes it is the natural spline: the
/// line); the identity when coarse_nodes == dense_nodes.
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
