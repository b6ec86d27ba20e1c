#include "flagsim/coarse_physics/stretch_springs.hpp"

#include <algorithm>

namespace flagsim::physics {

void StretchSprings::add_forces(std::span<const Vec3> x_m, std::span<const Vec3>,
                                std::span<Vec3> forces_n) const {
  for (const LinkFamily& family : model_.links) {
    for_each_link(model_, family, [&](std::size_t a, std::size_t b, double k, double rest) {
      const Vec3 d = x_m[b] - x_m[a];
      const double length = d.norm();
      // f on a = k (|d| - S) d/|d|; a zero-length link has no direction and gets no force.
      const double scale = length > 0.0 ? k * (length - rest) / length : 0.0;
      const Vec3 f = scale * d;
      forces_n[a] += f;
      forces_n[b] -= f;
    });
  }
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
