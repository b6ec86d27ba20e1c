#include "flagsim/core/strain.hpp"

#include <cassert>
#include <cmath>
#include <limits>

namespace flagsim {

StrainStats link_strain(const Lattice& lattice, std::span<const Vec3> positions_m) {
  assert(positions_m.size() == lattice.node_count());
  double max_strain = 0.0;
  double sum = 0.0;
  bool finite = true;
  auto visit = [&](const Vec3& a, const Vec3& b, double rest) {
    const double strain = std::abs((b - a).norm() - rest) / rest;
    finite = finite && std::isfinite(strain);
    max_strain = std::max(max_strain, strain);
    sum += strain;
  };
  const int rows = lattice.rows, cols = lattice.cols;
  for (int j = 0; j < rows; ++j) {
    for (int k = 0; k < cols; ++k) {
      const Vec3& here = positions_m[lattice.index(j, k)];
      if (k + 1 < cols) visit(here, positions_m[lattice.index(j, k + 1)], lattice.spacing_x_m);
      if (j + 1 < rows) visit(here, positions_m[lattice.index(j + 1, k)], lattice.spacing_y_m);
    }
  }
  const double links = double(rows) * (cols - 1) + double(rows - 1) * cols;
  if (!finite)
    return {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  return {max_strain, sum / links};
}

}  // namespace flagsim
