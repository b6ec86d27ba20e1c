#include "flagsim/infill/fiber_projection.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace flagsim::infill {
namespace {

// Relative distance of a link of relative length `relative` outside `band`.
double outside(double relative, const LinkBand& band) {
  return std::max({0.0, band.lower - relative, relative - band.upper});
}

}  // namespace

FiberProjection::FiberProjection(const Lattice& fine)
    : lattice_(fine),
      inverse_mass_(fine.node_count(), 1.0),
      row_bands_(std::size_t(fine.rows) * std::size_t(fine.cols - 1)),
      col_bands_(std::size_t(fine.rows - 1) * std::size_t(fine.cols)) {
  const std::size_t lanes = std::size_t(std::max(fine.rows, fine.cols)) * kLanes;
  for (std::vector<double>* buffer :
       {&x_, &y_, &z_, &w_, &lower_, &upper_, &nx_, &ny_, &nz_, &length_, &diag_, &off_, &rhs_})
    buffer->resize(lanes);
  set_uniform_band(0.0);
}

void FiberProjection::hold(std::span<const std::uint8_t> held) {
  assert(held.size() == inverse_mass_.size());
  for (std::size_t i = 0; i < held.size(); ++i) inverse_mass_[i] = held[i] ? 0.0 : 1.0;
}

void FiberProjection::set_uniform_band(double band) {
  std::fill(row_bands_.begin(), row_bands_.end(), LinkBand{1.0 - band, 1.0 + band});
  std::fill(col_bands_.begin(), col_bands_.end(), LinkBand{1.0 - band, 1.0 + band});
}

