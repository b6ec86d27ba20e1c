#include "flagsim/coarse_physics/creased_bending.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>
#include <unsupported/Eigen/AutoDiff>

namespace flagsim::physics {

std::vector<double> fold_rest_angles(std::span<const Fold> folds, const Lattice& lattice) {
  const int rows = lattice.rows, cols = lattice.cols;
  // bending_triples' order: row triples (j, m) for m in 1..K-2, then column
  // triples (j, m) for j in 1..J-2.
  const std::size_t row_triples = std::size_t(rows) * std::size_t(std::max(0, cols - 2));
  const std::size_t col_triples = std::size_t(std::max(0, rows - 2)) * std::size_t(cols);
  std::vector<double> rest(row_triples + col_triples, 0.0);
  for (const Fold& fold : folds) {
    // A line along a column bends the rows (centres along k); along a row, the columns.
    const bool bends_rows = fold.axis == FoldAxis::kCol;
    const int nodes = bends_rows ? cols : rows;
    if (nodes < 3) continue;  // no interior node to fold at
    const double place = fold.at * (nodes - 1);
    const int before = int(std::floor(place));
    const double share_after = place - before;
    // The fibers it crosses: those of [from, to] along its line, a fiber on
    // an end within the flag by half (the strip of cloth it stands for is
    // half inside), so two stretches meeting there share it.
    const int fibers = bends_rows ? rows : cols;
    const auto stretch = [&](int fiber) {
      const double f = fibers > 1 ? double(fiber) / (fibers - 1) : 0.0;
      const double tolerance = 1e-9;
      if (f < fold.from - tolerance || f > fold.to + tolerance) return 0.0;
      const bool on_end = (std::abs(f - fold.from) <= tolerance && fold.from > 0.0) ||
                          (std::abs(f - fold.to) <= tolerance && fold.to < 1.0);
      return on_end ? 0.5 : 1.0;
    };
    const auto add = [&](int centre, double angle) {
      centre = std::clamp(centre, 1, nodes - 2);
      if (bends_rows)
        for (int j = 0; j < rows; ++j)
          rest[std::size_t(j) * std::size_t(cols - 2) + std::size_t(centre - 1)] +=
              stretch(j) * angle;
      else
        for (int k = 0; k < cols; ++k)
          rest[row_triples + std::size_t(centre - 1) * std::size_t(cols) + std::size_t(k)] +=
              stretch(k) * angle;
    };
    add(before, fold.angle_rad * (1.0 - share_after));
    if (share_after > 0.0) add(before + 1, fold.angle_rad * share_after);
  }
  for (double& angle : rest) angle = std::clamp(angle, -std::numbers::pi, std::numbers::pi);
  return rest;
}

std::vector<double> initial_crease_memory(std::span<const Fold> folds, const Lattice& lattice) {
  std::vector<double> memory = fold_rest_angles(folds, lattice);
  memory.resize(2 * memory.size(), 0.0);
  return memory;
}

std::unique_ptr<CreasedBending> make_creased_bending(const Scene& scene, const ClothModel& model,
                                                     bool plain) {
  const Material& material = model.material;
  if (!material.creased()) return nullptr;
  return std::make_unique<CreasedBending>(
      model, *material.bending_rigidity_j, *material.creases, 1.0 / scene.fps,
      initial_crease_memory(scene.flag.folds, model.lattice), plain);
}

CreasedBending::CreasedBending(const ClothModel& model, double rigidity_j, const Creases& creases,
                               double frame_s, std::vector<double> memory, bool plain)
    : triples_(bending_triples(model.lattice, rigidity_j)),
      memory_(std::move(memory)),
      creases_(creases),
      stretch_modulus_n_m_(model.material.stretch_modulus_n_m),
      hinge_tension_n_m_(rigidity_j / (creases.width_m * creases.width_m)),
      frame_s_(frame_s),
      plain_(plain ? 1.0 : 0.0) {
  assert(memory_.size() == 2 * triples_.size());
  const Lattice& lattice = model.lattice;
  const std::size_t row_triples =
      std::size_t(lattice.rows) * std::size_t(std::max(0, lattice.cols - 2));
  spacing_m_.resize(triples_.size());
  for (std::size_t t = 0; t < triples_.size(); ++t)
    spacing_m_[t] = t < row_triples ? lattice.spacing_x_m : lattice.spacing_y_m;
  // The fold axis of each triple: the cross fiber's chord through its centre.
  const auto at = [&](int j, int k) { return std::uint32_t(lattice.index(j, k)); };
  axis_.reserve(triples_.size());
  for (int j = 0; j < lattice.rows; ++j)
    for (int m = 1; m + 1 < lattice.cols; ++m)
      axis_.push_back({at(std::max(0, j - 1), m), at(std::min(lattice.rows - 1, j + 1), m)});
  for (int j = 1; j + 1 < lattice.rows; ++j)
    for (int m = 0; m < lattice.cols; ++m)
      axis_.push_back({at(j, std::min(lattice.cols - 1, m + 1)), at(j, std::max(0, m - 1))});
  assert(axis_.size() == triples_.size());
}

void CreasedBending::set_memory(std::span<const double> memory) {
  assert(memory.size() == memory_.size());
  std::copy(memory.begin(), memory.end(), memory_.begin());
}

namespace {

// Nodes of a triple's stencil: a, b, c, then the fold axis' ends p and m.
constexpr int kStencil = 5;

template <typename S>
using V3 = Eigen::Matrix<S, 3, 1>;

// The crease's energy over k_b (whole, or less the plain 1/2 |q|^2 with
// plain = 0) and its gradient at the stencil's nodes x (a, b, c, p, m), for a
// rest angle `rest` and rest link length s: E = 1/4 |q - r1|^2 + 1/4 |q - r2|^2,
// r1 = s ((cos rest - 1) u1 + sin rest n1) and r2 = s ((1 - cos rest) u2 +
// sin rest n2) the rest fold's q in the frames of the two links (u = e / |e|,
// n = t x e / |t x e|, the front normal of the link's side); false where a frame
// has no direction (a link of no length, or along the axis). S is double, or
// an automatic differentiation scalar for the Hessian.
template <typename S>
bool crease_gradient(const std::array<V3<S>, kStencil>& x, double s, double rest, double plain,
                     S& energy, std::array<V3<S>, kStencil>& gradient) {
  using std::sqrt;
  const V3<S> e1 = x[1] - x[0], e2 = x[2] - x[1], t = x[3] - x[4], q = e2 - e1;
  const V3<S> w1 = t.cross(e1), w2 = t.cross(e2);
  const S l1 = sqrt(e1.squaredNorm()), l2 = sqrt(e2.squaredNorm());
  const S m1 = sqrt(w1.squaredNorm()), m2 = sqrt(w2.squaredNorm());
  if (!(l1 > 0.0 && l2 > 0.0 && m1 > 0.0 && m2 > 0.0)) return false;
  const S il1 = 1.0 / l1, il2 = 1.0 / l2, im1 = 1.0 / m1, im2 = 1.0 / m2;
  const V3<S> u1 = e1 * il1, u2 = e2 * il2, n1 = w1 * im1, n2 = w2 * im2;
  const double bend = std::cos(rest) - 1.0, turn = std::sin(rest);
  const V3<S> d1 = q - s * (bend * u1 + turn * n1), d2 = q - s * (-bend * u2 + turn * n2);
  energy = 0.25 * (d1.squaredNorm() + d2.squaredNorm()) - (0.5 * (1.0 - plain)) * q.squaredNorm();
  // dE/dq, and through r1, r2 into the frames' unit vectors.
  const V3<S> g_q = 0.5 * (d1 + d2) - (1.0 - plain) * q;
  const V3<S> g_u1 = (-0.5 * s * bend) * d1, g_n1 = (-0.5 * s * turn) * d1;
  const V3<S> g_u2 = (0.5 * s * bend) * d2, g_n2 = (-0.5 * s * turn) * d2;
  // A unit vector v / |v| passes g on as (g - v^ (v^ . g)) / |v|.
  V3<S> g_e1 = (g_u1 - u1 * u1.dot(g_u1)) * il1 - g_q;
  V3<S> g_e2 = (g_u2 - u2 * u2.dot(g_u2)) * il2 + g_q;
  const V3<S> g_w1 = (g_n1 - n1 * n1.dot(g_n1)) * im1, g_w2 = (g_n2 - n2 * n2.dot(g_n2)) * im2;
  // w = t x e: dw . g = dt . (e x g) + de . (g x t).
  const V3<S> g_t = e1.cross(g_w1) + e2.cross(g_w2);
  g_e1 += g_w1.cross(t);
  g_e2 += g_w2.cross(t);
  gradient = {V3<S>(-g_e1), V3<S>(g_e1 - g_e2), g_e2, g_t, V3<S>(-g_t)};
  return true;
}

double signed_angle(const Vec3& xa, const Vec3& xb, const Vec3& xc, const Vec3& xp,
                    const Vec3& xm) {
  const Vec3 e1 = xb - xa, e2 = xc - xb, t = xp - xm;
  const double length = t.norm();
  if (!(length > 0.0)) return 0.0;
  const Vec3 tau = t / length;
  return std::atan2(e1.cross(e2).dot(tau), e1.dot(e2) - e1.dot(tau) * e2.dot(tau));
}

}  // namespace

std::vector<double> CreasedBending::angles(std::span<const Vec3> x_m) const {
  std::vector<double> theta(triples_.size());
  for (std::size_t t = 0; t < triples_.size(); ++t) {
    const BendingTriple& tr = triples_[t];
    theta[t] = signed_angle(x_m[tr.a], x_m[tr.b], x_m[tr.c], x_m[axis_[t][0]], x_m[axis_[t][1]]);
  }
  return theta;
}

std::vector<double> CreasedBending::hinge_shares(std::span<const Vec3> x_m) const {
  std::vector<double> phi(triples_.size());
  for (std::size_t t = 0; t < triples_.size(); ++t) {
    const BendingTriple& tr = triples_[t];
    const double strain =
        0.5 * ((x_m[tr.b] - x_m[tr.a]).norm() + (x_m[tr.c] - x_m[tr.b]).norm()) / spacing_m_[t] -
        1.0;
    const double tension = stretch_modulus_n_m_ * std::max(strain, 0.0);
    phi[t] = tension > 0.0 ? 1.0 / (1.0 + std::sqrt(hinge_tension_n_m_ / tension)) : 0.0;
  }
  return phi;
}

void CreasedBending::begin_frame(double time_s, std::span<const Vec3> x_m) {
  if (!(time_s > 0.0)) return;  // nothing was held before t = 0
  const double set = 1.0 - std::exp(-frame_s_ / creases_.set_time_s);
  const std::vector<double> theta = angles(x_m);
  std::vector<double> phi;  // only where a crease is held flatter than it
  const std::size_t n = triples_.size();
  for (std::size_t t = 0; t < n; ++t) {
    double& rest = memory_[t];
    double& held = memory_[n + t];
    held += (theta[t] - held) * set;
    // The side of the crease (of the held fold where there is none yet).
    const double side = rest != 0.0 ? std::copysign(1.0, rest) : std::copysign(1.0, held);
    if (side * held > std::max(std::abs(rest), creases_.yield_angle_rad)) {
      rest += (held - rest) * set;
    } else if (rest != 0.0 && side * theta[t] < std::abs(rest)) {
      if (phi.empty()) phi = hinge_shares(x_m);
      rest += (theta[t] - rest) * (1.0 - std::exp(-frame_s_ * phi[t] / creases_.relax_time_s));
    }
  }
}

void CreasedBending::add_forces(std::span<const Vec3> x_m, std::span<const Vec3>,
                                std::span<Vec3> forces_n) const {
  for (std::size_t t = 0; t < triples_.size(); ++t) {
    const auto [a, b, c, k] = triples_[t];
    const double rest = memory_[t];
    if (rest != 0.0) {
      const std::array<std::uint32_t, kStencil> nodes = {a, b, c, axis_[t][0], axis_[t][1]};
      std::array<Vec3, kStencil> x, gradient;
      for (int i = 0; i < kStencil; ++i) x[std::size_t(i)] = x_m[nodes[std::size_t(i)]];
      double energy = 0.0;
      if (crease_gradient(x, spacing_m_[t], rest, plain_, energy, gradient)) {
        for (int i = 0; i < kStencil; ++i)
          forces_n[nodes[std::size_t(i)]] -= k * gradient[std::size_t(i)];
        continue;
      }
    }
    // No crease (or a link of no length, which has no frame): -dE/dx of
    // 1/2 k |q|^2, as bending_springs does (the same bits).
    if (plain_ == 0.0) continue;
    const Vec3 kq = k * (x_m[a] - 2.0 * x_m[b] + x_m[c]);
    forces_n[a] -= kq;
    forces_n[b] += 2.0 * kq;
    forces_n[c] -= kq;
  }
}

double CreasedBending::energy(std::span<const Vec3> x_m) const {
  double total = 0.0;
  for (std::size_t t = 0; t < triples_.size(); ++t) {
    const auto [a, b, c, k] = triples_[t];
    const double rest = memory_[t];
    if (rest != 0.0) {
      const std::array<Vec3, kStencil> x = {x_m[a], x_m[b], x_m[c], x_m[axis_[t][0]],
                                            x_m[axis_[t][1]]};
      std::array<Vec3, kStencil> gradient;
      double energy = 0.0;
      if (crease_gradient(x, spacing_m_[t], rest, plain_, energy, gradient)) {
        total += k * energy;
        continue;
      }
    }
    total += 0.5 * plain_ * k * (x_m[a] - 2.0 * x_m[b] + x_m[c]).squaredNorm();
  }
  return total;
}

void CreasedBending::add_stiffness_bound(std::span<double> row_sum_n_m) const {
  // The plain part: k g g^T with g = (1, -2, 1), row sums 4k, 8k, 4k. The
  // crease part, on every triple whatever its rest angle now (plastic flow may
  // crease any of them later in the run): its Hessian's absolute row sums
  // over k, at most kCreaseRowSum at the fiber's nodes and kAxisRowSum at
  // the axis' ends for links within 30% of their rest length
  // (tests/coarse_physics/creased_bending_test.cpp samples it).
  for (std::size_t t = 0; t < triples_.size(); ++t) {
    const auto [a, b, c, k] = triples_[t];
    row_sum_n_m[a] += k * (4.0 * plain_ + kCreaseRowSum);
    row_sum_n_m[b] += k * (8.0 * plain_ + kCreaseRowSum);
    row_sum_n_m[c] += k * (4.0 * plain_ + kCreaseRowSum);
    row_sum_n_m[axis_[t][0]] += k * kAxisRowSum;
    row_sum_n_m[axis_[t][1]] += k * kAxisRowSum;
  }
}

void CreasedBending::linearize(std::span<const Vec3> x_m, std::span<const Vec3>, Definiteness how) {
  hessian_.resize(triples_.size());
  creased_.clear();
  using Scalar = Eigen::AutoDiffScalar<Eigen::Matrix<double, 3 * kStencil, 1>>;
  for (std::size_t t = 0; t < triples_.size(); ++t) {
    const auto [a, b, c, k] = triples_[t];
    hessian_[t] = plain_ * k * Mat3::Identity();  // no crease: bending_springs'
    const double rest = memory_[t];
    if (rest == 0.0) continue;
    CreasedBlock block{{a, b, c, axis_[t][0], axis_[t][1]}, {}};
    // x as automatic differentiation scalars: the Hessian is the derivative of the gradient.
    std::array<V3<Scalar>, kStencil> x;
    for (int i = 0; i < kStencil; ++i)
      for (int d = 0; d < 3; ++d)
        x[std::size_t(i)][d] = Scalar(x_m[block.nodes[std::size_t(i)]][d], 3 * kStencil, 3 * i + d);
    std::array<V3<Scalar>, kStencil> gradient;
    Scalar energy;
    if (!crease_gradient(x, spacing_m_[t], rest, plain_, energy, gradient)) continue;
    hessian_[t] = Mat3::Zero();  // the block holds all of it
    for (int i = 0; i < kStencil; ++i)
      for (int d = 0; d < 3; ++d)
        block.hessian.row(3 * i + d) = k * gradient[std::size_t(i)][d].derivatives().transpose();
    block.hessian = 0.5 * (block.hessian + block.hessian.transpose()).eval();
    if (how == Definiteness::kProjected) {
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 15, 15>> eigen(block.hessian);
      block.hessian = eigen.eigenvectors() * eigen.eigenvalues().cwiseMax(0.0).asDiagonal() *
                      eigen.eigenvectors().transpose();
    }
    creased_.push_back(block);
  }
}

void CreasedBending::add_stiffness_product(std::span<const Vec3> dx_m,
                                           std::span<Vec3> out_n) const {
  for (std::size_t t = 0; t < triples_.size(); ++t) {
    const auto [a, b, c, k] = triples_[t];
    const Vec3 hq = hessian_[t] * (dx_m[a] - 2.0 * dx_m[b] + dx_m[c]);
    out_n[a] += hq;
    out_n[b] -= 2.0 * hq;
    out_n[c] += hq;
  }
  for (const CreasedBlock& block : creased_) {
    Eigen::Matrix<double, 15, 1> dx;
    for (Eigen::Index i = 0; i < kStencil; ++i)
      dx.segment<3>(3 * i) = dx_m[block.nodes[std::size_t(i)]];
    const Eigen::Matrix<double, 15, 1> out = block.hessian * dx;
    for (Eigen::Index i = 0; i < kStencil; ++i)
      out_n[block.nodes[std::size_t(i)]] += out.segment<3>(3 * i);
  }
}

void CreasedBending::add_stiffness_diagonal(std::span<Mat3> diagonal_n_m) const {
  for (std::size_t t = 0; t < triples_.size(); ++t) {
    const auto [a, b, c, k] = triples_[t];
    diagonal_n_m[a] += hessian_[t];
    diagonal_n_m[b] += 4.0 * hessian_[t];
    diagonal_n_m[c] += hessian_[t];
  }
  // A node in two places of a stencil (the axis' end on the border is the
  // centre) takes the blocks between them too.
  for (const CreasedBlock& block : creased_)
    for (Eigen::Index i = 0; i < kStencil; ++i)
      for (Eigen::Index j = 0; j < kStencil; ++j)
        if (block.nodes[std::size_t(i)] == block.nodes[std::size_t(j)])
          diagonal_n_m[block.nodes[std::size_t(i)]] += block.hessian.block<3, 3>(3 * i, 3 * j);
}

}  // namespace flagsim::physics
