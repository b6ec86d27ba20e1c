#include "flagsim/coarse_physics/aero_force.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace flagsim::physics {

Vec3 triangle_aero_force(const Vec3& x0, const Vec3& x1, const Vec3& x2,
                         const Vec3& relative_velocity, const Wind& wind) {
  // With c = (x1 - x0) x (x2 - x0) = 2 A n and u_n = u.n = (u.c)/|c|:
  //   drag = 1/2 rho C_d A u_n |u_n| n                    = 1/4 rho C_d u_n |u_n| c
  //   lift = 1/2 rho C_l A u_n (|u| n - u_n u/|u|)        = 1/4 rho C_l u_n (|u| c - |c| u_n u/|u|)
  // Written with u.c, |c|^2 and r = |c| |u| only: one square root, two divisions.
  const Vec3 c = (x1 - x0).cross(x2 - x0);
  const Vec3& u = relative_velocity;
  const double c_norm2 = c.squaredNorm(), speed2 = u.squaredNorm();
  if (c_norm2 == 0.0 || speed2 == 0.0) return Vec3::Zero();
  const double u_dot_c = u.dot(c);
  const double r = std::sqrt(c_norm2 * speed2);  // |c| |u|
  const double inv_c_norm2 = 1.0 / c_norm2;
  const double quarter_rho = 0.25 * wind.air_density_kg_m3;
  // u_n |u_n| = (u.c)|u.c|/|c|^2,  u_n |u| = (u.c) r/|c|^2,  u_n^2 |c|/|u| = (u.c)^2/r
  const double along_c =
      quarter_rho * u_dot_c * inv_c_norm2 * (wind.drag * std::abs(u_dot_c) + wind.lift * r);
  const double along_u = quarter_rho * wind.lift * u_dot_c * u_dot_c / r;
  return along_c * c - along_u * u;
}

Mat3 triangle_aero_velocity_jacobian(const Vec3& x0, const Vec3& x1, const Vec3& x2,
                                     const Vec3& relative_velocity, const Wind& wind) {
  // F = alpha c - beta u with s = u.c, r = |c| |u|:
  //   alpha = q/|c|^2 (C_d s |s| + C_l s r),  beta = q C_l s^2 / r,  q = rho / 4;
  //   ds/du = c,  dr/du = |c|^2 u / r;
  //   dF/du = c (dalpha/du)^T - u (dbeta/du)^T - beta I.
  const Vec3 c = (x1 - x0).cross(x2 - x0);
  const Vec3& u = relative_velocity;
  const double c_norm2 = c.squaredNorm(), speed2 = u.squaredNorm();
  if (c_norm2 == 0.0 || speed2 == 0.0) return Mat3::Zero();
  const double s = u.dot(c);
  const double r = std::sqrt(c_norm2 * speed2);
  const double q = 0.25 * wind.air_density_kg_m3;
  const Vec3 dr = (c_norm2 / r) * u;
  const Vec3 dalpha =
      (q / c_norm2) * (wind.drag * 2.0 * std::abs(s) * c + wind.lift * (r * c + s * dr));
  const double beta = q * wind.lift * s * s / r;
  const Vec3 dbeta = q * wind.lift * ((2.0 * s / r) * c - (s * s / (r * r)) * dr);
  return c * dalpha.transpose() - u * dbeta.transpose() - beta * Mat3::Identity();
}

AeroForce::AeroForce(const ClothModel& model, const Wind& wind, std::uint64_t seed,
                     double areal_density_kg_m2, double cloth_speed_bound_m_s)
    : lattice_(model.lattice),
      wind_(wind),
      field_(wind, seed),
      areal_density_kg_m2_(areal_density_kg_m2),
      cloth_speed_bound_m_s_(cloth_speed_bound_m_s) {
  air_m_s_.assign(lattice_.node_count(), wind.velocity_m_s);
  begin_frame(0.0, lattice_.rest_positions());
}

void AeroForce::begin_frame(double time_s, std::span<const Vec3> x_m) {
  if (field_.steady()) return;  // the mean wind everywhere, set once
  for (std::size_t i = 0; i < air_m_s_.size(); ++i) air_m_s_[i] = field_.velocity(x_m[i], time_s);
}

