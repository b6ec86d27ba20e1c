#pragma once
// Draws one frame of a cloth: the lattice as lines (wireframe), as a lit
// surface with smooth normals, both faces lit (shaded), or with a texture
// (textured); a pole along the pinned edge down to the ground, a ground plane
// and a sky, so that motion reads at a glance.
//
// The renderer sees only a FrameView: positions and the lattice's shape, from
// an output file or a running simulation's snapshot; never the simulator.
#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "flagsim/core/vec3.hpp"
#include "flagsim/render/camera.hpp"
#include "flagsim/render/image.hpp"
#include "flagsim/render/offscreen_context.hpp"
#include "flagsim/scene/scene.hpp"

namespace flagsim::render {

/// The scene's render.style (kRenderStyleNames), as drawn here.
using Style = RenderStyle;
using flagsim::to_string;

/// "wireframe" / "shaded" / "textured", or nullopt.
std::optional<Style> parse_style(const std::string& name);

/// One frame: J x K positions, m, row-major (contract lattice order), and the
/// top of the pole (drawn down to the ground) if the cloth hangs on one.
struct FrameView {
  int rows = 0;
  int cols = 0;
  std::span<const Vec3> positions_m;
  std::optional<Vec3> pole_top_m;
  /// [J*K] a per-node value to colour by (RenderOptions::color), or empty.
  std::span<const double> field;
  /// The pole's radius, m (a solid pole's, else a flagpole's 2 cm); its
  /// surface touches the pole edge (axis at top.x - radius).
  double pole_radius_m = 0.02;
};

/// Colours a per-node value on the shaded surface: [low, high] mapped through
/// a viridis-like ramp (dark blue, teal, green, yellow), clamped outside.
struct ColorScale {
  double low = 0.0, high = 1.0;
};

/// The ramp's colour at t in [0, 1] (clamped), RGB in [0, 1].
std::array<float, 3> ramp_color(double t);

struct RenderOptions {
  Style style = Style::kShaded;
  Camera camera;
  /// Texture for kTextured; empty: the built-in flag pattern.
  Image texture;
  /// Height of the ground plane, m.
  double ground_y_m = 0.0;
  /// kShaded only: colour the cloth by FrameView::field on this scale.
  std::optional<ColorScale> color;
};

class FrameRenderer {
 public:
  /// Draws into `context` (kept, not owned).
  FrameRenderer(OffscreenContext& context, RenderOptions options);
  Image render(const FrameView& frame);

 private:
  void draw_backdrop() const;
  void draw_pole(const Vec3& top, double radius) const;
  void draw_cloth(const FrameView& frame);
  /// Every how many lattice lines the wireframe draws one.
  int wire_step(const FrameView& frame) const;

  OffscreenContext& context_;
  RenderOptions options_;
  unsigned texture_id_ = 0;
  std::vector<float> vertices_, normals_, colors_;  ///< [3 J K] this frame's, for GL
  std::vector<unsigned> triangles_;                 ///< the mesh's indices, kept between frames
  int triangle_rows_ = 0, triangle_cols_ = 0;
};

}  // namespace flagsim::render
