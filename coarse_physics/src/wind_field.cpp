#include "flagsim/coarse_physics/wind_field.hpp"

#include <cmath>
#include <numbers>
#include <random>

namespace flagsim::physics {
namespace {

// Uniform in [0, 1) from the top 53 bits (the same numbers on every standard library).
double unit_uniform(std::mt19937_64& rng) {
  return double(rng() >> 11) * 0x1.0p-53;
}

Vec3 random_direction(std::mt19937_64& rng) {
  const double z = 2.0 * unit_uniform(rng) - 1.0;
  const double phi = 2.0 * std::numbers::pi * unit_uniform(rng);
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return Vec3(r * std::cos(phi), r * std::sin(phi), z);
}

// von Karman energy spectrum shape, E(k) ~ (kL)^4 / (1 + (kL)^2)^(17/6).
double von_karman(double kl) {
  return std::pow(kl, 4) / std::pow(1.0 + kl * kl, 17.0 / 6.0);
}

}  // namespace

WindField::WindField(const Wind& wind, std::uint64_t seed)
    : mean_m_s_(wind.velocity_m_s), bound_mean_m_s_(wind.velocity_m_s.norm()), gusts_(wind.gusts) {
  if (!wind.turbulence || wind.turbulence->intensity == 0.0) return;
  const double sigma = wind.turbulence->intensity * wind.velocity_m_s.norm();
  sigma_m_s_ = sigma;
  const double length = wind.turbulence->length_scale_m;
  // A stream of its own: the field does not shift when other users of the seed change.
  std::mt19937_64 rng(seed ^ 0x57494e44u);  // "WIND"
  const double log_low = std::log(0.05), log_high = std::log(50.0);
  const double step = (log_high - log_low) / kModes;
  std::vector<double> weight(kModes);
  double total = 0.0;
  modes_.resize(kModes);
  for (int n = 0; n < kModes; ++n) {
    const double kl = std::exp(log_low + (n + 0.5) * step);
    weight[n] = von_karman(kl) * kl * step;  // E(k) dk with dk = k d(log k)
    total += weight[n];
    const Vec3 k_hat = random_direction(rng);
    Vec3 across = k_hat.cross(random_direction(rng));
    if (across.norm() < 1e-9) across = k_hat.unitOrthogonal();
    modes_[n].wavevector = (kl / length) * k_hat;
    modes_[n].amplitude = across.normalized();
    modes_[n].phase = 2.0 * std::numbers::pi * unit_uniform(rng);
  }
  // Each mode a cos(...) e adds a^2/2 to the summed variance of the three
  // components: 3 sigma^2 for isotropic turbulence. With finitely many random
  // directions the split between components is itself random (+-15% at 64
  // modes), so the amplitudes are then scaled to give the along-wind
  // component, the one "intensity" means, exactly sigma.
  for (int n = 0; n < kModes; ++n)
    modes_[n].amplitude *= std::sqrt(2.0 * 3.0 * sigma * sigma * weight[n] / total);
  const Vec3 along = wind.velocity_m_s.normalized();
  double along_variance = 0.0;
  for (const Mode& mode : modes_) along_variance += 0.5 * std::pow(mode.amplitude.dot(along), 2);
  if (along_variance > 0.0)
    for (Mode& mode : modes_) mode.amplitude *= sigma / std::sqrt(along_variance);
}

Vec3 WindField::velocity(const Vec3& x_m, double time_s) const {
  Vec3 u = mean_m_s_;
  if (gusts_)
    u *= 1.0 + gusts_->amplitude * std::sin(2.0 * std::numbers::pi * time_s / gusts_->period_s);
  if (modes_.empty()) return u;
  // Frozen turbulence moves with the mean wind (x - U t while it never changed).
  const Vec3 carried = x_m - (offset_m_ + (time_s - since_s_) * mean_m_s_);
  for (const Mode& mode : modes_)
    u += std::cos(mode.wavevector.dot(carried) + mode.phase) * mode.amplitude;
  return u;
}

void WindField::set_drift(const Drift& drift) {
  mean_m_s_ = drift.mean_m_s;
  offset_m_ = drift.offset_m;
  since_s_ = drift.since_s;
}

WindField::Drift WindField::with_mean(const Drift& drift, const Vec3& mean_m_s, double time_s) {
  return {mean_m_s, drift.offset_m + (time_s - drift.since_s) * drift.mean_m_s, time_s};
}

double WindField::speed_bound_m_s() const {
  // The scene's wind, not the present one: the substeps were sized for it
  // (Simulation::set_wind refuses a faster one).
  return bound_mean_m_s_ * (1.0 + (gusts_ ? std::abs(gusts_->amplitude) : 0.0)) +
         4.0 * std::sqrt(3.0) * sigma_m_s_;
}

}  // namespace flagsim::physics
