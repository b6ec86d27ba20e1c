#include "flagsim/infill/smooth/fiber_projection.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include "flagsim/core/lanes.hpp"
#include "flagsim/core/stop_request.hpp"

// Lanes (core/lanes.hpp) are passed by value only between inlined helpers of this
// file, never across an ABI boundary.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace flagsim::infill {
namespace {

// How far ahead along a column its gather asks for the nodes and bands it
// will read. A column's nodes are a row apart (18 kB at 513 x 769, a new page
// each), which the hardware prefetcher does not follow: without, gathering
// the columns cost more than solving them there, and the median frame 43 ms;
// 8 / 32 / 128 nodes ahead: 37 / 31 / 29-32 ms (one run each, this machine's
// noise is about 10%). Lattices whose columns stay in cache (257 x 385 and
// smaller) do not change beyond that noise.
constexpr int kPrefetchNodes = 32;

// Relative distance of a link of relative length `relative` outside `band`.
double outside(double relative, const LinkBand& band) {
  return std::max({0.0, band.lower - relative, relative - band.upper});
}

// Whether each of the `n` links from here[k] to next[k] is outside its squared
// bounds [low2[k], high2[k]]: `outside[k] |= 1` for every one that is (with
// `any_only`, only outside[0], for any of them). Four links at a time; the
// squared lengths are those of Vec3::squaredNorm (the same operations in the
// same order), so the flags are the scalar loop's.
FLAGSIM_LANES_CLONES void flag_outside(const Vec3* here, const Vec3* next, const double* low2,
                                       const double* high2, int n, bool any_only,
                                       std::uint8_t* outside) {
  using lanes::Lanes;
  constexpr int L = lanes::kWidth;
  int k = 0;
  auto any = lanes::splat(0.0) < lanes::splat(0.0);  // all false
  for (; k + L <= n; k += L) {
    const Lanes length2 = lanes::squared_lengths(here + k, next + k);
    const auto out = (length2 < lanes::load(low2 + k)) | (length2 > lanes::load(high2 + k));
    if (any_only) {
      any |= out;
    } else {
      for (int l = 0; l < L; ++l) outside[k + l] |= std::uint8_t(out[l] != 0);
    }
  }
  int tail = 0;
  for (; k < n; ++k) {
    const double length2 = (next[k] - here[k]).squaredNorm();
    const int out = int(length2 < low2[k]) | int(length2 > high2[k]);
    if (any_only)
      tail |= out;
    else
      outside[k] |= std::uint8_t(out);
  }
  if (any_only) {
    for (int l = 0; l < L; ++l) tail |= int(any[l] != 0);
    outside[0] |= std::uint8_t(tail);
  }
}

}  // namespace

FiberProjection::FiberProjection(const Lattice& fine)
    : lattice_(fine), inverse_mass_(fine.node_count(), 1.0), bands_(fine), fixed_(fine, 0) {
  const std::size_t lanes = std::size_t(std::max(fine.rows, fine.cols)) * kLanes;
  for (std::vector<double>* buffer : {&x_, &y_, &z_, &w_, &lower_, &upper_, &length_, &nx_, &ny_,
                                      &nz_, &diag_, &off_, &rhs_, &dx_, &dy_, &dz_})
    buffer->resize(lanes);
  set_uniform_band(0.0);
}

void FiberProjection::hold(std::span<const std::uint8_t> held) {
  assert(held.size() == inverse_mass_.size());
  for (std::size_t i = 0; i < held.size(); ++i) inverse_mass_[i] = held[i] ? 0.0 : 1.0;
  for_each_link(lattice_, [&](const Link& link) { fixed_[link] = held[link.a] && held[link.b]; });
}

void FiberProjection::set_uniform_band(double band) {
  bands_.fill(LinkBand{1.0 - band, 1.0 + band});
}

// The lanes as vectors of doubles (core/lanes.hpp).
using lanes::Lanes;
using lanes::load;
using lanes::splat;
using lanes::store;
static_assert(kLanes % lanes::kWidth == 0);

