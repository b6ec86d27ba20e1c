#include "flagsim/core/strain.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <vector>

#include "flagsim/core/lanes.hpp"

// Lanes (core/lanes.hpp) are passed by value only between inlined helpers of this
// file, never across an ABI boundary.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace flagsim {
namespace {

using lanes::Lanes;

// out[k] = |(|next[k] - here[k]| - rest) / rest| for k < n: strain_of's
// operations in its order (the squared length as Vec3::squaredNorm adds
// it), four links at a time.
FLAGSIM_LANES_CLONES void link_strains(const Vec3* here, const Vec3* next, int n, double rest_m,
                                       double* out) {
  constexpr int L = lanes::kWidth;
  const Lanes rest = lanes::splat(rest_m);
  int k = 0;
  for (; k + L <= n; k += L) {
    const Lanes length2 = lanes::squared_lengths(here + k, next + k);
    Lanes length;
    for (int l = 0; l < L; ++l) length[l] = std::sqrt(length2[l]);
    const Lanes difference = length - rest;
    Lanes excess;
    for (int l = 0; l < L; ++l) excess[l] = std::abs(difference[l]);
    lanes::store(out + k, excess / rest);
  }
  for (; k < n; ++k) out[k] = std::abs((next[k] - here[k]).norm() - rest_m) / rest_m;
}

// Adds the n values to four running sums and raises the running maximum (a
// NaN leaves the maximum, as std::max does, and makes the sum NaN).
FLAGSIM_LANES_CLONES void accumulate(const double* values, int n, double (&sum)[lanes::kWidth],
                                     double& max) {
  constexpr int L = lanes::kWidth;
  Lanes total = lanes::load(sum), largest = lanes::splat(max);
  int k = 0;
  for (; k + L <= n; k += L) {
    const Lanes v = lanes::load(values + k);
    total += v;
    largest = v > largest ? v : largest;
  }
  lanes::store(sum, total);
  for (int l = 0; l < L; ++l) max = std::max(max, largest[l]);
  for (; k < n; ++k) {
    sum[0] += values[k];
    max = std::max(max, values[k]);
  }
}

}  // namespace

StrainStats link_strain(const Lattice& lattice, std::span<const Vec3> positions_m,
                        std::span<float> node_strain) {
  assert(positions_m.size() == lattice.node_count());
  assert(node_strain.empty() || node_strain.size() == lattice.node_count());
  const int J = lattice.rows, K = lattice.cols;
  // Row by row: the row's links, then the column links down to the next row.
  // A node's strain is the largest of its (up to four) links' (float
  // conversion is monotonic, so the max of the converted strains is the
  // converted max). The sum in four partial sums (the mean's last bits follow
  // their order, not for_each_link's).
  const auto count = [](int n) { return std::size_t(std::max(n, 0)); };
  std::vector<double> along(count(K - 1)), down(count(K)), above(count(K), 0.0);
  double sum[lanes::kWidth] = {};
  double max_strain = 0.0;
  for (int j = 0; j < J; ++j) {
    const Vec3* row = positions_m.data() + lattice.index(j, 0);
    link_strains(row, row + 1, K - 1, lattice.spacing_x_m, along.data());
    accumulate(along.data(), K - 1, sum, max_strain);
    const bool last = j + 1 == J;
    if (!last) {
      link_strains(row, row + K, K, lattice.spacing_y_m, down.data());
      accumulate(down.data(), K, sum, max_strain);
    }
    if (node_strain.empty()) continue;
    float* out = node_strain.data() + lattice.index(j, 0);
    for (int k = 0; k < K; ++k) {
      float s = j > 0 ? float(above[std::size_t(k)]) : 0.0f;
      if (k > 0) s = std::max(s, float(along[std::size_t(k - 1)]));
      if (k + 1 < K) s = std::max(s, float(along[std::size_t(k)]));
      if (!last) s = std::max(s, float(down[std::size_t(k)]));
      out[k] = s;
    }
    std::swap(above, down);
  }
  const double total = (sum[0] + sum[1]) + (sum[2] + sum[3]);
  const std::size_t links =
      std::size_t(J) * std::size_t(K - 1) + std::size_t(J - 1) * std::size_t(K);
  // A non-finite strain makes the sum non-finite (the maximum may have dropped
  // a NaN): the statistics say so, never a silent 0. The node field of such a
  // frame is not meaningful; the run stops there as diverged, unwritten.
  if (!std::isfinite(total))
    return {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  return {max_strain, links ? total / double(links) : 0.0};
}

}  // namespace flagsim
