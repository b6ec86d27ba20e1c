#include "flagsim/infill/wrinkles.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace flagsim::infill {

double bending_constant_k_r4(double fiber_modulus_pa, double fiber_radius_m) {
  const double r2 = fiber_radius_m * fiber_radius_m;
  return 0.5 * fiber_modulus_pa * std::numbers::pi / 4.0 * r2 * r2;  // eq. (10) times r^4
}

double turning_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 u = b - a, v = c - b;
  // atan2(|u x v|, u.v): accurate for small and large angles alike.
  return std::atan2(u.cross(v).norm(), u.dot(v));
}

double fiber_bending_energy(const Fiber& fiber, std::span<const Vec3> positions_m, double k_r4) {
  double total = 0.0;
  for (int i = 1; i < fiber.segments; ++i) {
    const double theta = turning_angle(positions_m[fiber.node(i - 1)], positions_m[fiber.node(i)],
                                       positions_m[fiber.node(i + 1)]);
    total += k_r4 * theta * theta;  // eqs. (1)-(2), summed: eq. (11)
  }
  return total;
}

double fiber_target_energy(const Fiber& fiber, std::span<const Vec3> positions_m, double k_prime) {
  const double chord = (positions_m[fiber.node(fiber.segments)] - positions_m[fiber.node(0)]).norm();
  const double off = chord - fiber.rest_length_m();
  return k_prime * fiber.rest_spacing_m * off * off;  // eq. (13), k' = k_prime h
}

bool rewrinkle_fiber(const Fiber& fiber, std::span<Vec3> positions_m, const Vec3& normal,
                     const WrinkleParams& params) {
  if (fiber.segments < 2) return false;
  const double energy = fiber_bending_energy(fiber, positions_m, params.k_r4);
  const double target = fiber_target_energy(fiber, positions_m, params.k_prime);
  const double scale = std::max(energy, target);
  if (scale <= 0.0 || std::abs(energy - target) <= params.tolerance * scale) return false;

  const Vec3 start = positions_m[fiber.node(0)];
  const Vec3 chord_vec = positions_m[fiber.node(fiber.segments)] - start;
  const double chord = chord_vec.norm();
  if (chord == 0.0) return false;
  const Vec3 along = chord_vec / chord;
  Vec3 across = normal - normal.dot(along) * along;
  if (across.norm() < 1e-12) return false;
  across.normalize();
  const double slack = fiber.rest_length_m() - chord;
  int half_waves = 0;
  double amplitude = 0.0;
  if (slack > 0.0 && params.k_r4 > 0.0) {
    const double m = chord / std::numbers::pi * std::sqrt(params.k_prime * slack / (2.0 * params.k_r4));
    // A half-wave needs 4 segments to be a wave and not a zigzag of the lattice.
    const int finest = std::max(1, fiber.segments / 4);
    half_waves = std::clamp(int(std::lround(m)), 1, finest);
    amplitude = 2.0 * chord / (half_waves * std::numbers::pi) * std::sqrt(slack / chord);
  }
  // The sign that best matches the present shape keeps a wrinkle on its side.
  double match = 0.0;
  for (int i = 1; i < fiber.segments; ++i) {
    const double s = double(i) / fiber.segments;
    const double offset = (positions_m[fiber.node(i)] - start - s * chord_vec).dot(across);
    match += offset * std::sin(half_waves * std::numbers::pi * s);
  }
  const double sign = match < 0.0 ? -1.0 : 1.0;
  for (int i = 1; i < fiber.segments; ++i) {
    const double s = double(i) / fiber.segments;
    positions_m[fiber.node(i)] =
        start + s * chord_vec + (sign * amplitude * std::sin(half_waves * std::numbers::pi * s)) * across;
  }
  return true;
}

}  // namespace flagsim::infill
