#pragma once
// `flag-sim render` and `run --render`: the frames of an output file drawn to
// numbered PNGs in a directory or to an MP4.
#include <limits>
#include <optional>
#include <string>

#include "flagsim/core/enum_names.hpp"
#include "flagsim/os/file_roles.hpp"
#include "flagsim/render/camera.hpp"
#include "flagsim/render/frame_renderer.hpp"
#include "flagsim/render/image.hpp"
#include "flagsim/render/video_writer.hpp"
#include "flagsim/scene/scene.hpp"

namespace flagsim::data {
class OutputReader;
}

namespace flagsim::app {

struct RenderRequest {
  std::string output;                  ///< OUT.mp4, or a directory for frame_NNNNN.png
  std::optional<std::string> size;     ///< --size WxH
  std::optional<std::string> style;    ///< --style
  std::optional<std::string> texture;  ///< --texture PNG
  std::string output_flag = "-o";      ///< how the user gave `output`, for messages
  std::optional<std::string> frames;   ///< --frames A:B (render only)
  std::optional<std::string> camera;   ///< --camera three-quarter|front|side
  std::optional<std::string> color;    ///< --color strain|speed
  std::optional<std::string> eye;      ///< --eye X,Y,Z (m): an explicit camera position
  std::optional<std::string> target;   ///< --target X,Y,Z (m): what it looks at
  std::optional<int> antialias;        ///< --antialias N: N x N samples a pixel (1: none)
  bool quiet = false;                  ///< --quiet: no progress line
};

/// What the shaded cloth is coloured by (--color).
enum class ColorBy { kNone, kStrain, kSpeed };
/// --color's names (kNone: no --color).
inline constexpr NameTable<ColorBy, 2> kColorByNames = {
    {{ColorBy::kStrain, "strain"}, {ColorBy::kSpeed, "speed"}}};

/// Everything a render needs, checked before anything is written or run.
struct RenderPlan {
  std::string output;
  int width = 1280, height = 720;
  render::Style style = render::Style::kShaded;
  render::Image texture;  ///< empty: the built-in pattern
  bool pole = false;      ///< the cloth hangs from its left edge (flag.pin = "left")
  /// A solid pole's radius ([pole] radius), m; nullopt: the renderer's own.
  std::optional<double> pole_radius_m;
  std::optional<double> ground_height_m;       ///< a solid ground ([ground] height), m
  std::optional<render::Container> container;  ///< the video's; nullopt: PNG frames
  double fps = 30.0;                           ///< of the video: the frames' own rate
  render::View view = render::View::kThreeQuarter;
  /// Frames first .. last - 1 are drawn, numbered as in the file (parse_frame_range: negative
  /// from the end, last kToEnd: to the end).
  int first_frame = 0, last_frame = std::numeric_limits<int>::max();
  /// -o NAME.png: the one frame of the range drawn to that file (a still).
  bool still = false;
  /// Drawn pixels per image pixel along each side, averaged (supersampling; 1: none).
  int samples = 2;
  ColorBy color = ColorBy::kNone;
  /// --eye / --target: an explicit camera (target: the run's centre when not given).
  std::optional<Vec3> eye_m, target_m;
  bool quiet = false;              ///< no progress line (run --quiet)
  CreatedDirectories directories;  ///< made for the output; removed again if left empty
};

/// Checks a request against the run's scene (its [render] defaults for style,
/// size and texture, and its pins; null when the scene is unknown) and the
/// run's frames per second (`fps`, from the scene or the file's attribute),
/// and prepares the output destination. Throws UserError (exit 2) naming the
/// bad flag, key or attribute; creates nothing on error.
RenderPlan plan_render(const RenderRequest& request, const Scene* scene, double fps);

/// Frames per second of a file's frames: 1 / the median step of /frames/time
/// (the scene's fps over output.every), else its `fps` attribute.
double frame_rate_of(const data::OutputReader& reader);

/// The files a render of frames first .. last - 1 writes to `output`, as
/// outputs of `files`: the video and its .partial, or each frame's PNG (and
/// its .partial) in the directory. `flag` is how the user gave it ("-o").
void add_render_outputs(FileRoles& files, const std::string& output, const std::string& flag,
                        int first, int last);

/// Draws every frame of the file `h5_path` as planned. Returns the summary line.
std::string render_file(const std::string& h5_path, const RenderPlan& plan);

/// `render`: the frames of the output file `h5_path` as the request says.
/// Returns the process exit code.
int render_command(const std::string& h5_path, const RenderRequest& request);

}  // namespace flagsim::app