// The lane loops below have a fixed trip count and no branches, so the
// compiler vectorises them across fibers; the AVX2 clone is picked at run time
// where the CPU has it (the same IEEE operations either way: same bits).
__attribute__((target_clones("avx2", "default"))) void FiberProjection::step_lanes(
    int links, double rest_m, double tolerance, int steps, int* steps_made) {
  constexpr int L = kLanes;
  const double inv_rest = 1.0 / rest_m, degenerate_m = 1e-12 * rest_m;
  double* __restrict x = x_.data();
  double* __restrict y = y_.data();
  double* __restrict z = z_.data();
  const double* __restrict w = w_.data();
  const double* __restrict lo = lower_.data();
  const double* __restrict hi = upper_.data();
  double* __restrict nx = nx_.data();
  double* __restrict ny = ny_.data();
  double* __restrict nz = nz_.data();
  double* __restrict inverse_pivot = diag_.data();
  double* __restrict c = off_.data();
  double* __restrict d = rhs_.data();
  double* __restrict length = length_.data();
  const int count = links * L;  // link a = i L + l joins node a and node a + L
  for (int step = 0; step < steps; ++step) {
    // Constraint values C_i = |x_{i+1} - x_i| - clamp(|.|, lower S, upper S)
    // (d = -C), link directions n_i, and each lane's worst excess.
    for (int a = 0; a < count; ++a) {
      const double dx = x[a + L] - x[a], dy = y[a + L] - y[a], dz = z[a + L] - z[a];
      length[a] = std::sqrt(dx * dx + dy * dy + dz * dz);
    }
    for (int a = 0; a < count; ++a) {
      const double relative = length[a] * inv_rest;
      d[a] = (std::min(std::max(relative, lo[a]), hi[a]) - relative) * rest_m;
      // A zero-length link has no direction; any unit vector keeps the system regular.
      const bool degenerate = length[a] <= degenerate_m;
      const double inv = 1.0 / (degenerate ? 1.0 : length[a]);
      nx[a] = degenerate ? 1.0 : (x[a + L] - x[a]) * inv;
      ny[a] = degenerate ? 0.0 : (y[a + L] - y[a]) * inv;
      nz[a] = degenerate ? 0.0 : (z[a + L] - z[a]) * inv;
    }
    double worst[L] = {};
    for (int i = 0; i < links; ++i)
      for (int l = 0; l < L; ++l) worst[l] = std::max(worst[l], std::abs(d[i * L + l]) * inv_rest);
    // A lane within tolerance makes no step (its right-hand side is zeroed).
    bool any = false;
    double moving[L];
    for (int l = 0; l < L; ++l) {
      moving[l] = worst[l] > tolerance ? 1.0 : 0.0;
      any = any || worst[l] > tolerance;
      *steps_made += worst[l] > tolerance ? 1 : 0;
    }
    if (!any) return;
    // (grad C) W (grad C)^T mu = -C is tridiagonal: diagonal w_i + w_{i+1},
    // off-diagonal A[i][i+1] = A[i+1][i] = -w_{i+1} (n_i . n_{i+1}). Thomas
    // algorithm, forward elimination: c' into c, d' into d.
    for (int l = 0; l < L; ++l) {
      const double diag = w[l] + w[l + L];
      const bool both_held = diag == 0.0;  // nothing to solve for
      inverse_pivot[l] = 1.0 / (both_held ? 1.0 : diag);
      d[l] = both_held ? 0.0 : d[l] * moving[l] * inverse_pivot[l];
    }
    for (int i = 0; i + 1 < links; ++i)
      for (int l = 0; l < L; ++l) {
        const int a = i * L + l, b = a + L;
        const double upper = -w[b] * (nx[a] * nx[b] + ny[a] * ny[b] + nz[a] * nz[b]);
        c[a] = upper * inverse_pivot[a];
        const double diag = w[b] + w[b + L];
        const bool both_held = diag == 0.0;
        inverse_pivot[b] = 1.0 / ((both_held ? 1.0 : diag) - upper * c[a]);
        d[b] = both_held ? 0.0 : (d[b] * moving[l] - upper * d[a]) * inverse_pivot[b];
      }
    // Back substitution: mu_i = d'_i - c'_i mu_{i+1}, into d.
    for (int i = links - 2; i >= 0; --i)
      for (int l = 0; l < L; ++l) {
        const int a = i * L + l;
        d[a] -= c[a] * d[a + L];
      }
    // dx_j = w_j (mu_{j-1} n_{j-1} - mu_j n_j); the ends have one link each.
    for (int l = 0; l < L; ++l) {
      x[l] -= w[l] * d[l] * nx[l];
      y[l] -= w[l] * d[l] * ny[l];
      z[l] -= w[l] * d[l] * nz[l];
      const int e = links * L + l, p = e - L;
      x[e] += w[e] * d[p] * nx[p];
      y[e] += w[e] * d[p] * ny[p];
      z[e] += w[e] * d[p] * nz[p];
    }
    for (int j = 1; j < links; ++j)
      for (int l = 0; l < L; ++l) {
        const int a = j * L + l, p = a - L;
        x[a] += w[a] * (d[p] * nx[p] - d[a] * nx[a]);
        y[a] += w[a] * (d[p] * ny[p] - d[a] * ny[a]);
        z[a] += w[a] * (d[p] * nz[p] - d[a] * nz[a]);
      }
  }
}

