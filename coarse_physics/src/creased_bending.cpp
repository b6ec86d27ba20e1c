#include "flagsim/coarse_physics/creased_bending.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

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
    const auto add = [&](int centre, double angle) {
      centre = std::clamp(centre, 1, nodes - 2);
      if (bends_rows)
        for (int j = 0; j < rows; ++j)
          rest[std::size_t(j) * std::size_t(cols - 2) + std::size_t(centre - 1)] += angle;
      else
        for (int k = 0; k < cols; ++k)
          rest[row_triples + std::size_t(centre - 1) * std::size_t(cols) + std::size_t(k)] += angle;
    };
    add(before, fold.angle_rad * (1.0 - share_after));
    if (share_after > 0.0) add(before + 1, fold.angle_rad * share_after);
  }
  for (double& angle : rest) angle = std::min(angle, std::numbers::pi);
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
  rest_m_.resize(triples_.size());
  for (std::size_t t = 0; t < triples_.size(); ++t) set_rest_length(t);
}

void CreasedBending::set_rest_length(std::size_t t) {
  rest_m_[t] = 2.0 * spacing_m_[t] * std::sin(0.5 * memory_[t]);
}

void CreasedBending::set_memory(std::span<const double> memory) {
  assert(memory.size() == memory_.size());
  std::copy(memory.begin(), memory.end(), memory_.begin());
  for (std::size_t t = 0; t < triples_.size(); ++t) set_rest_length(t);
}

std::vector<double> CreasedBending::angles(std::span<const Vec3> x_m) const {
  std::vector<double> theta(triples_.size());
  for (std::size_t t = 0; t < triples_.size(); ++t) {
    const BendingTriple& tr = triples_[t];
    const double q = (x_m[tr.a] - 2.0 * x_m[tr.b] + x_m[tr.c]).norm();
    theta[t] = 2.0 * std::asin(std::min(1.0, q / (2.0 * spacing_m_[t])));
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
    if (held > std::max(rest, creases_.yield_angle_rad)) {
      rest += (held - rest) * set;
    } else if (theta[t] < rest) {
      if (phi.empty()) phi = hinge_shares(x_m);
      rest += (theta[t] - rest) * (1.0 - std::exp(-frame_s_ * phi[t] / creases_.relax_time_s));
    } else {
      continue;
    }
    set_rest_length(t);
  }
}

namespace {

// dE/dq / k_b = (plain - c / R) q, with R = sqrt(|q|^2 + eps^2).
Vec3 scaled_gradient(const Vec3& q, double c, double eps, double plain) {
  if (c == 0.0) return plain * q;  // no crease: bending_springs' force, bit for bit
  return (plain - c / std::sqrt(q.squaredNorm() + eps * eps)) * q;
}

}  // namespace

void CreasedBending::add_forces(std::span<const Vec3> x_m, std::span<const Vec3>,
                                std::span<Vec3> forces_n) const {
  for (std::size_t t = 0; t < triples_.size(); ++t) {
    const auto [a, b, c, k] = triples_[t];
    const Vec3 q = x_m[a] - 2.0 * x_m[b] + x_m[c];
    const Vec3 g = k * scaled_gradient(q, rest_m_[t], kCreaseRounding * spacing_m_[t], plain_);
    forces_n[a] -= g;
    forces_n[b] += 2.0 * g;
    forces_n[c] -= g;
  }
}

double CreasedBending::energy(std::span<const Vec3> x_m) const {
  double total = 0.0;
  for (std::size_t t = 0; t < triples_.size(); ++t) {
    const auto [a, b, c, k] = triples_[t];
    const double q2 = (x_m[a] - 2.0 * x_m[b] + x_m[c]).squaredNorm();
    const double eps = kCreaseRounding * spacing_m_[t];
    total += 0.5 * plain_ * k * q2 - k * rest_m_[t] * (std::sqrt(q2 + eps * eps) - eps);
  }
  return total;
}

void CreasedBending::add_stiffness_bound(std::span<double> row_sum_n_m) const {
  // ||d2E/dq2|| <= k_b max(1, c / eps - 1) <= k_b (1 + c / eps) (the crease's part
  // alone: k_b c / eps); g g^T's row sums 4, 8, 4.
  for (std::size_t t = 0; t < triples_.size(); ++t) {
    const auto [a, b, c, k] = triples_[t];
    const double bound = k * (plain_ + rest_m_[t] / (kCreaseRounding * spacing_m_[t]));
    row_sum_n_m[a] += 4.0 * bound;
    row_sum_n_m[b] += 8.0 * bound;
    row_sum_n_m[c] += 4.0 * bound;
  }
}

void CreasedBending::linearize(std::span<const Vec3> x_m, std::span<const Vec3>, Definiteness how) {
  hessian_.resize(triples_.size());
  for (std::size_t t = 0; t < triples_.size(); ++t) {
    const auto [a, b, c, k] = triples_[t];
    const Vec3 q = x_m[a] - 2.0 * x_m[b] + x_m[c];
    const double eps = kCreaseRounding * spacing_m_[t], rest = rest_m_[t];
    const double q2 = q.squaredNorm(), r2 = q2 + eps * eps, r = std::sqrt(r2);
    // (1 - c / R) across q, 1 - c eps^2 / R^3 along it (less the 1 for the crease alone).
    double across = plain_ - rest / r, along = plain_ - rest * eps * eps / (r2 * r);
    if (how == Definiteness::kProjected) {
      across = std::max(across, 0.0);
      along = std::max(along, 0.0);
    }
    Mat3 h = across * Mat3::Identity();
    if (q2 > 0.0) h += ((along - across) / q2) * (q * q.transpose());
    hessian_[t] = k * h;
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
}

void CreasedBending::add_stiffness_diagonal(std::span<Mat3> diagonal_n_m) const {
  for (std::size_t t = 0; t < triples_.size(); ++t) {
    const auto [a, b, c, k] = triples_[t];
    diagonal_n_m[a] += hessian_[t];
    diagonal_n_m[b] += 4.0 * hessian_[t];
    diagonal_n_m[c] += hessian_[t];
  }
}

}  // namespace flagsim::physics