FLAGSIM_LANES_CLONES void FiberProjection::step_lanes(int links, int distinct, double rest_m,
                                                      double tolerance, int steps,
                                                      double relaxation, int* steps_made) {
  // Node i of the group's fiber l is at [i * kLanes + l]: H vectors of V fibers
  // each, whose arithmetic is written out side by side (`for (h ...)`) so the
  // serial recurrences of the H vectors overlap.
  constexpr int L = kLanes, V = lanes::kWidth, H = kLanes / lanes::kWidth;
  const Lanes zero = splat(0.0), one = splat(1.0), rest = splat(rest_m),
              inv_rest = splat(1.0 / rest_m), degenerate = splat(1e-12 * rest_m);
  double* const x = x_.data();
  double* const y = y_.data();
  double* const z = z_.data();
  const double* const w = w_.data();
  double* const nx = nx_.data();
  double* const ny = ny_.data();
  double* const nz = nz_.data();
  double* const inverse_pivot = diag_.data();
  double* const c = off_.data();
  double* const d = rhs_.data();
  double* const step_x = dx_.data();
  double* const step_y = dy_.data();
  double* const step_z = dz_.data();
  double* const link_length = length_.data();
  // Link a's direction n = (x_b - x_a) / |x_b - x_a|, in place. A zero-length
  // link has no direction; any unit vector keeps the system regular.
  const auto normalise = [&](int a) __attribute__((always_inline)) {
    const Lanes length = load(link_length + a);
    const auto is_degenerate = length <= degenerate;
    const Lanes inv = one / (is_degenerate ? one : length);
    store(nx + a, is_degenerate ? one : load(nx + a) * inv);
    store(ny + a, is_degenerate ? zero : load(ny + a) * inv);
    store(nz + a, is_degenerate ? zero : load(nz + a) * inv);
  };
  for (int step = 0; step < steps; ++step) {
    // Constraint values C_i = |x_{i+1} - x_i| - clamp(|.|, lower S, upper S)
    // (d = -C), the links' lengths and unnormalised directions, and each
    // lane's worst excess. The directions are normalised only if a lane moves,
    // inside the forward elimination below (whose serial recurrence leaves the
    // divider idle): about half of these passes find every lane within
    // tolerance and end the fibers' steps.
    Lanes worst[H];
    for (int h = 0; h < H; ++h) worst[h] = zero;
    for (int i = 0; i < links; ++i) {
#pragma GCC unroll 2
      for (int h = 0; h < H; ++h) {
        const int a = i * L + h * V, b = a + L;
        const Lanes dx = load(x + b) - load(x + a), dy = load(y + b) - load(y + a),
                    dz = load(z + b) - load(z + a);
        Lanes length;
        const Lanes length2 = dx * dx + dy * dy + dz * dz;
        for (int l = 0; l < V; ++l) length[l] = std::sqrt(length2[l]);
        const Lanes relative = length * inv_rest;
        const Lanes low = load(lower_.data() + a), high = load(upper_.data() + a);
        Lanes target = relative < low ? low : relative;
        target = target > high ? high : target;
        const Lanes error = target - relative;
        const Lanes magnitude = error < zero ? -error : error;
        worst[h] = magnitude > worst[h] ? magnitude : worst[h];
        store(d + a, error * rest);
        store(link_length + a, length);
        store(nx + a, dx);
        store(ny + a, dy);
        store(nz + a, dz);
      }
    }
    // A lane within tolerance makes no step (its right-hand side is zeroed).
    Lanes moving[H];
    bool any = false;
    for (int h = 0; h < H; ++h) {
      const auto moves = worst[h] > splat(tolerance);
      for (int l = 0; l < V; ++l) {
        any = any || moves[l];
        *steps_made += moves[l] && h * V + l < distinct ? 1 : 0;
      }
      moving[h] = moves ? one : zero;
    }
    if (!any) return;
    const Lanes damping = splat(kDamping);
    // (grad C) W (grad C)^T mu = -C is tridiagonal: diagonal w_i + w_{i+1},
    // off-diagonal A[i][i+1] = A[i+1][i] = -w_{i+1} (n_i . n_{i+1}). Thomas
    // algorithm, forward elimination: c' into c, d' into d. A link with both
    // ends held has nothing to solve for (diagonal 1, right-hand side 0).
    for (int h = 0; h < H; ++h) {
      const int a = h * V;
      normalise(a);
      const Lanes diag = load(w + a) + load(w + a + L) + damping;
      const auto both_held = diag == damping;
      store(inverse_pivot + a, one / (both_held ? one : diag));
      store(d + a, both_held ? zero : load(d + a) * moving[h] * load(inverse_pivot + a));
    }
    for (int i = 0; i + 1 < links; ++i) {
#pragma GCC unroll 2
      for (int h = 0; h < H; ++h) {
        const int a = i * L + h * V, b = a + L;
        normalise(b);
        const Lanes upper =
            -load(w + b) * (load(nx + a) * load(nx + b) + load(ny + a) * load(ny + b) +
                            load(nz + a) * load(nz + b));
        const Lanes ca = upper * load(inverse_pivot + a);
        store(c + a, ca);
        const Lanes diag = load(w + b) + load(w + b + L) + damping;
        const auto both_held = diag == damping;
        const Lanes ib = one / ((both_held ? one : diag) - upper * ca);
        store(inverse_pivot + b, ib);
        store(d + b, both_held ? zero : (load(d + b) * moving[h] - upper * load(d + a)) * ib);
      }
    }
    // Back substitution: mu_i = d'_i - c'_i mu_{i+1}, into d.
    for (int i = links - 2; i >= 0; --i) {
#pragma GCC unroll 2
      for (int h = 0; h < H; ++h) {
        const int a = i * L + h * V;
        store(d + a, load(d + a) - load(c + a) * load(d + a + L));
      }
    }
    // dx_j = w_j (mu_{j-1} n_{j-1} - mu_j n_j); the ends have one link each.
    // Trust region: no node moves more than kMaxStep of the fiber's length in
    // a step. A fiber held at both ends and too short along a straight line
    // has no solution along itself (the linearised system is singular there);
    // the step is then bounded instead of unbounded.
    Lanes largest2[H];
    for (int h = 0; h < H; ++h) largest2[h] = zero;
    for (int j = 0; j <= links; ++j) {
#pragma GCC unroll 2
      for (int h = 0; h < H; ++h) {
        const int a = j * L + h * V, p = a - L;
        Lanes fx = zero, fy = zero, fz = zero;
        if (j > 0) {
          const Lanes mu = load(d + p);
          fx += mu * load(nx + p);
          fy += mu * load(ny + p);
          fz += mu * load(nz + p);
        }
        if (j < links) {
          const Lanes mu = load(d + a);
          fx -= mu * load(nx + a);
          fy -= mu * load(ny + a);
          fz -= mu * load(nz + a);
        }
        const Lanes wj = load(w + a);
        fx *= wj;
        fy *= wj;
        fz *= wj;
        store(step_x + a, fx);
        store(step_y + a, fy);
        store(step_z + a, fz);
        const Lanes step2 = fx * fx + fy * fy + fz * fz;
        largest2[h] = step2 > largest2[h] ? step2 : largest2[h];
      }
    }
    Lanes scale[H];
    const double limit = kMaxStep * links * rest_m;
    for (int h = 0; h < H; ++h) {
      scale[h] = splat(relaxation);
      for (int l = 0; l < V; ++l)
        if (!(largest2[h][l] <= limit * limit))
          scale[h][l] = std::isfinite(largest2[h][l])
                            ? std::min(scale[h][l], limit / std::sqrt(largest2[h][l]))
                            : 0.0;
    }
    for (int j = 0; j <= links; ++j) {
#pragma GCC unroll 2
      for (int h = 0; h < H; ++h) {
        const int a = j * L + h * V;
        store(x + a, load(x + a) + scale[h] * load(step_x + a));
        store(y + a, load(y + a) + scale[h] * load(step_y + a));
        store(z + a, load(z + a) + scale[h] * load(step_z + a));
      }
    }
  }
}

