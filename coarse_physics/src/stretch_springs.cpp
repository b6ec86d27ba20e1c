#include "flagsim/coarse_physics/stretch_springs.hpp"

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

}  // namespace flagsim::physics