double FiberProjection::project_family(bool rows, std::span<Vec3> positions_m, double tolerance,
                                       int steps, int* steps_made) {
  const int J = lattice_.rows, K = lattice_.cols;
  const int fibers = rows ? J : K, links = rows ? K - 1 : J - 1;
  const std::size_t stride = rows ? 1 : std::size_t(K);
  const double rest_m = rows ? lattice_.spacing_x_m : lattice_.spacing_y_m;
  const auto first_of = [&](int f) { return rows ? lattice_.index(f, 0) : lattice_.index(0, f); };
  const auto band_of = [&](int f, int i) -> const LinkBand& {
    return rows ? row_bands_[std::size_t(f) * std::size_t(K - 1) + std::size_t(i)]
                : col_bands_[std::size_t(i) * std::size_t(K) + std::size_t(f)];
  };
  // Which fibers have a link outside its band by more than the tolerance:
  // squared lengths, so a fiber already in its bands costs no square root;
  // row-major order for both families (a column's links are K apart).
  fiber_worst_.assign(std::size_t(fibers), 0.0);
  const double inv_rest2 = 1.0 / (rest_m * rest_m);
  for (int j = 0; j < (rows ? J : J - 1); ++j) {
    const Vec3* here = positions_m.data() + lattice_.index(j, 0);
    const Vec3* next = rows ? here + 1 : here + K;
    const LinkBand* band = rows ? row_bands_.data() + std::size_t(j) * std::size_t(K - 1)
                                : col_bands_.data() + std::size_t(j) * std::size_t(K);
    for (int k = 0; k < (rows ? K - 1 : K); ++k) {
      const double relative2 = (next[k] - here[k]).squaredNorm() * inv_rest2;
      const double low = band[k].lower - tolerance, high = band[k].upper + tolerance;
      if (relative2 >= low * low && relative2 <= high * high) continue;
      double& worst_of_fiber = fiber_worst_[std::size_t(rows ? j : k)];
      worst_of_fiber = std::max(worst_of_fiber, outside(std::sqrt(relative2), band[k]));
    }
  }
  double worst = 0.0;
  active_.clear();
  for (int f = 0; f < fibers; ++f) {
    worst = std::max(worst, fiber_worst_[std::size_t(f)]);
    if (fiber_worst_[std::size_t(f)] > tolerance) active_.push_back(f);
  }
  // kLanes at a time; a short last group repeats its last fiber, written once.
  for (std::size_t g = 0; g < active_.size(); g += kLanes) {
    int lane_fiber[kLanes];
    for (int l = 0; l < kLanes; ++l)
      lane_fiber[l] = active_[std::min(g + std::size_t(l), active_.size() - 1)];
    for (int i = 0; i <= links; ++i)
      for (int l = 0; l < kLanes; ++l) {
        const std::size_t node = first_of(lane_fiber[l]) + std::size_t(i) * stride;
        const int a = i * kLanes + l;
        x_[a] = positions_m[node].x();
        y_[a] = positions_m[node].y();
        z_[a] = positions_m[node].z();
        w_[a] = inverse_mass_[node];
        if (i < links) {
          lower_[a] = band_of(lane_fiber[l], i).lower;
          upper_[a] = band_of(lane_fiber[l], i).upper;
        }
      }
    int lane_steps = 0;
    step_lanes(links, rest_m, tolerance, steps, &lane_steps);
    const int distinct = int(std::min<std::size_t>(kLanes, active_.size() - g));
    *steps_made += lane_steps;
    for (int i = 0; i <= links; ++i)
      for (int l = 0; l < distinct; ++l) {
        const int a = i * kLanes + l;
        positions_m[first_of(lane_fiber[l]) + std::size_t(i) * stride] = Vec3(x_[a], y_[a], z_[a]);
      }
  }
  return worst;
}

ProjectionReport FiberProjection::project(std::span<Vec3> positions_m, double tolerance,
                                          int max_rounds, int steps_per_fiber) {
  assert(positions_m.size() == lattice_.node_count());
  ProjectionReport report;
  for (int round = 1; round <= max_rounds; ++round) {
    report.rounds = round;
    const double worst =
        std::max(project_family(true, positions_m, tolerance, steps_per_fiber, &report.fiber_steps),
                 project_family(false, positions_m, tolerance, steps_per_fiber,
                                &report.fiber_steps));
    if (worst <= tolerance) {  // a whole round found nothing to move
      report.converged = true;
      report.worst_excess = worst;
      return report;
    }
  }
  report.worst_excess = worst_excess(positions_m);
  report.converged = report.worst_excess <= tolerance;
  return report;
}

double FiberProjection::worst_excess(std::span<const Vec3> positions_m) const {
  const int J = lattice_.rows, K = lattice_.cols;
  double worst = 0.0;
  for (int j = 0; j < J; ++j)
    for (int k = 0; k < K; ++k) {
      const Vec3& p = positions_m[lattice_.index(j, k)];
      if (k + 1 < K)
        worst = std::max(worst, outside((positions_m[lattice_.index(j, k + 1)] - p).norm() /
                                            lattice_.spacing_x_m,
                                        row_bands_[std::size_t(j) * (K - 1) + std::size_t(k)]));
      if (j + 1 < J)
        worst = std::max(worst, outside((positions_m[lattice_.index(j + 1, k)] - p).norm() /
                                            lattice_.spacing_y_m,
                                        col_bands_[std::size_t(j) * K + std::size_t(k)]));
    }
  return worst;
}

}  // namespace flagsim::infill
