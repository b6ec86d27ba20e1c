#include "flagsim/infill/keyframes.hpp"

#include <cassert>

namespace flagsim::infill {

std::array<Vec3, 4> corners_at(std::span<const Keyframe> keyframes, double time_s) {
  assert(!keyframes.empty());
  if (time_s <= keyframes.front().time_s) return keyframes.front().corners_m;
  for (std::size_t i = 1; i < keyframes.size(); ++i) {
    const Keyframe& before = keyframes[i - 1];
    const Keyframe& after = keyframes[i];
    if (time_s <= after.time_s) {
      const double s = (time_s - before.time_s) / (after.time_s - before.time_s);
      std::array<Vec3, 4> corners;
      for (int c = 0; c < 4; ++c)
        corners[c] = (1.0 - s) * before.corners_m[c] + s * after.corners_m[c];
      return corners;
    }
  }
  return keyframes.back().corners_m;
}

}  // namespace flagsim::infill