template <typename Visit>
void AeroForce::for_each_triangle(Visit&& visit) const {
  const int rows = lattice_.rows, cols = lattice_.cols;
  for (int j = 0; j + 1 < rows; ++j) {
    for (int k = 0; k + 1 < cols; ++k) {
      const std::size_t n00 = lattice_.index(j, k), n01 = n00 + 1;
      const std::size_t n10 = n00 + std::size_t(cols), n11 = n10 + 1;
      visit(n00, n01, n10);
      visit(n01, n11, n10);
    }
  }
}

namespace {
constexpr double kThird = 1.0 / 3.0;  // multiply: Eigen's "/ 3.0" is three divisions
}  // namespace

void AeroForce::add_forces(std::span<const Vec3> x_m, std::span<const Vec3> v_m_s,
                           std::span<Vec3> forces_n) const {
  for_each_triangle([&](std::size_t a, std::size_t b, std::size_t c) {
    const Vec3 u =
        kThird * ((air_m_s_[a] + air_m_s_[b] + air_m_s_[c]) - (v_m_s[a] + v_m_s[b] + v_m_s[c]));
    const Vec3 third = kThird * triangle_aero_force(x_m[a], x_m[b], x_m[c], u, wind_);
    forces_n[a] += third;
    forces_n[b] += third;
    forces_n[c] += third;
  });
}

void AeroForce::linearize(std::span<const Vec3> x_m, std::span<const Vec3> v_m_s,
                          Definiteness how) {
  damping_.resize(2 * std::size_t(lattice_.rows - 1) * std::size_t(lattice_.cols - 1));
  std::size_t t = 0;
  for_each_triangle([&](std::size_t a, std::size_t b, std::size_t c) {
    const Vec3 u =
        kThird * ((air_m_s_[a] + air_m_s_[b] + air_m_s_[c]) - (v_m_s[a] + v_m_s[b] + v_m_s[c]));
    Mat3 block = (1.0 / 9.0) * triangle_aero_velocity_jacobian(x_m[a], x_m[b], x_m[c], u, wind_);
    if (how == Definiteness::kProjected) {
      const Mat3 symmetric = 0.5 * (block + block.transpose());
      Eigen::SelfAdjointEigenSolver<Mat3> eigen;
      eigen.computeDirect(symmetric);
      const Vec3 clamped = eigen.eigenvalues().cwiseMax(0.0);
      block = eigen.eigenvectors() * clamped.asDiagonal() * eigen.eigenvectors().transpose();
    }
    damping_[t++] = block;
  });
}

void AeroForce::add_damping_product(std::span<const Vec3> dv_m_s, std::span<Vec3> out_n) const {
  std::size_t t = 0;
  for_each_triangle([&](std::size_t a, std::size_t b, std::size_t c) {
    const Vec3 w = damping_[t++] * (dv_m_s[a] + dv_m_s[b] + dv_m_s[c]);
    out_n[a] += w;
    out_n[b] += w;
    out_n[c] += w;
  });
}

void AeroForce::add_damping_diagonal(std::span<Mat3> diagonal_n_s_m) const {
  std::size_t t = 0;
  for_each_triangle([&](std::size_t a, std::size_t b, std::size_t c) {
    const Mat3& block = damping_[t++];
    diagonal_n_s_m[a] += block;
    diagonal_n_s_m[b] += block;
    diagonal_n_s_m[c] += block;
  });
}

double AeroForce::velocity_rate_bound() const {
  // |dF/dv| of a node ~ (its share of area) rho (C_d + C_l) |u|, over its mass
  // (density * area): rho (C_d + C_l) |u| / density, with |u| <= |wind| + cloth speed.
  const double relative_speed = field_.speed_bound_m_s() + cloth_speed_bound_m_s_;
  return wind_.air_density_kg_m3 * (wind_.drag + wind_.lift) * relative_speed /
         areal_density_kg_m2_;
}

}  // namespace flagsim::physics
