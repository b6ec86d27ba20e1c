#include "flagsim/render/camera.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace flagsim::render {

Camera frame_bounds(const Bounds& bounds, double aspect, View view) {
  Camera camera;
  const Vec3 centre = 0.5 * (bounds.low + bounds.high);
  const double radius = std::max(0.5 * (bounds.high - bounds.low).norm(), 1e-3);
  const double vertical = camera.vertical_fov_deg * std::numbers::pi / 180.0;
  const double horizontal = 2.0 * std::atan(std::tan(0.5 * vertical) * aspect);
  const double half_fov = 0.5 * std::min(vertical, horizontal);
  const double distance = radius / std::sin(half_fov) / 0.9;
  // Three-quarter: from the front (+z), 20 degrees toward the fly end (+x) and 12 above.
  Vec3 direction = Vec3(std::sin(0.35), std::sin(0.21), std::cos(0.35)).normalized();
  if (view == View::kFront) direction = Vec3::UnitZ();
  if (view == View::kSide) direction = Vec3(1.0, std::sin(0.21), 0.0).normalized();
  camera.target_m = centre;
  camera.eye_m = centre + distance * direction;
  return camera;
}

}  // namespace flagsim::render
