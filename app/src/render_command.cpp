#include "render_command.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <regex>

#include "dense_input.hpp"
#include "flagsim/core/errors.hpp"
#include "flagsim/core/limits.hpp"
#include "flagsim/core/message.hpp"
#include "flagsim/core/near_miss.hpp"
#include "flagsim/core/stop_request.hpp"
#include "flagsim/data/output_reader.hpp"
#include "flagsim/os/file_roles.hpp"
#include "flagsim/render/camera.hpp"
#include "flagsim/render/color_bar.hpp"
#include "flagsim/render/offscreen_context.hpp"
#include "flagsim/render/png_io.hpp"
#include "flagsim/render/video_writer.hpp"
#include "flagsim/scene/scene_parser.hpp"
#include "frame_range.hpp"
#include "interrupt.hpp"
#include "progress.hpp"
#include "render_command.hpp"

namespace flagsim::app {
namespace fs = std::filesystem;
namespace {

constexpr int kMinSide = limits::kImageSideMin, kMaxSide = limits::kImageSideMax;

std::pair<int, int> parse_size(const std::string& text) {
  static const std::regex pattern(R"(^\s*(\d{1,6})\s*[xX]\s*(\d{1,6})\s*$)");
  std::smatch match;
  if (!std::regex_match(text, match, pattern))
    throw UserError(fmt::format("--size {}: expected WxH in pixels, e.g. 1280x720", text));
  const int w = std::stoi(match[1]), h = std::stoi(match[2]);
  if (w < kMinSide || h < kMinSide || w > kMaxSide || h > kMaxSide)
    throw UserError(
        fmt::format("--size {}: each side must be {} to {} pixels", text, kMinSide, kMaxSide));
  return {w, h};
}

// --eye / --target X,Y,Z in metres, each within the coordinate limit.
Vec3 parse_point(const std::string& flag, const std::string& text) {
  static const std::regex number(R"(^\s*([-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?)\s*$)");
  Vec3 p;
  std::size_t start = 0;
  for (int c = 0; c < 3; ++c) {
    const std::size_t comma = c < 2 ? text.find(',', start) : text.size();
    std::smatch m;
    const std::string item = comma == std::string::npos ? "" : text.substr(start, comma - start);
    if (comma == std::string::npos || !std::regex_match(item, m, number) ||
        (c == 2 && text.find(',', start) != std::string::npos))
      throw UserError(
          fmt::format("{} {}: expected X,Y,Z in metres, e.g. 0.75,1.5,4", flag, printable(text)));
    p[c] = std::stod(m[1]);
    if (!std::isfinite(p[c]) || std::abs(p[c]) > limits::kCoordinate_m)
      throw UserError(fmt::format("{} {}: each coordinate within {} m", flag, printable(text),
                                  limits::kCoordinate_m));
    start = comma + 1;
  }
  return p;
}

bool ends_with(const std::string& text, const std::string& tail) {
  return text.size() >= tail.size() &&
         text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
}

// The directory that will hold the output: created when missing (never more
// than the request asked for, and removed again if nothing is written into
// it), then checked for writing.
void prepare_directory(const fs::path& dir, const std::string& what,
                       CreatedDirectories& directories) {
  std::error_code error;
  if (!dir.empty()) directories.create(dir.string(), error);
  const fs::path probe = dir.empty() ? fs::path(".") : dir;
  if (error || !fs::is_directory(probe) || access(probe.c_str(), W_OK) != 0)
    throw UserError(fmt::format("{}: cannot write to {} (check the path and its permissions)", what,
                                probe.string()));
}

// -o NAME.png (any case), not a directory: one still.
bool names_a_still(const std::string& output) {
  std::string extension = fs::path(output).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  std::error_code ec;
  return extension == ".png" && !ends_with(output, "/") && !fs::is_directory(output, ec);
}

}  // namespace

void add_render_outputs(FileRoles& files, const std::string& output, const std::string& flag,
                        int first, int last) {
  if (names_a_still(output)) {
    if (last - first != 1)
      throw UserError(fmt::format(
          "{} {}: a PNG file holds one frame, and frames {} to {} are {}; pick one with --frames "
          "N (-1: the last), or give a directory for PNG frames",
          flag, output, first, last - 1, last - first));
    files.output(output, flag);
    files.output(output + ".partial", flag + " (while written)");
    return;
  }
  if (render::container_of(output)) {
    files.output(output, flag);
    files.output(output + ".partial", flag + " (while encoded)");
    return;
  }
  // A directory name that is already a file: an output too ("would overwrite"
  // when it is an input, "not a directory" otherwise).
  std::error_code ec;
  if (fs::exists(output, ec) && !fs::is_directory(output, ec)) files.output(output, flag);
  std::vector<std::string> names;
  names.reserve(2 * std::size_t(std::max(0, last - first)));
  for (int t = first; t < last; ++t) {
    names.push_back(fmt::format("frame_{:05d}.png", t));
    names.push_back(fmt::format("frame_{:05d}.png.partial", t));
  }
  files.outputs_in(output, names, flag);
}

double frame_rate_of(const data::OutputReader& reader) {
  // From the frames' own times (a run with output.every = 3 at 30 fps wrote
  // frames 0.1 s apart: its video plays at 10 fps); the attribute when there
  // are fewer than two frames or the times are not increasing.
  const std::vector<double> times = reader.times_s();
  std::vector<double> steps;
  for (std::size_t t = 1; t < times.size(); ++t) steps.push_back(times[t] - times[t - 1]);
  if (steps.empty()) return reader.number_attribute("fps", 30.0);
  std::nth_element(steps.begin(), steps.begin() + long(steps.size() / 2), steps.end());
  const double step = steps[steps.size() / 2];
  return step > 0.0 && std::isfinite(step) ? 1.0 / step : reader.number_attribute("fps", 30.0);
}

RenderPlan plan_render(const RenderRequest& request, const Scene* scene, double fps) {
  const Render* scene_render = scene && scene->render ? &*scene->render : nullptr;
  RenderPlan plan;
  plan.output = request.output;
  plan.quiet = request.quiet;
  if (plan.output.empty()) throw UserError("render: -o OUT.mp4 or -o DIR is required");
  plan.container = render::container_of(plan.output);
  const bool video = plan.container.has_value();
  // Anything else is a directory of PNG frames; a name with some other
  // extension (run.avi) is almost surely meant as a video: refused rather than
  // made into a directory of that name. An existing directory, or a trailing
  // '/', says "directory" whatever the name.
  plan.still = names_a_still(plan.output);
  if (!video && !plan.still && !ends_with(plan.output, "/") && !fs::is_directory(plan.output)) {
    const std::string extension = fs::path(plan.output).extension().string();
    if (!extension.empty() && extension != ".")
      throw UserError(fmt::format(
          "{} {}: '{}' is not a video flag-sim writes (.mp4, .mkv, .webm, .gif) nor a still "
          "(.png, one frame); for PNG frames give a directory (a trailing '/' makes any name one)",
          request.output_flag, plan.output, extension));
  }
  if (video && !(fps > 0.0 && fps <= limits::kFps))
    throw UserError(
        fmt::format("{} {}: the run's frames per second ({}) is not in (0, {}]: "
                    "cannot time a video; render PNG frames to a directory instead",
                    request.output_flag, plan.output, fps, limits::kFps));
  plan.fps = fps;
  plan.pole = scene && scene->flag.pin == PinSet::kLeft;
  if (scene && scene->solid_pole) plan.pole_radius_m = scene->solid_pole->radius_m;
  if (scene && scene->ground) plan.ground_height_m = scene->ground->height_m;
  if (scene_render) {
    plan.width = scene_render->size_px[0];
    plan.height = scene_render->size_px[1];
    plan.style = scene_render->style;
  }
  if (request.size) std::tie(plan.width, plan.height) = parse_size(*request.size);
  // "--style shadd: expected one of ... (did you mean "shaded"?)" (issue 33, item 8).
  const auto unknown = [](const char* flag, const std::string& typed, const auto& table) {
    const std::vector<std::string_view> names = names_in(table);
    const std::string guess = detail::closest_name(typed, names);
    return UserError(fmt::format(
        "{} {}: expected one of \"{}\"{}", flag, printable(typed), fmt::join(names, "\", \""),
        guess.empty() ? "" : fmt::format(" (did you mean \"{}\"?)", guess)));
  };
  if (request.style) {
    const auto style = render::parse_style(*request.style);
    if (!style) throw unknown("--style", *request.style, kRenderStyleNames);
    plan.style = *style;
  }
  if (request.camera) {
    const auto view = render::parse_view(*request.camera);
    if (!view) throw unknown("--camera", *request.camera, render::kViewNames);
    plan.view = *view;
  }
  if (request.frames)
    std::tie(plan.first_frame, plan.last_frame) = parse_frame_range(*request.frames);
  if (request.antialias) {
    if (*request.antialias < 1 || *request.antialias > 4)
      throw UserError(
          fmt::format("--antialias {}: expected 1 (none) to 4 samples along each side of a pixel",
                      *request.antialias));
    plan.samples = *request.antialias;
  }
  if (request.eye) plan.eye_m = parse_point("--eye", *request.eye);
  if (request.target) plan.target_m = parse_point("--target", *request.target);
  if (request.target && !request.eye)
    throw UserError(fmt::format("--target {}: goes with --eye X,Y,Z", *request.target));
  if (request.eye && request.camera)
    throw UserError(fmt::format("--eye {}: give --eye or --camera {}, not both", *request.eye,
                                *request.camera));
  if (request.color) {
    const std::optional<ColorBy> color = value_in(kColorByNames, *request.color);
    if (!color)
      throw UserError(fmt::format("--color {}: expected \"{}\"", printable(*request.color),
                                  fmt::join(names_in(kColorByNames), "\" or \"")));
    plan.color = *color;
    if (plan.style != render::Style::kShaded)
      throw UserError(fmt::format("--color {}: colours the shaded style (not {})", *request.color,
                                  render::to_string(plan.style)));
  }
  if (video && render::needs_even_size(*plan.container) && (plan.width % 2 || plan.height % 2))
    throw UserError(fmt::format("--size {}x{}: {} (yuv420p) needs an even width and height",
                                plan.width, plan.height, render::to_string(*plan.container)));
  std::string texture = request.texture.value_or(scene_render ? scene_render->texture : "");
  if (!texture.empty()) {
    if (plan.style != render::Style::kTextured)
      throw UserError(fmt::format("--texture {}: a texture needs --style textured", texture));
    plan.texture = render::read_png(texture);
  }
  if (video) {
    if (render::find_ffmpeg().empty())
      throw UserError(
          fmt::format("{} {}: a video needs ffmpeg, which is not on PATH (apt-get "
                      "install ffmpeg), or give a directory for PNG frames",
                      request.output_flag, plan.output));
    prepare_directory(fs::path(plan.output).parent_path(), request.output_flag + " " + plan.output,
                      plan.directories);
    if (fs::is_directory(plan.output))
      throw UserError(fmt::format("{} {}: is a directory", request.output_flag, plan.output));
  } else if (plan.still) {  // its directory made, as a video's
    prepare_directory(fs::path(plan.output).parent_path(), request.output_flag + " " + plan.output,
                      plan.directories);
  } else {
    prepare_directory(fs::path(plan.output), request.output_flag + " " + plan.output,
                      plan.directories);
  }
  return plan;
}

std::string render_file(const std::string& h5_path, const RenderPlan& plan) {
  using Clock = std::chrono::steady_clock;
  const DenseInput dense(h5_path);  // a coarse trajectory's frames refined first
  const data::OutputReader reader(dense.path());
  const int frames = reader.frame_count(), rows = reader.rows(), cols = reader.cols();
  // Frame the whole run: every node of every frame, and the ground below it.
  render::Bounds bounds;
  for (int t = 0; t < frames; ++t) bounds.add(reader.positions(t));
  if (bounds.empty()) throw UserError(fmt::format("{}: has no frames to render", h5_path));
  render::RenderOptions options;
  options.style = plan.style;
  options.texture = plan.texture;
  options.camera = render::frame_bounds(bounds, double(plan.width) / plan.height, plan.view);
  if (plan.eye_m) {  // the automatic camera's field of view, from where the user said
    options.camera.eye_m = *plan.eye_m;
    if (plan.target_m) options.camera.target_m = *plan.target_m;
    if ((options.camera.target_m - options.camera.eye_m).norm() < 1e-6)
      throw UserError("--eye: the camera is at the point it looks at; move it or give --target");
    if ((options.camera.target_m - options.camera.eye_m)
            .normalized()
            .cross(options.camera.up)
            .norm() < 1e-6)
      options.camera.up = Vec3::UnitZ();  // looking straight down or up: y cannot be up
  }
  // The range, against the file (the camera above still frames the whole run).
  const auto [first, last] =
      resolve_frame_range({plan.first_frame, plan.last_frame}, frames, h5_path);
  // A solid ground is drawn where it is; otherwise a floor below the run.
  options.ground_y_m = plan.ground_height_m.value_or(std::min(0.0, bounds.low.y() - 0.05));
  // --color: one scale for every drawn frame, 0 to the largest value among them.
  const auto field_of = [&](int t) -> std::vector<double> {
    if (plan.color == ColorBy::kStrain) return reader.node_strain(t);
    std::vector<double> speed;
    for (const Vec3& v : reader.velocities(t)) speed.push_back(v.norm());
    return speed;
  };
  const char* field_name = plan.color == ColorBy::kStrain ? "strain" : "velocity";
  std::string colored;
  std::optional<std::pair<std::string, std::string>> legend;  // --color: top and bottom labels
  if (plan.color != ColorBy::kNone) {
    double high = 0.0;
    for (int t = first; t < last; ++t) {
      const std::vector<double> field = field_of(t);
      if (field.empty())
        throw UserError(fmt::format(
            "--color {}: {} has no /frames/{} (written when [output] fields lists \"{}\")",
            plan.color == ColorBy::kStrain ? "strain" : "speed", h5_path, field_name, field_name));
      for (double value : field)
        if (std::isfinite(value)) high = std::max(high, value);
    }
    options.color = render::ColorScale{0.0, high};
    colored = plan.color == ColorBy::kStrain
                  ? fmt::format(", coloured by strain 0 .. {:.3g}%", 100.0 * high)
                  : fmt::format(", coloured by speed 0 .. {:.3g} m/s", high);
    // The legend drawn into every frame: the scale's top and bottom.
    legend = plan.color == ColorBy::kStrain
                 ? std::pair{fmt::format("{:.3g}%", 100.0 * high), std::string("0%")}
                 : std::pair{fmt::format("{:.3g} m/s", high), std::string("0 m/s")};
  }

  const auto context = render::make_osmesa_context(plan.width, plan.height, plan.samples);
  render::FrameRenderer renderer(*context, options);
  std::optional<render::VideoWriter> video;
  if (plan.container)
    video.emplace(plan.output, *plan.container, plan.width, plan.height, plan.fps);
  double draw_s = 0.0, encode_s = 0.0;
  Progress progress(Progress::wanted(plan.quiet), last - first, "render");
  const std::vector<double> times = reader.times_s();
  for (int t = first; t < last; ++t) {
    if (stop_requested())  // SIGINT / SIGTERM: stop between frames, the run's file is kept
      throw Interrupted(
          fmt::format("rendering {} stopped by a signal after {} of {} frames; {} is "
                      "kept",
                      plan.output, t - first, last - first, h5_path));
    const std::vector<Vec3> positions = reader.positions(t);
    const std::vector<double> field =
        plan.color == ColorBy::kNone ? std::vector<double>() : field_of(t);
    render::FrameView view{rows, cols, positions, std::nullopt, field};
    if (plan.pole) view.pole_top_m = positions[0];  // node (0, 0): the top of the pole edge
    if (plan.pole_radius_m) view.pole_radius_m = *plan.pole_radius_m;
    const Clock::time_point start = Clock::now();
    render::Image image = renderer.render(view);
    if (legend) render::draw_color_bar(image, legend->first, legend->second);
    const Clock::time_point drawn = Clock::now();
    if (video) {
      video->write(image);
    } else if (plan.still) {
      render::write_png(plan.output, image);
    } else {
      render::write_png((fs::path(plan.output) / fmt::format("frame_{:05d}.png", t)).string(),
                        image);
    }
    draw_s += std::chrono::duration<double>(drawn - start).count();
    encode_s += std::chrono::duration<double>(Clock::now() - drawn).count();
    progress.update(t - first, times[std::size_t(t)], 1e3 * (draw_s + encode_s) / (t - first + 1));
  }
  progress.done();
  const Clock::time_point closing = Clock::now();
  if (video) video->finish();
  encode_s += std::chrono::duration<double>(Clock::now() - closing).count();
  const double n = std::max(1, last - first);
  return fmt::format(
      "rendered {} ({}{}, {}x{}), {:.1f} ms/frame drawing + {:.1f} ms/frame {} -> {}",
      counted(last - first, "frame"), render::to_string(plan.style), colored, plan.width,
      plan.height, 1e3 * draw_s / n, 1e3 * encode_s / n,
      plan.container ? render::to_string(*plan.container) : "PNG", plan.output);
}

int render_command(const std::string& h5_path, const RenderRequest& request) {
  const InterruptGuard interrupt;
  FileRoles files;
  files.input(h5_path, "the input");
  if (request.texture) files.input(*request.texture, "--texture");
  files.check();  // the inputs: regular files, before one is opened
  // The file first: a missing or foreign input is the first thing to say.
  std::optional<Scene> scene;
  double fps = 30.0;
  int first = 0, last = 0;
  {
    const data::OutputReader reader(h5_path);
    fps = frame_rate_of(reader);
    try {
      scene = parse_scene(reader.attribute("scene"), h5_path);
    } catch (const UserError&) {  // a scene this version cannot read: defaults, no pole
    }
    std::tie(first, last) =
        resolve_frame_range(request.frames ? parse_frame_range(*request.frames) : kAllFrames,
                            reader.frame_count(), h5_path);
  }
  // Every file the render will write, checked against the inputs before anything is made.
  add_render_outputs(files, request.output, "-o", first, last);
  files.check();
  const RenderPlan plan = plan_render(request, scene ? &*scene : nullptr, fps);
  fmt::print("{}\n", render_file(h5_path, plan));
  return int(ExitCode::kSuccess);
}

}  // namespace flagsim::app
