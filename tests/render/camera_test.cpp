#include "flagsim/render/camera.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tolerances.hpp"

namespace flagsim::render {
namespace {

// Where p lands in the image of `camera` (aspect = width / height): x and y
// in [-1, 1] when it is in the picture, and its depth along the view.
struct Projected {
  double x = 0.0, y = 0.0, depth = 0.0;
};
Projected project(const Camera& camera, double aspect, const Vec3& p) {
  const Vec3 forward = (camera.target_m - camera.eye_m).normalized();
  const Vec3 right = forward.cross(camera.up).normalized();
  const Vec3 up = right.cross(forward);
  const Vec3 d = p - camera.eye_m;
  const double depth = d.dot(forward);
  const double half = std::tan(0.5 * camera.vertical_fov_deg * std::numbers::pi / 180.0);
  return {d.dot(right) / depth / (half * aspect), d.dot(up) / depth / half, depth};
}

TEST(Camera, ParsesTheThreeViewsAndNothingElse) {
  EXPECT_EQ(parse_view("three-quarter"), View::kThreeQuarter);
  EXPECT_EQ(parse_view("front"), View::kFront);
  EXPECT_EQ(parse_view("side"), View::kSide);
  EXPECT_FALSE(parse_view("Front").has_value());
  EXPECT_FALSE(parse_view("").has_value());
}

TEST(Camera, EveryViewSeesTheWholeBoundsFromItsSide) {
  // The default flag's rest rectangle, bulged by 0.3 m toward +z.
  Bounds bounds;
  bounds.add(Vec3(0.0, 1.0, -0.1));
  bounds.add(Vec3(1.5, 2.0, 0.3));
  const Vec3 centre = 0.5 * (bounds.low + bounds.high);
  for (const View view : {View::kThreeQuarter, View::kFront, View::kSide})
    for (const double aspect : {16.0 / 9.0, 1.0, 0.5}) {
      const Camera camera = frame_bounds(bounds, aspect, view);
      EXPECT_TRUE(camera.target_m.isApprox(centre, test::kAnalyticRelTol));
      double widest = 0.0;
      for (int corner = 0; corner < 8; ++corner) {
        const Vec3 p((corner & 1) ? bounds.high.x() : bounds.low.x(),
                     (corner & 2) ? bounds.high.y() : bounds.low.y(),
                     (corner & 4) ? bounds.high.z() : bounds.low.z());
        const Projected q = project(camera, aspect, p);
        EXPECT_GT(q.depth, 0.0) << int(view) << " " << aspect << " corner " << corner;
        EXPECT_LE(std::abs(q.x), 1.0) << int(view) << " " << aspect << " corner " << corner;
        EXPECT_LE(std::abs(q.y), 1.0) << int(view) << " " << aspect << " corner " << corner;
        widest = std::max({widest, std::abs(q.x), std::abs(q.y)});
      }
      // Framed tight: the limiting corner at 90% of the half field of view (framing the
      // bounding sphere left the side view's profile a tenth of the picture wide).
      EXPECT_NEAR(widest, 0.9, 1e-9) << int(view) << " " << aspect;
      const Vec3 from = (camera.eye_m - centre).normalized();
      if (view == View::kFront) {
        EXPECT_GT(from.z(), 0.999);
      } else if (view == View::kSide) {
        EXPECT_GT(from.x(), 0.9);
      } else {
        EXPECT_GT(from.z(), 0.8);
        EXPECT_GT(from.x(), 0.2);  // toward the fly end
        EXPECT_GT(from.y(), 0.1);  // from above
      }
    }
}

}  // namespace
}  // namespace flagsim::render
