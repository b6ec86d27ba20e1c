#include "flagsim/render/camera.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace flagsim::render {

Camera frame_bounds(const Bounds& bounds, double aspect, View view) {
  Camera camera;
  const Vec3 centre = 0.5 * (bounds.low + bounds.high);
  const double vertical = camera.vertical_fov_deg * std::numbers::pi / 180.0;
  const double tan_v = std::tan(0.5 * vertical), tan_h = tan_v * aspect;
  // Three-quarter: from the front (+z), 20 degrees toward the fly end (+x) and 12 above.
  Vec3 direction = Vec3(std::sin(0.35), std::sin(0.21), std::cos(0.35)).normalized();
  if (view == View::kFront) direction = Vec3::UnitZ();
  if (view == View::kSide) direction = Vec3(1.0, std::sin(0.21), 0.0).normalized();
  // The box's eight corners in the view's frame (right, up, toward the camera):
  // the eye is as close as keeps every corner inside 90% of both fields of
  // view. (The bounding sphere framed the side view's thin profile a tenth of
  // the image wide.)
  const Vec3 right = camera.up.cross(direction).normalized();
  const Vec3 up = direction.cross(right);
  double distance = 1e-3;
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 p((corner & 1) ? bounds.high.x() : bounds.low.x(),
                 (corner & 2) ? bounds.high.y() : bounds.low.y(),
                 (corner & 4) ? bounds.high.z() : bounds.low.z());
    const Vec3 d = p - centre;
    const double toward = d.dot(direction);
    distance = std::max({distance, toward + std::abs(d.dot(right)) / (0.9 * tan_h),
                         toward + std::abs(d.dot(up)) / (0.9 * tan_v)});
  }
  camera.target_m = centre;
  camera.eye_m = centre + distance * direction;
  return camera;
}

}  // namespace flagsim::render
