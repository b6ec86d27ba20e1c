#include "flagsim/coarse_physics/pin_motion.hpp"

#include <cmath>
#include <numbers>

namespace flagsim::physics {

Vec3 PinMotion::offset_m(double time_s) const {
  if (!pole_) return Vec3::Zero();
  const double phase = 2.0 * std::numbers::pi * pole_->frequency_hz * time_s;
  return pole_->axis_unit * (pole_->amplitude_m * std::sin(phase));
}

Vec3 PinMotion::velocity_m_s(double time_s) const {
  if (!pole_) return Vec3::Zero();
  const double omega = 2.0 * std::numbers::pi * pole_->frequency_hz;
  return pole_->axis_unit * (pole_->amplitude_m * omega * std::cos(omega * time_s));
}

double PinMotion::max_speed_m_s() const {
  return pole_ ? pole_->amplitude_m * 2.0 * std::numbers::pi * pole_->frequency_hz : 0.0;
}

}  // namespace flagsim::physics
