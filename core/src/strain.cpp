#include "flagsim/core/strain.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <vector>

namespace flagsim {

StrainStats link_strain(const Lattice& lattice, std::span<const Vec3> positions_m,
                        std::span<float> node_strain) {
  assert(positions_m.size() == lattice.node_count());
  assert(node_strain.empty() || node_strain.size() == lattice.node_count());
  const int rows = lattice.rows, cols = lattice.cols;
  const double sx = lattice.spacing_x_m, sy = lattice.spacing_y_m;
  // One row at a time: its row links, then the column links down to the next
  // row, each into a buffer that the node field reads (a node's links are the
  // row links k - 1 and k, the column links above and below it).
  std::vector<double> row_links(std::size_t(std::max(cols - 1, 0)));
  std::vector<double> above(std::size_t(cols), 0.0), below(std::size_t(cols), 0.0);
  double max_strain = 0.0, sum = 0.0;
  const auto strain_of = [](const Vec3& a, const Vec3& b, double rest) {
    return std::abs((b - a).norm() - rest) / rest;
  };
  for (int j = 0; j < rows; ++j) {
    const Vec3* here = positions_m.data() + lattice.index(j, 0);
    for (int k = 0; k + 1 < cols; ++k)
      row_links[std::size_t(k)] = strain_of(here[k], here[k + 1], sx);
    if (j + 1 < rows)
      for (int k = 0; k < cols; ++k) below[std::size_t(k)] = strain_of(here[k], here[k + cols], sy);
    else
      std::fill(below.begin(), below.end(), 0.0);
    for (int k = 0; k + 1 < cols; ++k) {
      max_strain = std::max(max_strain, row_links[std::size_t(k)]);
      sum += row_links[std::size_t(k)];
    }
    if (j + 1 < rows)
      for (int k = 0; k < cols; ++k) {
        max_strain = std::max(max_strain, below[std::size_t(k)]);
        sum += below[std::size_t(k)];
      }
    if (!node_strain.empty()) {
      float* out = node_strain.data() + lattice.index(j, 0);
      for (int k = 0; k < cols; ++k) {
        double s = std::max(above[std::size_t(k)], below[std::size_t(k)]);
        if (k > 0) s = std::max(s, row_links[std::size_t(k - 1)]);
        if (k + 1 < cols) s = std::max(s, row_links[std::size_t(k)]);
        out[k] = float(s);
      }
    }
    std::swap(above, below);
  }
  const double links = double(rows) * (cols - 1) + double(rows - 1) * cols;
  // A non-finite strain makes the sum non-finite (std::max may have dropped a
  // NaN): the statistics say so, never a silent 0. The node field of such a
  // frame is not meaningful; the run stops there as diverged, unwritten.
  if (!std::isfinite(sum))
    return {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  return {max_strain, sum / links};
}

}  // namespace flagsim
