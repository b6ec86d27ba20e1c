#pragma once
// Where the image is seen from: a pinhole camera (perspective, vertical field
// of view), and the automatic framing of a whole run.
#include <optional>
#include <span>
#include <string_view>

#include "flagsim/core/enum_names.hpp"
#include "flagsim/core/vec3.hpp"

namespace flagsim::render {

struct Camera {
  Vec3 eye_m = Vec3(0.75, 1.5, 4.0);
  Vec3 target_m = Vec3(0.75, 1.5, 0.0);
  Vec3 up = Vec3::UnitY();
  double vertical_fov_deg = 35.0;
};

/// Axis-aligned bounds of a set of points, m.
struct Bounds {
  Vec3 low = Vec3::Constant(1e300);
  Vec3 high = Vec3::Constant(-1e300);
  void add(const Vec3& p) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  void add(std::span<const Vec3> points) {
    for (const Vec3& p : points) add(p);
  }
  bool empty() const { return low.x() > high.x(); }
};

/// Where the automatic camera looks from.
enum class View {
  kThreeQuarter,  ///< in front (+z), 20 degrees toward the fly end (+x), 12 above (default)
  kFront,         ///< straight in front (+z)
  kSide,          ///< from the fly end (+x), a little above: the flapping in profile
};
/// --camera's names, in the order users are told them.
inline constexpr NameTable<View, 3> kViewNames = {
    {{View::kThreeQuarter, "three-quarter"}, {View::kFront, "front"}, {View::kSide, "side"}}};
/// "three-quarter", "front" or "side"; nullopt otherwise.
inline std::optional<View> parse_view(std::string_view name) {
  return value_in(kViewNames, name);
}

/// A camera that sees all of `bounds` in an image of the given aspect
/// (width / height) from `view`, looking at the centre of the bounds, as close
/// as keeps every corner of the bounds within 90% of both fields of view.
Camera frame_bounds(const Bounds& bounds, double aspect, View view = View::kThreeQuarter);

}  // namespace flagsim::render
