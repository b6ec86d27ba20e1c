#include "flagsim/coarse_physics/aero_force.hpp"

#include <cmath>

namespace flagsim::physics {

Vec3 triangle_aero_force(const Vec3& x0, const Vec3& x1, const Vec3& x2,
                         const Vec3& relative_velocity, const Wind& wind) {
  // c = 2 A n, so A n = c/2 and u.n = u.c/|c|.
  const Vec3 c = (x1 - x0).cross(x2 - x0);
  const double c_norm2 = c.squaredNorm();
  const Vec3& u = relative_velocity;
  const double speed = u.norm();
  if (c_norm2 == 0.0 || speed == 0.0) return Vec3::Zero();
  const double c_norm = std::sqrt(c_norm2);
  const double u_dot_c = u.dot(c);
  const double half_rho = 0.5 * wind.air_density_kg_m3;
  // drag: 1/2 rho C_d A (u.n)|u.n| n = 1/2 rho C_d (u.c)|u.c| c / (2 |c|^2)
  const Vec3 drag = (half_rho * wind.drag * u_dot_c * std::abs(u_dot_c) / (2.0 * c_norm2)) * c;
  // lift: with A (u.n) = (u.c)/2, n = c/|c| and u.n = (u.c)/|c|,
  // 1/2 rho C_l A (u.n) (|u| n - (u.n) u/|u|) = 1/2 rho C_l (u.c)/2 (|u| c/|c| - (u.c) u/(|c| |u|)).
  const Vec3 lift = (half_rho * wind.lift * u_dot_c / 2.0) *
                    (speed / c_norm * c - (u_dot_c / (c_norm * speed)) * u);
  return drag + lift;
}

AeroForce::AeroForce(const ClothModel& model, const Wind& wind, double areal_density_kg_m2,
                     double cloth_speed_bound_m_s)
    : lattice_(model.lattice),
      wind_(wind),
      areal_density_kg_m2_(areal_density_kg_m2),
      cloth_speed_bound_m_s_(cloth_speed_bound_m_s) {}

void AeroForce::add_forces(std::span<const Vec3> x_m, std::span<const Vec3> v_m_s,
                           std::span<Vec3> forces_n) const {
  const int rows = lattice_.rows, cols = lattice_.cols;
  const Vec3& wind = wind_.velocity_m_s;
  auto apply = [&](std::size_t a, std::size_t b, std::size_t c) {
    const Vec3 u = wind - (v_m_s[a] + v_m_s[b] + v_m_s[c]) / 3.0;
    const Vec3 third = triangle_aero_force(x_m[a], x_m[b], x_m[c], u, wind_) / 3.0;
    forces_n[a] += third;
    forces_n[b] += third;
    forces_n[c] += third;
  };
  for (int j = 0; j + 1 < rows; ++j) {
    for (int k = 0; k + 1 < cols; ++k) {
      const std::size_t n00 = lattice_.index(j, k), n01 = n00 + 1;
      const std::size_t n10 = n00 + std::size_t(cols), n11 = n10 + 1;
      apply(n00, n01, n10);
      apply(n01, n11, n10);
    }
  }
}

double AeroForce::velocity_rate_bound() const {
  // |dF/dv| of a node ~ (its share of area) rho (C_d + C_l) |u|, over its mass
  // (density * area): rho (C_d + C_l) |u| / density, with |u| <= |wind| + cloth speed.
  const double relative_speed = wind_.velocity_m_s.norm() + cloth_speed_bound_m_s_;
  return wind_.air_density_kg_m3 * (wind_.drag + wind_.lift) * relative_speed /
         areal_density_kg_m2_;
}

}  // namespace flagsim::physics
