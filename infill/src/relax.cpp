#include "flagsim/infill/relax.hpp"

#include <algorithm>
#include <cmath>

namespace flagsim::infill {
namespace {

// One link of 3.4: moves a and b along their link to distance `rest` (half
// each; all of it on the free one if the other is held). Returns |d - S| / S
// before the move. The same projection as project_distance(), written for the
// hot loop: one square root, one division.
inline double relax_link(Vec3& a, Vec3& b, bool a_held, bool b_held, double rest, double inv_rest) {
  const Vec3 d = b - a;
  const double length2 = d.squaredNorm();
  if (length2 == 0.0) return 1.0;
  const double length = std::sqrt(length2);
  const double error = std::abs(length * inv_rest - 1.0);
  if (a_held && b_held) return error;
  const double shrink = 1.0 - rest / length;  // fraction of d that closes the gap
  if (a_held) {
    b -= shrink * d;
  } else if (b_held) {
    a += shrink * d;
  } else {
    const Vec3 half = (0.5 * shrink) * d;
    a += half;
    b -= half;
  }
  return error;
}

}  // namespace

int relax_lattice(const Lattice& lattice, std::span<const std::uint8_t> held,
                  std::span<Vec3> positions_m, int max_sweeps, double tolerance) {
  const int rows = lattice.rows, cols = lattice.cols;
  const double sx = lattice.spacing_x_m, sy = lattice.spacing_y_m;
  const double inv_sx = 1.0 / sx, inv_sy = 1.0 / sy;
  const std::size_t stride = std::size_t(cols);
  Vec3* x = positions_m.data();
  const std::uint8_t* h = held.data();
  for (int sweep = 1; sweep <= max_sweeps; ++sweep) {
    // Red-black order: row links from even columns, then odd; column links from
    // even rows, then odd. Links of one pass share no node, so each pass has
    // no chain of dependent updates and the CPU overlaps them (a plain
    // row-major sweep waits on every square root and division in turn).
    double worst = 0.0;
    for (int parity = 0; parity < 2; ++parity)
      for (int j = 0; j < rows; ++j) {
        const std::size_t row = std::size_t(j) * stride;
        for (int k = parity; k + 1 < cols; k += 2) {
          const std::size_t a = row + std::size_t(k);
          worst = std::max(worst, relax_link(x[a], x[a + 1], h[a], h[a + 1], sx, inv_sx));
        }
      }
    for (int parity = 0; parity < 2; ++parity)
      for (int j = parity; j + 1 < rows; j += 2) {
        const std::size_t row = std::size_t(j) * stride;
        for (int k = 0; k < cols; ++k) {
          const std::size_t a = row + std::size_t(k);
          worst = std::max(worst, relax_link(x[a], x[a + stride], h[a], h[a + stride], sy, inv_sy));
        }
      }
    if (worst <= tolerance) return sweep;
  }
  return max_sweeps;
}

}  // namespace flagsim::infill
