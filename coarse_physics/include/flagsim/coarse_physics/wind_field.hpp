#pragma once
// The air's velocity in space and time: the scene's mean wind, periodic gusts
// ([wind.gusts]) and seeded turbulence ([wind.turbulence]).
//
//   u(x, t) = g(t) U + u'(x - U t),   g(t) = 1 + amplitude sin(2 pi t / period)
//
// u' is frozen turbulence carried by the mean wind (Taylor's hypothesis), a sum
// of kModes random Fourier modes (Kraichnan's method): wavenumbers k_n with
// magnitudes spread log-evenly over [0.05, 50] / length_scale and directions
// uniform on the sphere, each mode along a direction perpendicular to k_n (so
// u' is divergence free), amplitudes from the von Karman energy spectrum
// E(k) ~ (kL)^4 / (1 + (kL)^2)^(17/6), scaled so that the along-wind
// component's standard deviation is intensity * |U| (the turbulence intensity
// of wind engineering); the cross-wind ones come out near it. Every random number comes from the
// scene's seed: the same seed gives the same field.
#include <array>
#include <cstdint>
#include <vector>

#include "flagsim/core/scene.hpp"

namespace flagsim::physics {

class WindField {
 public:
  static constexpr int kModes = 64;

  WindField(const Wind& wind, std::uint64_t seed);
  /// Air velocity at x (m) and time t (s), m/s.
  Vec3 velocity(const Vec3& x_m, double time_s) const;
  /// True without gusts and turbulence: the same velocity everywhere, always.
  bool steady() const { return !gusts_ && modes_.empty(); }
  /// |U| (1 + gust amplitude) + 4 sqrt(3) sigma: what |u| stays under but for
  /// rare turbulent peaks, m/s (for the stability estimate only).
  double speed_bound_m_s() const;

 private:
  struct Mode {
    Vec3 wavevector;  ///< k, 1/m
    Vec3 amplitude;   ///< m/s, perpendicular to k
    double phase = 0.0;
  };
  Vec3 mean_m_s_;
  double sigma_m_s_ = 0.0;
  std::optional<Gusts> gusts_;
  std::vector<Mode> modes_;
};

}  // namespace flagsim::physics
