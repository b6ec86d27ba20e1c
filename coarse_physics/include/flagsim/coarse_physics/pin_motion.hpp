#pragma once
// Prescribed motion of the pinned nodes: at rest, or shaken by [pole]:
//   x(t) = rest + axis * amplitude * sin(2 pi f t),  v(t) = axis * amplitude * 2 pi f cos(2 pi f
//   t).
#include <optional>

#include "flagsim/scene/scene.hpp"

namespace flagsim::physics {

class PinMotion {
 public:
  explicit PinMotion(const std::optional<PoleMotion>& pole) : pole_(pole) {}
  /// Offset from the rest position at time t, m.
  Vec3 offset_m(double time_s) const;
  /// Velocity at time t, m/s.
  Vec3 velocity_m_s(double time_s) const;
  /// Largest speed the pins reach, m/s.
  double max_speed_m_s() const;

 private:
  std::optional<PoleMotion> pole_;
};

}  // namespace flagsim::physics
