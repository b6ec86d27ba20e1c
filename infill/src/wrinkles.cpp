#include "flagsim/infill/wrinkles.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

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
  const double chord =
      (positions_m[fiber.node(fiber.segments)] - positions_m[fiber.node(0)]).norm();
  const double off = chord - fiber.rest_length_m();
  return k_prime * fiber.rest_spacing_m * off * off;  // eq. (13), k' = k_prime h
}

namespace {

// The wave x = s c, y = A sin(m pi s), s in [0, 1], sampled finely enough that
// its polyline is its arc to well under the 0.5% relaxation tolerance. The
// sines are tabulated once per wave, in the wave's own table.
class Wave {
 public:
  Wave(double chord, int half_waves, int samples) : chord_(chord), samples_(samples) {
    std::vector<double>& table = table_;
    table.resize(std::size_t(samples) + 1);
    // sin(k a) by the recurrence sin((k+1) a) = 2 cos(a) sin(k a) - sin((k-1) a):
    // a few hundred steps stay within 1e-13 of std::sin, at a fraction of its cost.
    const double step = half_waves * std::numbers::pi / samples, twice_cos = 2.0 * std::cos(step);
    table[0] = 0.0;
    table[1] = std::sin(step);
    for (int k = 2; k <= samples; ++k)
      table[std::size_t(k)] = twice_cos * table[std::size_t(k - 1)] - table[std::size_t(k - 2)];
  }
  int samples() const { return samples_; }
  Eigen::Vector2d at(int sample, double amplitude) const {
    return {chord_ * sample / samples_, amplitude * table_[std::size_t(sample)]};
  }
  double length(double amplitude) const {
    const double dx2 = (chord_ / samples_) * (chord_ / samples_);
    double total = 0.0;
    for (int k = 1; k <= samples_; ++k) {
      const double dy = amplitude * (table_[std::size_t(k)] - table_[std::size_t(k - 1)]);
      total += std::sqrt(dx2 + dy * dy);  // not std::hypot: no overflow here, 5x faster
    }
    return total;
  }
  /// The amplitude whose wave is `length` long, by the secant method from the
  /// small-slope estimate (which alone is too long at large slopes: relaxing the
  /// surplus folds the crests).
  double amplitude_for(double length, int half_waves) const {
    const double slack = length - chord_;
    double a0 = 2.0 * chord_ / (half_waves * std::numbers::pi) * std::sqrt(slack / chord_);
    double a1 = 0.9 * a0;
    double f0 = this->length(a0) - length, f1 = this->length(a1) - length;
    for (int iteration = 0; iteration < 30 && std::abs(f1) > 1e-12 * length && f1 != f0;
         ++iteration) {
      const double a2 = std::max(0.0, a1 - f1 * (a1 - a0) / (f1 - f0));
      a0 = a1;
      f0 = f1;
      a1 = a2;
      f1 = this->length(a1) - length;
    }
    return a1;
  }

 private:
  double chord_;
  int samples_;
  std::vector<double> table_;  ///< sin(k pi m / samples), k = 0 .. samples
};

}  // namespace

double wave_amplitude_m(double chord_m, double length_m, int half_waves, int segments) {
  if (length_m <= chord_m) return 0.0;
  const Wave wave(chord_m, half_waves, 4 * segments);
  return wave.amplitude_for(length_m, half_waves);
}

int half_wave_count(double chord_m, double slack_m, int segments, const WrinkleParams& params) {
  const double m =
      chord_m / std::numbers::pi * std::sqrt(params.k_prime * slack_m / (2.0 * params.k_r4));
  // A half-wave needs 4 segments to be a wave and not a zigzag of the lattice.
  const int finest = std::max(1, segments / 4);
  return std::clamp(int(std::lround(m)), 1, finest);
}

bool rewrinkle_fiber(const Fiber& fiber, std::span<Vec3> positions_m, const Vec3& normal,
                     const WrinkleParams& params) {
  if (fiber.segments < 2) return false;
  const double energy = fiber_bending_energy(fiber, positions_m, params.k_r4);
  const double target = fiber_target_energy(fiber, positions_m, params.k_prime);
  const double scale = std::max(energy, target);
  if (scale <= 0.0 || std::abs(energy - target) < params.tolerance * scale) return false;

  const Vec3 start = positions_m[fiber.node(0)];
  const Vec3 chord_vec = positions_m[fiber.node(fiber.segments)] - start;
  const double chord = chord_vec.norm();
  if (chord == 0.0) return false;
  const Vec3 along = chord_vec / chord;
  Vec3 across = normal - normal.dot(along) * along;
  if (across.norm() < 1e-12) return false;
  across.normalize();
  const double slack = fiber.rest_length_m() - chord;
  if (slack <= 0.0 || params.k_r4 <= 0.0) {  // no slack: straight, evenly spaced
    for (int i = 1; i < fiber.segments; ++i)
      positions_m[fiber.node(i)] = start + (double(i) / fiber.segments) * chord_vec;
    return true;
  }
  const int half_waves = half_wave_count(chord, slack, fiber.segments, params);
  const Wave wave(chord, half_waves, 4 * fiber.segments);
  const double amplitude = wave.amplitude_for(fiber.rest_length_m(), half_waves);
  // The sign that best matches the present shape keeps a wrinkle on its side.
  double match = 0.0;
  for (int i = 1; i < fiber.segments; ++i) {
    const double s = double(i) / fiber.segments;
    const double offset = (positions_m[fiber.node(i)] - start - s * chord_vec).dot(across);
    match += offset * std::sin(half_waves * std::numbers::pi * s);
  }
  const double sign = match < 0.0 ? -1.0 : 1.0;
  // Nodes at equal arc length along the wave, so that 3.4 has little left to do.
  const double step = wave.length(amplitude) / fiber.segments;
  double walked = 0.0;
  int sample = 0;
  for (int i = 1; i < fiber.segments; ++i) {
    const double wanted = i * step;
    Eigen::Vector2d a = wave.at(sample, amplitude), b = wave.at(sample + 1, amplitude);
    while (walked + (b - a).norm() < wanted && sample + 1 < wave.samples()) {
      walked += (b - a).norm();
      ++sample;
      a = b;
      b = wave.at(sample + 1, amplitude);
    }
    const double piece = (b - a).norm();
    const Eigen::Vector2d p =
        piece > 0.0 ? Eigen::Vector2d(a + (wanted - walked) / piece * (b - a)) : a;
    positions_m[fiber.node(i)] = start + p.x() * along + (sign * p.y()) * across;
  }
  return true;
}

}  // namespace flagsim::infill
