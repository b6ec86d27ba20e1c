#pragma once
// The cloth as the air sees it: a lattice of panels of a fixed physical size,
// whatever the cloth's own lattice.
//
// Why: the quasi-steady wind (aero_force.hpp) is local. Evaluated on every
// triangle of the cloth, its lift (a pressure that grows with the surface's
// slope to the flow) drives the shortest wave the lattice can carry at least as
// hard as the flag-length wave, so the full-lattice flag's waves shrank with the
// spacing (wavelength 1.04 -> 0.34 flag lengths from 17 x 25 to 129 x 193) and
// had no converged answer. A real flag's pressure is set by the air around it,
// which averages the surface over lengths of the order of the flag's height.
// Here the wind is evaluated on a lattice of panels about `panel` metres wide
// (wind.panel, default a sixth of flag.size[0]: 6 x 4 panels of 0.25 m on the
// default 1.5 x 1.0 m flag),
// whose nodes are weighted averages of the cloth's nodes, and each panel node's
// force is spread back over the same cloth nodes with the same weights:
//
//   X_a = sum_i W_ai x_i,   V_a = sum_i W_ai v_i,   f_i += sum_a W_ai F_a,
//   W_ai = integral(hat_a phi_i dA) / integral(hat_a dA)
//
// with hat_a the bilinear hat of panel node a (1 at a, 0 at its neighbours)
// and phi_i the cloth node's own bilinear hat over the rest rectangle: X_a is
// the hat-weighted mean of the piecewise-bilinear cloth, the same surface
// average at every lattice (exact for an affine field, O(h^2) in the cloth's
// spacing h otherwise). The force is the
// transpose of the sampling, so it does the virtual work F . dX of the panels
// (total force and moment are kept), and a uniform pressure p on the panels
// gives p m_i (m_i = integral(phi_i dA), the node's area share) on every cloth
// node: the same force per area at any resolution.
// Waves shorter than about two panels are neither seen nor driven. The
// weights are separable (row weights times column weights), so sampling and
// spreading are two one-dimensional passes each, O(J K) whatever the panels.
//
// When the cloth is no finer than the panels in a direction (the 5 x 7
// hybrid's coarse lattice on the default flag), the panels are the cloth's own nodes
// and both maps are the identity: same_lattice() says so and the wind skips them.
#include <span>
#include <utility>
#include <vector>

#include "flagsim/core/lattice.hpp"
#include "flagsim/core/vec3.hpp"

namespace flagsim::physics {

class AirPanels {
 public:
  /// Panels of at most `panel_m` on a side over `cloth`'s rest rectangle.
  AirPanels(const Lattice& cloth, double panel_m);

  /// The panels' nodes (rows x cols, the cloth's rectangle); the cloth's own
  /// lattice when same_lattice().
  const Lattice& lattice() const { return panels_; }
  bool same_lattice() const { return same_; }
  int cloth_cols() const { return cloth_cols_; }

  /// to[axis][a] = sum_i W_ai from[i][axis]: the panel nodes' positions (or
  /// velocities) from the cloth's; `to` holds panel-node count values per axis.
  void sample(std::span<const Vec3> cloth, std::vector<double> (&to)[3]) const;
  /// Two fields sampled in one pass over the weights (the positions and the
  /// velocities of a substep): the same values as two sample() calls.
  void sample(std::span<const Vec3> cloth_a, std::vector<double> (&to_a)[3],
              std::span<const Vec3> cloth_b, std::vector<double> (&to_b)[3]) const;
  /// cloth[i] += sum_a W_ai from[axis][a]: panel-node forces onto the cloth.
  void spread(const std::vector<double> (&from)[3], std::span<Vec3> cloth) const;
  /// W_ai: cloth node i's weight in panel node a (W_ai = row_weight(pa, j) col_weight(qa, k)).
  double weight(std::size_t panel_node, std::size_t cloth_node) const;
  double row_weight(int panel_row, int cloth_row) const {
    return rows_.table[std::size_t(panel_row) * std::size_t(cloth_rows_) + std::size_t(cloth_row)];
  }
  double col_weight(int panel_col, int cloth_col) const {
    return cols_.table[std::size_t(panel_col) * std::size_t(cloth_cols_) + std::size_t(cloth_col)];
  }
  /// The cloth rows (columns) [first, last] with a weight in panel row (column) p.
  std::pair<int, int> cloth_rows_of(int panel_row) const {
    return rows_.range[std::size_t(panel_row)];
  }
  std::pair<int, int> cloth_cols_of(int panel_col) const {
    return cols_.range[std::size_t(panel_col)];
  }

  /// One direction's weights, normalised per panel index: `table` dense
  /// [panel x cloth]; `range[p]` the cloth indices [first, last] with a weight
  /// in panel index p; `panels_of[i]` the panel indices [first, last] in which
  /// cloth index i has a weight (at most three).
  struct Axis {
    std::vector<double> table;
    std::vector<std::pair<int, int>> range, panels_of;
  };

 private:
  Lattice panels_;
  int cloth_rows_, cloth_cols_;
  bool same_ = true;
  Axis rows_, cols_;
  template <int Fields>
  void sample_fields(const std::span<const Vec3> (&cloth)[Fields],
                     std::vector<double>* const (&to)[Fields]) const;

  /// [cloth rows x panel cols] between the two passes, three per field sampled at once
  mutable std::vector<double> half_[6];
};

}  // namespace flagsim::physics