bool FiberProjection::project_family(bool rows, std::span<Vec3> positions_m, double tolerance,
                                     int steps, double relaxation, int* steps_made,
                                     int* fibers_outside, bool check) {
  const int J = lattice_.rows, K = lattice_.cols;
  const int fibers = rows ? J : K, links = rows ? K - 1 : J - 1;
  const std::size_t stride = rows ? 1 : std::size_t(K);
  const double rest_m = rows ? lattice_.spacing_x_m : lattice_.spacing_y_m;
  const auto first_of = [&](int f) { return rows ? lattice_.index(f, 0) : lattice_.index(0, f); };
  // Which fibers have a link outside its band by more than the tolerance:
  // squared lengths against squared bounds (set up by project()), no square
  // root and no branch, row-major order for both families (a column's links
  // are K apart), four links at a time (flag_outside).
  //
  // Only links that can have changed since they were last found inside are
  // looked at again: a fiber of this family solved in its last pass is
  // checked whole; any other was inside at that pass's check, and since then
  // only the other family's fibers solved after it have moved its nodes (a
  // fiber moves no node off itself): the row links beside a column solved in
  // the last column pass, the column links beside a row solved in this
  // round's row pass. The flags are those of checking every link. Where more
  // than half of a line's links would be looked at, the whole line is (in
  // lanes).
  const int family = rows ? 0 : 1;
  const int steps_before = *steps_made;
  fiber_flag_.assign(std::size_t(fibers), check ? 0 : 1);
  const std::vector<double>& low2 = rows ? row_low2_ : col_low2_;
  const std::vector<double>& high2 = rows ? row_high2_ : col_high2_;
  // flag_outside of the one link from `node` (its bounds at `link`) into *flag.
  const auto flag_link = [&](std::size_t node, std::size_t link, std::uint8_t* flag) {
    flag_outside(positions_m.data() + node, positions_m.data() + node + stride, low2.data() + link,
                 high2.data() + link, 1, rows, flag);
  };
  if (check) {
    // The other family's fibers solved since: which link positions of a line they touch.
    const int positions = rows ? K - 1 : J - 1;
    dirty_.assign(std::size_t(positions), 0);
    for (const int moved : solved_[1 - family]) {
      if (moved > 0) dirty_[std::size_t(moved - 1)] = 1;
      if (moved < positions) dirty_[std::size_t(moved)] = 1;
    }
    dirty_list_.clear();
    for (int at = 0; at < positions; ++at)
      if (dirty_[std::size_t(at)]) dirty_list_.push_back(at);
    const std::vector<int>& again = solved_[family];  // this family's fibers solved last pass
    if (rows) {
      const bool whole = 2 * dirty_list_.size() > std::size_t(positions);
      std::size_t next_solved = 0;
      for (int j = 0; j < J; ++j) {
        const bool solved = next_solved < again.size() && again[next_solved] == j;
        if (solved) ++next_solved;
        const std::size_t node = lattice_.index(j, 0), first = std::size_t(j) * std::size_t(K - 1);
        if (whole || solved) {
          flag_outside(positions_m.data() + node, positions_m.data() + node + 1,
                       low2.data() + first, high2.data() + first, K - 1, true,
                       &fiber_flag_[std::size_t(j)]);
        } else {
          for (const int k : dirty_list_) {
            flag_link(node + std::size_t(k), first + std::size_t(k), &fiber_flag_[std::size_t(j)]);
            if (fiber_flag_[std::size_t(j)]) break;
          }
        }
      }
    } else {
      const bool whole = 2 * again.size() > std::size_t(K);
      for (int j = 0; j + 1 < J; ++j) {
        const std::size_t node = lattice_.index(j, 0), first = std::size_t(j) * std::size_t(K);
        if (whole || dirty_[std::size_t(j)]) {
          flag_outside(positions_m.data() + node, positions_m.data() + node + K,
                       low2.data() + first, high2.data() + first, K, false, fiber_flag_.data());
        } else {
          for (const int k : again)
            if (!fiber_flag_[std::size_t(k)])
              flag_link(node + std::size_t(k), first + std::size_t(k),
                        &fiber_flag_[std::size_t(k)]);
        }
      }
    }
  }
  active_.clear();
  for (int f = 0; f < fibers; ++f)
    if (fiber_flag_[std::size_t(f)]) active_.push_back(f);
  *fibers_outside = int(active_.size());
  solved_[family] = active_;
  // kLanes at a time; a short last group repeats its last fiber, written once.
  // Each lane reads its fiber through base pointers: node i of the fiber at
  // node[l][i * stride], link i's band at band[l][i * stride] (a column's
  // links are K apart, as its nodes).
  for (std::size_t g = 0; g < active_.size(); g += kLanes) {
    Vec3* node[kLanes];
    const double* mass[kLanes];
    const LinkBand* band[kLanes];
    for (int l = 0; l < kLanes; ++l) {
      const int f = active_[std::min(g + std::size_t(l), active_.size() - 1)];
      const std::size_t first = first_of(f);
      node[l] = positions_m.data() + first;
      mass[l] = inverse_mass_.data() + first;
      band[l] = rows ? &bands_.row(f, 0) : &bands_.col(0, f);
    }
    for (int i = 0; i <= links; ++i) {
      const std::size_t at = std::size_t(i) * stride;
      if (!rows && i + kPrefetchNodes <= links) {  // a column's nodes are a row apart
        const std::size_t ahead = at + std::size_t(kPrefetchNodes) * stride;
        for (int l = 0; l < kLanes; ++l) {
          __builtin_prefetch(node[l] + ahead);
          __builtin_prefetch(mass[l] + ahead);
          if (i + kPrefetchNodes < links) __builtin_prefetch(band[l] + ahead);
        }
      }
      for (int l = 0; l < kLanes; ++l) {
        const int a = i * kLanes + l;
        const Vec3& p = node[l][at];
        x_[a] = p.x();
        y_[a] = p.y();
        z_[a] = p.z();
        w_[a] = mass[l][at];
      }
      if (i < links)
        for (int l = 0; l < kLanes; ++l) {
          const LinkBand& b = band[l][at];
          lower_[i * kLanes + l] = b.lower;
          upper_[i * kLanes + l] = b.upper;
        }
    }
    const int distinct = int(std::min<std::size_t>(kLanes, active_.size() - g));
    step_lanes(links, distinct, rest_m, tolerance, steps, relaxation, steps_made);
    for (int i = 0; i <= links; ++i) {
      const std::size_t at = std::size_t(i) * stride;
      for (int l = 0; l < distinct; ++l) {
        const int a = i * kLanes + l;
        node[l][at] = Vec3(x_[a], y_[a], z_[a]);
      }
    }
  }
  return *steps_made > steps_before;  // a fiber flagged but within tolerance after all: no move
}

