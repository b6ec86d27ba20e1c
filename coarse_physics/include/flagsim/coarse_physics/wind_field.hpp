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
//
// The mean wind can change during a run (set_mean, Simulation::set_wind): the
// turbulence is then carried by the wind as it was, x - offset(t) with
// offset(t) = offset(t0) + (t - t0) U since the last change at t0 (U t while
// the wind never changed, bit for bit). The turbulence's strength stays the
// scene's.
#include <array>
#include <cstdint>
#include <vector>

#include "flagsim/scene/scene.hpp"

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

  /// The mean wind and how far it has carried the turbulence: what a later
  /// velocity() depends on beside the seed (part of a simulation's state).
  struct Drift {
    Vec3 mean_m_s = Vec3::Zero();
    Vec3 offset_m = Vec3::Zero();  ///< the carried distance at since_s
    double since_s = 0.0;
  };
  Drift drift() const { return {mean_m_s_, offset_m_, since_s_}; }
  void set_drift(const Drift& drift);
  /// `drift` with the mean wind `mean_m_s` from time_s on (the turbulence
  /// carried on continuously from where the old wind had taken it).
  static Drift with_mean(const Drift& drift, const Vec3& mean_m_s, double time_s);
  /// |U| of the scene's wind, m/s: the fastest mean wind the stepping was sized for.
  double scene_speed_m_s() const { return bound_mean_m_s_; }

 private:
  struct Mode {
    Vec3 wavevector;  ///< k, 1/m
    Vec3 amplitude;   ///< m/s, perpendicular to k
    double phase = 0.0;
  };
  Vec3 mean_m_s_;
  Vec3 offset_m_ = Vec3::Zero();
  double since_s_ = 0.0;
  double bound_mean_m_s_ = 0.0;  ///< |U| of the scene: what speed_bound_m_s() was sized for
  double sigma_m_s_ = 0.0;
  std::optional<Gusts> gusts_;
  std::vector<Mode> modes_;
};

}  // namespace flagsim::physics
