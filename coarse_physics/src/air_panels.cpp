#include "flagsim/coarse_physics/air_panels.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <utility>

#include "flagsim/scene/scene.hpp"

namespace flagsim::physics {
namespace {

/// One direction's weights from `cloth_nodes` onto `panel_nodes` (fewer):
/// w[p][i] = integral of hat_p(xi) phi_i(xi) over the side, normalised per
/// panel node p, with hat_p the panel node's hat and phi_i the cloth node's
/// (the piecewise-linear cloth between its nodes). Both are linear between
/// the cloth's nodes and the panels' nodes, so Simpson's rule on each piece is
/// exact: a panel node's sample of an affine field is the field's exact
/// hat-weighted mean at every lattice (a trapezoid sum would move an edge
/// panel node by about h^2 / (6 panel) with the cloth's spacing h).
AirPanels::Axis axis_weights(int cloth_nodes, int panel_nodes) {
  const double cloth_per_panel = double(cloth_nodes - 1) / double(panel_nodes - 1);
  const auto hat = [](double at, int node) { return std::max(0.0, 1.0 - std::abs(at - node)); };
  std::vector<double> table(std::size_t(panel_nodes) * std::size_t(cloth_nodes), 0.0);
  const auto w = [&](int p, int i) -> double& {
    return table[std::size_t(p) * std::size_t(cloth_nodes) + std::size_t(i)];
  };
  for (int i = 0; i + 1 < cloth_nodes; ++i) {
    // The cloth element [i, i + 1], in panel units, cut at the panel nodes inside it.
    const double a = double(i) / cloth_per_panel, b = double(i + 1) / cloth_per_panel;
    std::vector<double> cuts = {a};
    for (int p = int(std::floor(a)) + 1; double(p) < b; ++p) cuts.push_back(double(p));
    cuts.push_back(b);
    for (std::size_t c = 0; c + 1 < cuts.size(); ++c) {
      const double lo = cuts[c], hi = cuts[c + 1], length = hi - lo;
      const int p0 = std::min(int(std::floor(0.5 * (lo + hi))), panel_nodes - 2);
      for (const double at : {lo, 0.5 * (lo + hi), hi}) {
        const double simpson = length * (at == 0.5 * (lo + hi) ? 4.0 : 1.0) / 6.0;
        const double phi_right = (at - a) / (b - a);  // phi_{i+1}; phi_i = 1 - it
        for (const int p : {p0, p0 + 1}) {
          w(p, i) += simpson * hat(at, p) * (1.0 - phi_right);
          w(p, i + 1) += simpson * hat(at, p) * phi_right;
        }
      }
    }
  }
  AirPanels::Axis axis;
  axis.range.assign(std::size_t(panel_nodes), {cloth_nodes, -1});
  axis.panels_of.assign(std::size_t(cloth_nodes), {panel_nodes, -1});
  for (int p = 0; p < panel_nodes; ++p) {
    double sum = 0.0;
    for (int i = 0; i < cloth_nodes; ++i) sum += w(p, i);
    for (int i = 0; i < cloth_nodes; ++i) {
      w(p, i) /= sum;
      if (w(p, i) <= 0.0) continue;
      auto& [first, last] = axis.range[std::size_t(p)];
      first = std::min(first, i);
      last = std::max(last, i);
      auto& [lowest, highest] = axis.panels_of[std::size_t(i)];
      lowest = std::min(lowest, p);
      highest = std::max(highest, p);
    }
  }
  axis.table = std::move(table);
  return axis;
}

}  // namespace

AirPanels::AirPanels(const Lattice& cloth, double panel_m)
    : panels_(cloth), cloth_rows_(cloth.rows), cloth_cols_(cloth.cols) {
  const double height = cloth.spacing_y_m * (cloth.rows - 1);
  const double width = cloth.spacing_x_m * (cloth.cols - 1);
  const int rows = air_panel_nodes(height, panel_m), cols = air_panel_nodes(width, panel_m);
  // Every hat holds a cloth node when the cloth is at least as fine as the
  // panels in both directions; otherwise the panels are the cloth's nodes.
  if (rows >= cloth.rows || cols >= cloth.cols) return;
  same_ = false;
  panels_ = Lattice::rectangle(rows, cols, width, height, cloth.origin_m);
  rows_ = axis_weights(cloth.rows, rows);
  cols_ = axis_weights(cloth.cols, cols);
  for (auto& h : half_) h.resize(std::size_t(cloth.rows) * std::size_t(cols));
}

// `Fields` cloth fields sampled at once: their 3 x `Fields` coordinates
// each pass over the weights together.
template <int Fields>
void AirPanels::sample_fields(const std::span<const Vec3> (&cloth)[Fields],
                              std::vector<double>* const (&to)[Fields]) const {
  assert(!same_);
  const std::size_t J = std::size_t(cloth_rows_), K = std::size_t(cloth_cols_);
  const std::size_t Jp = std::size_t(panels_.rows), Kp = std::size_t(panels_.cols);
  // Along the rows (cloth columns -> panel columns), every axis in one pass.
  // Each sum runs over one panel's few cloth nodes in registers: accumulating
  // into memory entry by entry chained every add through a store (measured:
  // half the wind's time on the hybrid's coarse lattice).
  for (std::size_t j = 0; j < J; ++j) {
    const Vec3* row[Fields];
    for (int f = 0; f < Fields; ++f) row[f] = cloth[f].data() + j * K;
    for (std::size_t q = 0; q < Kp; ++q) {
      const auto [first, last] = cols_.range[q];
      const double* w = cols_.table.data() + q * K;
      double s[Fields][3] = {};
      for (int i = first; i <= last; ++i)
        for (int f = 0; f < Fields; ++f) {
          s[f][0] += w[i] * row[f][i].x();
          s[f][1] += w[i] * row[f][i].y();
          s[f][2] += w[i] * row[f][i].z();
        }
      for (int f = 0; f < Fields; ++f)
        for (int axis = 0; axis < 3; ++axis) half_[3 * f + axis][j * Kp + q] = s[f][axis];
    }
  }
  // Down the columns (cloth rows -> panel rows).
  for (int f = 0; f < Fields; ++f)
    for (int axis = 0; axis < 3; ++axis) {
      const double* half = half_[3 * f + axis].data();
      for (std::size_t p = 0; p < Jp; ++p) {
        const auto [first, last] = rows_.range[p];
        const double* w = rows_.table.data() + p * J;
        double* out = to[f][axis].data() + p * Kp;
        for (std::size_t q = 0; q < Kp; ++q) {
          double sum = 0.0;
          for (int j = first; j <= last; ++j) sum += w[j] * half[std::size_t(j) * Kp + q];
          out[q] = sum;
        }
      }
    }
}

void AirPanels::sample(std::span<const Vec3> cloth, std::vector<double> (&to)[3]) const {
  sample_fields<1>({cloth}, {to});
}

void AirPanels::sample(std::span<const Vec3> cloth_a, std::vector<double> (&to_a)[3],
                       std::span<const Vec3> cloth_b, std::vector<double> (&to_b)[3]) const {
  sample_fields<2>({cloth_a, cloth_b}, {to_a, to_b});
}

void AirPanels::spread(const std::vector<double> (&from)[3], std::span<Vec3> cloth) const {
  assert(!same_);
  const std::size_t J = std::size_t(cloth_rows_), K = std::size_t(cloth_cols_);
  const std::size_t Kp = std::size_t(panels_.cols);
  // Up the columns (panel rows -> cloth rows): each cloth row from its few panel rows.
  for (int axis = 0; axis < 3; ++axis) {
    double* half = half_[axis].data();
    const double* in = from[axis].data();
    for (std::size_t j = 0; j < J; ++j) {
      const auto [first, last] = rows_.panels_of[j];
      for (std::size_t q = 0; q < Kp; ++q) {
        double sum = 0.0;
        for (int p = first; p <= last; ++p)
          sum += rows_.table[std::size_t(p) * J + j] * in[std::size_t(p) * Kp + q];
        half[j * Kp + q] = sum;
      }
    }
  }
  // Along the rows (panel columns -> cloth columns), the three axes in one pass.
  const double *h0 = half_[0].data(), *h1 = half_[1].data(), *h2 = half_[2].data();
  for (std::size_t j = 0; j < J; ++j) {
    Vec3* row = cloth.data() + j * K;
    const std::size_t in = j * Kp;
    for (std::size_t i = 0; i < K; ++i) {
      const auto [first, last] = cols_.panels_of[i];
      double s0 = 0.0, s1 = 0.0, s2 = 0.0;
      for (int q = first; q <= last; ++q) {
        const double w = cols_.table[std::size_t(q) * K + i];
        s0 += w * h0[in + std::size_t(q)];
        s1 += w * h1[in + std::size_t(q)];
        s2 += w * h2[in + std::size_t(q)];
      }
      row[i] += Vec3(s0, s1, s2);
    }
  }
}

double AirPanels::weight(std::size_t panel_node, std::size_t cloth_node) const {
  if (same_) return panel_node == cloth_node ? 1.0 : 0.0;
  const std::size_t K = std::size_t(cloth_cols_), Kp = std::size_t(panels_.cols);
  return row_weight(int(panel_node / Kp), int(cloth_node / K)) *
         col_weight(int(panel_node % Kp), int(cloth_node % K));
}

}  // namespace flagsim::physics