ProjectionReport FiberProjection::project(std::span<Vec3> positions_m, double tolerance,
                                          int max_rounds, int steps_per_fiber) {
  assert(positions_m.size() == lattice_.node_count());
  ProjectionReport report;
  // The bounds of every link with the tolerance, squared, in m^2; a link with
  // both ends held cannot be moved: never out of bounds (hold() marks them).
  const auto squared_bounds = [tolerance](std::span<const LinkBand> bands,
                                          std::span<const std::uint8_t> fixed, double rest_m,
                                          std::vector<double>& low2, std::vector<double>& high2) {
    low2.resize(bands.size());
    high2.resize(bands.size());
    for (std::size_t i = 0; i < bands.size(); ++i) {
      const double low = std::max(0.0, bands[i].lower - tolerance) * rest_m;
      const double high = (bands[i].upper + tolerance) * rest_m;
      low2[i] = fixed[i] ? 0.0 : low * low;
      high2[i] = fixed[i] ? std::numeric_limits<double>::infinity() : high * high;
    }
  };
  squared_bounds(bands_.rows(), fixed_.rows(), lattice_.spacing_x_m, row_low2_, row_high2_);
  squared_bounds(bands_.cols(), fixed_.cols(), lattice_.spacing_y_m, col_low2_, col_high2_);
  int outside_before = std::numeric_limits<int>::max();
  for (int round = 1; round <= max_rounds && !stop_requested(); ++round) {
    report.rounds = round;
    // The first round solves every fiber without checking first: nearly all
    // need a step then (a fiber that does not returns before its first one).
    const bool check = round > 1;
    int rows_outside = 0, cols_outside = 0;
    const bool rows_moved =
        project_family(true, positions_m, tolerance, steps_per_fiber, report.relaxation,
                       &report.fiber_steps, &rows_outside, check);
    const bool cols_moved =
        project_family(false, positions_m, tolerance, steps_per_fiber, report.relaxation,
                       &report.fiber_steps, &cols_outside, check);
    // Counted from the second round on (the first solves every fiber unchecked).
    if (check) {
      const int outside = rows_outside + cols_outside;
      if (outside > outside_before) report.relaxation = kUnderRelaxation;
      outside_before = outside;
    }
    if (!rows_moved && !cols_moved) {  // a whole round found nothing to move
      report.converged = true;
      return report;
    }
  }
  report.worst_excess = worst_excess(positions_m);
  report.converged = report.worst_excess <= tolerance;
  return report;
}

double FiberProjection::worst_excess(std::span<const Vec3> positions_m) const {
  // A link with both ends held cannot be moved: not counted (as in project()).
  double worst = 0.0;
  for_each_link(lattice_, [&](const Link& link) {
    if (!fixed_[link])
      worst = std::max(
          worst,
          outside((positions_m[link.b] - positions_m[link.a]).norm() / link.rest_m, bands_[link]));
  });
  return worst;
}

}  // namespace flagsim::infill
