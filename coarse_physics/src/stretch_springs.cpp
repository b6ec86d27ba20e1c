#include "flagsim/coarse_physics/stretch_springs.hpp"

#include <algorithm>
#include <cmath>

#include "flagsim/core/lanes.hpp"

// Lanes are passed by value only between inlined helpers of this file (core/lanes.hpp).
#pragma GCC diagnostic ignored "-Wpsabi"

namespace flagsim::physics {

namespace {
using lanes::Lanes;
using lanes::load;
using lanes::splat;
using lanes::store;
constexpr int kLanes = lanes::kWidth;

// Flat offset b - a of a family's links (positive for all four families).
long offset_of(const Lattice& lattice, const LinkFamily& family) {
  return long(family.row_step) * lattice.cols + family.col_step;
}
}  // namespace

FLAGSIM_LANES_CLONES void StretchSprings::family_forces(int family_index) const {
  // for_each_link's links, row by row, kLanes first nodes at a time: f on a =
  // k (|d| - S) d / |d| (a zero-length link has no direction and gets none),
  // 0 for a first node where the family has no link.
  const Lattice& lattice = model_.lattice;
  const LinkFamily& family = model_.links[std::size_t(family_index)];
  const int K = lattice.cols;
  const int k_begin = family.col_step < 0 ? 1 : 0;
  const int k_end = K - (family.col_step > 0 ? 1 : 0);
  const std::size_t offset = std::size_t(offset_of(lattice, family));
  const double edge_k = family.stiffness_n_m * family.edge_factor;
  const Lanes zero = splat(0.0), one = splat(1.0), rest = splat(family.rest_length_m);
  const Lanes iota = {0.0, 1.0, 2.0, 3.0};
  const double* const x[3] = {work_.x[0].data(), work_.x[1].data(), work_.x[2].data()};
  double* const out[3] = {work_.link[family_index][0].data() + work_.pad,
                          work_.link[family_index][1].data() + work_.pad,
                          work_.link[family_index][2].data() + work_.pad};
  for (int j = 0; j + family.row_step < lattice.rows; ++j) {
    // A link along the border is half a strip of cloth: edge_factor.
    const bool border_row = family.row_step == 0 && (j == 0 || j == lattice.rows - 1);
    const Lanes row_k = splat(border_row ? edge_k : family.stiffness_n_m);
    for (int k = 0; k < K; k += kLanes) {
      const std::size_t a = lattice.index(j, k);
      const Lanes dx = load(x[0] + a + offset) - load(x[0] + a);
      const Lanes dy = load(x[1] + a + offset) - load(x[1] + a);
      const Lanes dz = load(x[2] + a + offset) - load(x[2] + a);
      const Lanes length2 = (dx * dx + dy * dy) + dz * dz;
      Lanes length;
      for (int l = 0; l < kLanes; ++l) length[l] = std::sqrt(length2[l]);
      const Lanes column = splat(double(k)) + iota;
      const auto border_column = family.col_step == 0
                                     ? (column == zero) | (column == splat(double(K - 1)))
                                     : column < zero;  // none
      const Lanes stiffness = border_column ? splat(edge_k) : row_k;
      const auto has_length = length > zero;
      const Lanes scale =
          has_length ? stiffness * (length - rest) / (has_length ? length : one) : zero;
      const auto linked = (column >= splat(double(k_begin))) & (column < splat(double(k_end)));
      const Lanes fx = linked ? scale * dx : zero, fy = linked ? scale * dy : zero,
                  fz = linked ? scale * dz : zero;
      if (k + kLanes <= K) {
        store(out[0] + a, fx);
        store(out[1] + a, fy);
        store(out[2] + a, fz);
      } else {  // the row's last nodes: not into the next row's
        for (int l = 0; k + l < K; ++l) {
          out[0][a + std::size_t(l)] = fx[l];
          out[1][a + std::size_t(l)] = fy[l];
          out[2][a + std::size_t(l)] = fz[l];
        }
      }
    }
  }
}

FLAGSIM_LANES_CLONES void StretchSprings::sum_links() const {
  const std::size_t n = model_.lattice.node_count();
  std::array<std::size_t, 4> offset;
  for (std::size_t family = 0; family < 4; ++family)
    offset[family] = std::size_t(offset_of(model_.lattice, model_.links[family]));
  for (int axis = 0; axis < 3; ++axis) {
    double* const f = work_.f[axis].data();
    std::array<const double*, 4> link;
    for (std::size_t family = 0; family < 4; ++family)
      link[family] = work_.link[family][std::size_t(axis)].data() + work_.pad;
    // f -= the link ending at the node (first node n - offset), then f += the
    // link starting at it, family by family: the link loop's order. A missing
    // link adds or takes 0, which leaves the sum's bits as they are.
    std::size_t i = 0;
    for (; i + kLanes <= n; i += kLanes) {
      Lanes sum = load(f + i);
      for (std::size_t family = 0; family < 4; ++family) {
        sum = sum - load(link[family] + i - offset[family]);
        sum = sum + load(link[family] + i);
      }
      store(f + i, sum);
    }
    for (; i < n; ++i)
      for (std::size_t family = 0; family < 4; ++family)
        f[i] = (f[i] - link[family][i - offset[family]]) + link[family][i];
  }
}

void StretchSprings::add_forces(std::span<const Vec3> x_m, std::span<const Vec3>,
                                std::span<Vec3> forces_n) const {
  lanes::split(x_m, work_.x);
  lanes::split(forces_n, work_.f);
  for (int family = 0; family < 4; ++family) family_forces(family);
  sum_links();
  lanes::join(work_.f, forces_n);
}

double StretchSprings::energy(std::span<const Vec3> x_m) const {
  double total = 0.0;
  for (const LinkFamily& family : model_.links) {
    for_each_link(model_, family, [&](std::size_t a, std::size_t b, double k, double rest) {
      const double stretch = (x_m[b] - x_m[a]).norm() - rest;
      total += 0.5 * k * stretch * stretch;
    });
  }
  return total;
}

void StretchSprings::add_stiffness_bound(std::span<double> row_sum_n_m) const {
  // The Hessian of one link has blocks +-H with ||H|| = k along the link
  // (tension adds k*strain across it, covered by the integrator's safety factor).
  for (const LinkFamily& family : model_.links) {
    for_each_link(model_, family, [&](std::size_t a, std::size_t b, double k, double) {
      row_sum_n_m[a] += 2.0 * k;
      row_sum_n_m[b] += 2.0 * k;
    });
  }
}

StretchSprings::StretchSprings(const ClothModel& model) : model_(model) {
  for (const LinkFamily& family : model_.links)
    for_each_link(model_, family, [&](std::size_t a, std::size_t b, double, double) {
      links_.push_back({std::uint32_t(a), std::uint32_t(b)});
    });
  const Lattice& lattice = model_.lattice;
  const std::size_t n = lattice.node_count();
  // Room before the first node for the largest offset (a node with no link
  // ending at it reads a 0 there), and past the last for a lane's reads.
  work_.pad = std::size_t(lattice.cols) + 1;
  for (int axis = 0; axis < 3; ++axis) {
    work_.x[axis].assign(n + work_.pad + kLanes, 0.0);
    work_.f[axis].assign(n, 0.0);
    for (auto& family : work_.link) family[std::size_t(axis)].assign(work_.pad + n + kLanes, 0.0);
  }
}

void StretchSprings::linearize(std::span<const Vec3> x_m, std::span<const Vec3>, Definiteness how) {
  hessian_.resize(links_.size());
  std::size_t l = 0;
  for (const LinkFamily& family : model_.links) {
    for_each_link(model_, family, [&](std::size_t a, std::size_t b, double k, double rest) {
      const Vec3 d = x_m[b] - x_m[a];
      const double length = d.norm();
      Mat3& h = hessian_[l++];
      if (length == 0.0) {  // no direction: only the isotropic part survives
        h = Mat3::Zero();
        return;
      }
      const Vec3 n = d / length;
      double transverse = 1.0 - rest / length;
      if (how == Definiteness::kProjected) transverse = std::max(transverse, 0.0);
      const Mat3 nn = n * n.transpose();
      h = k * (nn + transverse * (Mat3::Identity() - nn));
    });
  }
}

void StretchSprings::add_stiffness_product(std::span<const Vec3> dx_m,
                                           std::span<Vec3> out_n) const {
  for (std::size_t l = 0; l < links_.size(); ++l) {
    const Link link = links_[l];
    const Vec3 f = hessian_[l] * (dx_m[link.a] - dx_m[link.b]);
    out_n[link.a] += f;
    out_n[link.b] -= f;
  }
}

void StretchSprings::add_stiffness_diagonal(std::span<Mat3> diagonal_n_m) const {
  for (std::size_t l = 0; l < links_.size(); ++l) {
    diagonal_n_m[links_[l].a] += hessian_[l];
    diagonal_n_m[links_[l].b] += hessian_[l];
  }
}

}  // namespace flagsim::physics
