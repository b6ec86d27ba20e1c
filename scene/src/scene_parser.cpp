#include "flagsim/scene/scene_parser.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>

#include "flagsim/core/errors.hpp"
#include "flagsim/core/limits.hpp"
#include "flagsim/core/message.hpp"
#include "flagsim/scene/material.hpp"
#include "scene_checks.hpp"
#include "toml_reader.hpp"

namespace flagsim {
namespace {

constexpr double kPi = std::numbers::pi;

using detail::Bound;
using detail::TableReader;

// Largest lattice side and node count accepted: a 8193 x 8193 lattice already
// needs ~1.6 GB per state vector; past this a typo is far likelier than intent.
constexpr long long kMaxLatticeSide = limits::kLatticeSide;
constexpr long long kMaxFrames = limits::kFrames;

// Every key of the schema, for "did you mean" across tables.
constexpr std::string_view kAllKeys[] = {"scene.name",
                                         "scene.mode",
                                         "scene.duration",
                                         "scene.fps",
                                         "scene.seed",
                                         "scene.frames",
                                         "flag.size",
                                         "flag.origin",
                                         "flag.fine",
                                         "flag.coarse",
                                         "flag.areal_density",
                                         "flag.stretch_modulus",
                                         "flag.shear_modulus",
                                         "flag.damping",
                                         "flag.pin",
                                         "flag.initial_perturbation",
                                         "flag.folds",
                                         "flag.folds.axis",
                                         "flag.folds.at",
                                         "flag.folds.angle",
                                         "flag.folds.from",
                                         "flag.folds.to",
                                         "pole.motion",
                                         "pole.axis",
                                         "pole.amplitude",
                                         "pole.frequency",
                                         "pole.radius",
                                         "pole.friction",
                                         "ground.height",
                                         "ground.friction",
                                         "contact.thickness",
                                         "gravity.acceleration",
                                         "wind.velocity",
                                         "wind.drag",
                                         "wind.lift",
                                         "wind.friction",
                                         "wind.lift_at_pole",
                                         "wind.panel",
                                         "wind.model",
                                         "wind.air_density",
                                         "wind.gusts",
                                         "wind.turbulence",
                                         "bending.stiffness",
                                         "bending.fiber_radius",
                                         "bending.fiber_modulus",
                                         "wrinkles.fiber_radius",
                                         "wrinkles.fiber_modulus",
                                         "wrinkles.k_prime",
                                         "wrinkles.tolerance",
                                         "wrinkles.rounds",
                                         "creases.yield_angle",
                                         "creases.set_time",
                                         "creases.relax_time",
                                         "creases.width",
                                         "infill.relax_iterations",
                                         "infill.solver",
                                         "solver.backend",
                                         "solver.substeps",
                                         "solver.iterations",
                                         "solver.linear",
                                         "solver.max_step_strain_change",
                                         "solver.wind_hold",
                                         "keyframe.time",
                                         "keyframe.corners",
                                         "output.file",
                                         "output.every",
                                         "output.flush_every",
                                         "output.fields",
                                         "output.dense",
                                         "output.compression",
                                         "output.checkpoint",
                                         "render.style",
                                         "render.size",
                                         "render.texture",
                                         "limits.max_strain",
                                         "limits.max_speed"};

std::string trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string_view::npos) return "";
  const auto last = s.find_last_not_of(" \t");
  return std::string(s.substr(first, last - first + 1));
}

void merge_into(toml::table& target, const toml::table& patch) {
  for (auto&& [key, node] : patch) {
    toml::node* existing = target.get(key.str());
    if (existing && existing->is_table() && node.is_table()) {
      merge_into(*existing->as_table(), *node.as_table());
    } else {
      target.insert_or_assign(key, node);
    }
  }
}

// --set KEY=VALUE: VALUE is TOML; a bare word (mass-spring) is taken as a string.
// Returns the dotted key, for error messages.
// toml++ parses nested tables, dotted keys and arrays by recursion: 50,000
// levels overflow the stack. No scene needs more than a handful; anything past
// kMaxNesting is refused before toml++ sees it. Counted outside strings and
// comments: the depth of [ and { in values, and the parts of a key (dots
// before a key's '=' or inside a [table] header).
constexpr int kMaxNesting = 64;

void check_nesting(std::string_view text, std::string_view source) {
  int depth = 0, line = 1, key_parts = 1;
  bool in_key = true;  // at the start of a line, before its '='
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      key_parts = 1;
      in_key = depth == 0;
      continue;
    }
    if (c == '#') {  // a comment runs to the end of the line
      while (i + 1 < text.size() && text[i + 1] != '\n') ++i;
      continue;
    }
    if (c == '"' || c == '\'') {  // a string: skip it (escapes in basic strings)
      const bool multi = text.substr(i, 3) == std::string(3, c);
      const std::string_view close = multi ? std::string_view(c == '"' ? "\"\"\"" : "'''")
                                           : std::string_view(c == '"' ? "\"" : "'");
      std::size_t j = i + close.size();
      while (j < text.size() && text.substr(j, close.size()) != close) {
        if (c == '"' && text[j] == '\\') ++j;
        if (j < text.size() && text[j] == '\n') ++line;
        ++j;
      }
      i = std::min(text.size(), j + close.size()) - 1;
      continue;
    }
    if (c == '=') in_key = false;
    if (c == '.' && in_key && ++key_parts > kMaxNesting)
      throw UserError(fmt::format("{}:{}: a key of more than {} parts: not a scene", source, line,
                                  kMaxNesting));
    if ((c == '[' || c == '{') && ++depth > kMaxNesting)
      throw UserError(fmt::format("{}:{}: nesting deeper than {} levels: not a scene", source, line,
                                  kMaxNesting));
    if ((c == ']' || c == '}') && depth > 0) --depth;
  }
}

std::string apply_override(toml::table& root, const Override& override) {
  const std::string& assignment = override.assignment;
  const std::string label = printable(override.typed, limits::kMessageBytes / 2);
  if (assignment.find_first_of("\n\r") != std::string::npos)
    throw UserError(label + ": a value must be on one line (it holds a line break)");
  const auto equals = assignment.find('=');
  if (equals == std::string::npos || trim(assignment.substr(0, equals)).empty())
    throw UserError(label + ": expected KEY=VALUE with a TOML value, e.g. --set flag.fine=[65,97]");
  std::string key = trim(assignment.substr(0, equals));  // returned: not const, moved
  const std::string value = trim(assignment.substr(equals + 1));
  check_nesting(key + " = " + value, label);
  toml::table patch;
  try {
    patch = toml::parse(key + " = " + value, label);
  } catch (const toml::parse_error& first_error) {
    const bool bare_word = !value.empty() && value.find_first_of("\"'[]{}=, ") == std::string::npos;
    try {
      if (!bare_word) throw;
      patch = toml::parse(key + " = \"" + value + "\"", label);
    } catch (const toml::parse_error&) {
      throw UserError(fmt::format("{}: not valid TOML ({})", label, first_error.description()));
    }
  }
  merge_into(root, patch);
  return key;
}

void read_scene_table(TableReader& in, Scene& scene, std::string_view source_path) {
  std::string stem = std::filesystem::path(std::string(source_path)).stem().string();
  scene.name = in.string("name", stem.empty() ? "scene" : stem);
  // Every fallback below is the field's own default (scene.hpp): one home per default.
  scene.mode = in.choice_of("mode", scene.mode, kModeNames);
  scene.fps = in.real("fps", scene.fps, Bound{0.0, limits::kFps, true}, "frames per second");
  scene.duration_s = in.real("duration", scene.duration_s, Bound{0.0, 1.0e6, true}, "s");
  if (auto frames = in.optional_integer("frames", 1, kMaxFrames))
    scene.duration_s = double(*frames - 1) / scene.fps;  // extension key, set by --frames
  scene.seed = std::uint64_t(
      in.integer("seed", (long long)scene.seed, 0, std::numeric_limits<long long>::max()));
  if (scene.duration_s * scene.fps + 1.0 > double(kMaxFrames))
    in.fail("duration", fmt::format("duration * fps gives {:.0f} frames; at most {} are allowed",
                                    scene.duration_s * scene.fps, kMaxFrames));
}

void read_flag_table(TableReader& in, FlagSpec& flag) {
  const auto size =
      in.real_pair("size", {flag.width_m, flag.height_m}, Bound{0.0, 1.0e3, true}, "[w, h] in m");
  flag.width_m = size[0];
  flag.height_m = size[1];
  flag.origin_m = in.vec3("origin", flag.origin_m, "m", limits::kCoordinate_m);
  if (auto fine = in.int_pair("fine", 2, kMaxLatticeSide, "[J, K] nodes",
                              std::array{flag.fine_rows, flag.fine_cols})) {
    flag.fine_rows = (*fine)[0];
    flag.fine_cols = (*fine)[1];
  }
  flag.coarse = in.int_pair("coarse", 2, kMaxLatticeSide, "[Jc, Kc] nodes");
  flag.areal_density_kg_m2 =
      in.real("areal_density", flag.areal_density_kg_m2, Bound{1.0e-4, 100.0, false}, "kg/m^2");
  flag.stretch_modulus_n_m =
      in.real("stretch_modulus", flag.stretch_modulus_n_m, Bound{0.0, 1.0e8, true}, "N/m");
  // Default shear stiffness: a tenth of the stretch stiffness, loosely woven
  // cloth (the one default derived from another key; FlagSpec's is 2e4 / 10).
  flag.shear_modulus_n_m =
      in.real("shear_modulus", flag.stretch_modulus_n_m / 10.0, Bound{0.0, 1.0e8, false}, "N/m");
  flag.damping_per_s = in.real("damping", flag.damping_per_s, Bound{0.0, 1.0e6, false}, "1/s");
  flag.pin = in.choice_of("pin", flag.pin, kPinNames);
  flag.initial_perturbation_m =
      in.real("initial_perturbation", flag.initial_perturbation_m, Bound::between(0.0, 10.0), "m");
  if (const toml::node* folds = in.table().get("folds")) {
    in.allow("folds");
    const toml::array* list = folds->as_array();
    if (!list || (!list->empty() && !list->is_array_of_tables()))
      in.fail("folds",
              "expected a list of fold lines [{ axis = \"col\", at = 0.5, angle = 2.5 }, ...]");
    for (const toml::node& item : *list) {
      TableReader fold_in(*item.as_table(), "flag.folds", detail::where(item.source()));
      Fold fold;
      fold.axis = fold_in.choice_of("axis", fold.axis, kFoldAxisNames);
      const std::optional<double> at =
          fold_in.optional_real("at", Bound{0.0, 1.0, true}, "(fraction of the flag)");
      const std::optional<double> angle =
          fold_in.optional_real("angle", Bound::between(-kPi, kPi), "rad");
      if (!at || !angle)
        fold_in.fail(at ? "angle" : "at", "a fold line needs where it lies (at) and its angle");
      if (*angle == 0.0)
        fold_in.fail("angle",
                     "a fold of 0 rad leaves nothing: positive folds toward the front (a valley "
                     "seen from it), negative toward the back (a mountain)");
      if (!(*at < 1.0))
        fold_in.fail("at", "1 is the flag's edge: a fold line lies inside, 0 < at < 1");
      fold.at = *at;
      fold.angle_rad = *angle;
      fold.from =
          fold_in.real("from", fold.from, Bound::between(0.0, 1.0), "(fraction of the line)");
      fold.to = fold_in.real("to", fold.to, Bound::between(0.0, 1.0), "(fraction of the line)");
      if (!(fold.from < fold.to))
        fold_in.fail("to", fmt::format("the fold runs from {} to {}: expected from < to", fold.from,
                                       fold.to));
      fold_in.finish(kAllKeys);
      flag.folds.push_back(fold);
    }
  }
}

void read_effect_tables(TableReader& root, Scene& scene) {
  if (const toml::table* t = root.subtable("pole")) {
    TableReader in(*t, "pole", root.where_of("pole"));
    // A table with a radius and no motion key is a pole that stands still;
    // any motion key (or a table without a radius, as before radii) shakes it.
    const bool moves = !in.has("radius") || in.has("motion") || in.has("axis") ||
                       in.has("amplitude") || in.has("frequency");
    if (moves) {
      in.choice("motion", "sine", {"sine"});
      PoleMotion pole;
      const Vec3 axis = in.vec3("axis", pole.axis_unit, "(direction)");
      if (axis.norm() == 0.0) in.fail("axis", "expected a non-zero direction [x, y, z]");
      pole.axis_unit = axis.normalized();
      pole.amplitude_m = in.real("amplitude", pole.amplitude_m, Bound::between(0.0, 100.0), "m");
      pole.frequency_hz = in.real("frequency", pole.frequency_hz, Bound::between(0.0, 100.0), "Hz");
      scene.pole = pole;
    }
    if (const auto radius = in.optional_real("radius", Bound{0.0, 1.0, true}, "m")) {
      SolidPole solid;
      solid.radius_m = *radius;
      solid.friction = in.real("friction", solid.friction, Bound::between(0.0, 10.0), "1");
      scene.solid_pole = solid;
    }
    in.finish(kAllKeys);
  }
  if (const toml::table* t = root.subtable("ground")) {
    TableReader in(*t, "ground", root.where_of("ground"));
    Ground ground;
    ground.height_m = in.real("height", ground.height_m, Bound::between(-1e4, 1e4), "m");
    ground.friction = in.real("friction", ground.friction, Bound::between(0.0, 10.0), "1");
    in.finish(kAllKeys);
    scene.ground = ground;
  }
  if (const toml::table* t = root.subtable("contact")) {
    TableReader in(*t, "contact", root.where_of("contact"));
    Contact contact;
    contact.thickness_m = in.real("thickness", contact.thickness_m, Bound{0.0, 1.0, true}, "m");
    in.finish(kAllKeys);
    scene.contact = contact;
  }
  if (const toml::table* t = root.subtable("gravity")) {
    TableReader in(*t, "gravity", root.where_of("gravity"));
    Gravity gravity;
    gravity.acceleration_m_s2 = in.vec3("acceleration", gravity.acceleration_m_s2, "m/s^2");
    // Past 1000 m/s^2 (100 g) no cloth scene is meant; the substeps would never end.
    if (!(gravity.acceleration_m_s2.stableNorm() <= 1000.0))
      in.fail("acceleration", fmt::format("expected a magnitude of at most 1000 m/s^2, got {:g}",
                                          gravity.acceleration_m_s2.stableNorm()));
    in.finish(kAllKeys);
    if (gravity.acceleration_m_s2.norm() > 0.0) scene.gravity = gravity;
  }
  if (const toml::table* t = root.subtable("wind")) {
    TableReader in(*t, "wind", root.where_of("wind"));
    Wind wind;
    wind.velocity_m_s = in.vec3("velocity", wind.velocity_m_s, "m/s");
    // Past 200 m/s (beyond any storm; a 1e308 wind never finished a frame).
    if (!(wind.velocity_m_s.stableNorm() <= 200.0))
      in.fail("velocity", fmt::format("expected a wind speed of at most 200 m/s, got {:g}",
                                      wind.velocity_m_s.stableNorm()));
    wind.drag = in.real("drag", wind.drag, Bound::between(0.0, 100.0), "");
    wind.lift = in.real("lift", wind.lift, Bound::between(0.0, 100.0), "");
    wind.lift_at_pole = in.boolean("lift_at_pole", wind.lift_at_pole);
    wind.friction = in.real("friction", wind.friction, Bound::between(0.0, 10.0), "");
    // Default: a sixth of the flag's length, so that the air sees every flag at
    // the same relative scale (docs/flag_physics.md, "The panel size").
    wind.panel_m = in.real("panel", scene.flag.width_m / 6.0, Bound{1.0e-3, 1.0e3, false}, "m");
    wind.model = in.choice_of("model", wind.model, kAirModelNames);
    wind.air_density_kg_m3 =
        in.real("air_density", wind.air_density_kg_m3, Bound{0.0, 100.0, true}, "kg/m^3");
    if (const toml::table* g = in.subtable("gusts")) {
      TableReader gin(*g, "wind.gusts", in.where_of("gusts"));
      Gusts gusts;
      gusts.amplitude =
          gin.real("amplitude", gusts.amplitude, Bound::between(0.0, 10.0), "(fraction)");
      gusts.period_s = gin.real("period", gusts.period_s, Bound{1.0e-3, 1.0e6, false}, "s");
      wind.gusts = gusts;
      gin.finish(kAllKeys);
    }
    if (const toml::table* tt = in.subtable("turbulence")) {
      TableReader tin(*tt, "wind.turbulence", in.where_of("turbulence"));
      Turbulence turbulence;
      turbulence.intensity =
          tin.real("intensity", turbulence.intensity, Bound::between(0.0, 10.0), "");
      turbulence.length_scale_m =
          tin.real("length_scale", turbulence.length_scale_m, Bound{1.0e-3, 1.0e4, false}, "m");
      wind.turbulence = turbulence;
      tin.finish(kAllKeys);
    }
    in.finish(kAllKeys);
    scene.wind = wind;
  }
  if (const toml::table* t = root.subtable("bending")) {
    TableReader in(*t, "bending", root.where_of("bending"));
    Bending bending;
    const std::optional<double> stiffness =
        in.optional_real("stiffness", Bound::between(0.0, 1.0), "N m");
    bending.fiber_radius_m = in.optional_real("fiber_radius", Bound{0.0, 0.01, true}, "m");
    bending.fiber_modulus_pa = in.optional_real("fiber_modulus", Bound{0.0, 1.0e12, true}, "Pa");
    if (bending.fiber_modulus_pa && !bending.fiber_radius_m)
      in.fail("fiber_modulus", "a yarn needs its radius too (bending.fiber_radius, m)");
    if (bending.fiber_modulus_pa && stiffness)
      in.fail("fiber_modulus",
              "the yarn's modulus and `stiffness` both state the bending (D = pi E r^3 / 8); "
              "state one of them");
    bending.rigidity_j = stiffness.value_or(bending.rigidity_j);
    if (bending.fiber_modulus_pa) {  // D of a sheet of these yarns (scene/material.hpp)
      bending.rigidity_j =
          Yarn{*bending.fiber_radius_m, *bending.fiber_modulus_pa}.sheet_rigidity_j();
      if (!(bending.rigidity_j <= 1.0))
        in.fail("fiber_modulus",
                fmt::format("a sheet of these yarns has D = pi E r^3 / 8 = {:g} N m: expected at "
                            "most 1 N m (a steel plate's); a thinner or softer yarn",
                            bending.rigidity_j));
    }
    scene.bending = bending;
    in.finish(kAllKeys);
  }
}

// Keyframe corners no cloth of the flag's size could span (a typo, or a
// flag torn apart): the infill would stretch every fiber to reach them and
// 3.1 would cut the motion into ever more steps. Each pair of corners may be
// at most kCornerReach times their rest distance apart.
constexpr double kCornerReach = 1.1;

void check_corner_reach(const TableReader& in, const Keyframe& key, const FlagSpec& flag) {
  static constexpr const char* kNames[4] = {"(0,0)", "(0,K-1)", "(J-1,0)", "(J-1,K-1)"};
  const double w = flag.width_m, h = flag.height_m;
  const double rest[4][4] = {{0.0, w, h, std::hypot(w, h)},
                             {w, 0.0, std::hypot(w, h), h},
                             {h, std::hypot(w, h), 0.0, w},
                             {std::hypot(w, h), h, w, 0.0}};
  for (int a = 0; a < 4; ++a)
    for (int b = a + 1; b < 4; ++b) {
      const double apart = (key.corners_m[a] - key.corners_m[b]).norm();
      if (apart > kCornerReach * rest[a][b])
        in.fail("corners",
                fmt::format("corners {} and {} are {:.4g} m apart, but the {:.4g} x {:.4g} m flag "
                            "spans only {:.4g} m between them (at most {:.4g} m with {:.0f}% "
                            "stretch)",
                            kNames[a], kNames[b], apart, w, h, rest[a][b],
                            kCornerReach * rest[a][b], (kCornerReach - 1.0) * 100.0));
    }
}

void read_infill_tables(TableReader& root, Scene& scene) {
  if (const toml::table* t = root.subtable("wrinkles")) {
    TableReader in(*t, "wrinkles", root.where_of("wrinkles"));
    Wrinkles w;
    w.fiber_radius_m = in.optional_real("fiber_radius", Bound{0.0, 0.01, true}, "m");
    w.fiber_modulus_pa = in.optional_real("fiber_modulus", Bound{0.0, 1.0e12, true}, "Pa");
    // One material: the yarn of [bending] (or the one its stiffness needs) is
    // the wrinkles' too; a key of [wrinkles] that says otherwise is refused here.
    Scene with = scene;
    with.wrinkles = w;
    material_of(with, [&](std::string_view key, const std::string& message) {
      in.fail(key.substr(key.find('.') + 1), message);
    });
    w.k_prime = in.optional_real("k_prime", Bound::between(0.0, 1.0e6), "N/m");
    w.tolerance = in.optional_real("tolerance", Bound::non_negative(), "(relative)");
    if (auto rounds = in.optional_integer("rounds", 0, 1000)) w.rounds = int(*rounds);
    in.finish(kAllKeys);
    scene.wrinkles = w;
  }
  if (const toml::table* t = root.subtable("creases")) {
    TableReader in(*t, "creases", root.where_of("creases"));
    Creases creases;
    creases.yield_angle_rad =
        in.real("yield_angle", creases.yield_angle_rad, Bound::between(0.0, kPi), "rad");
    creases.set_time_s = in.real("set_time", creases.set_time_s, Bound{0.0, 1.0e9, true}, "s");
    creases.relax_time_s =
        in.real("relax_time", creases.relax_time_s, Bound{0.0, 1.0e9, true}, "s");
    creases.width_m = in.real("width", creases.width_m, Bound{0.0, 1.0, true}, "m");
    in.finish(kAllKeys);
    scene.creases = creases;
  }
  if (const toml::table* t = root.subtable("infill")) {
    TableReader in(*t, "infill", root.where_of("infill"));
    InfillSettings settings;
    if (auto sweeps = in.optional_integer("relax_iterations", 1, 100000))
      settings.relax_iterations = int(*sweeps);
    if (in.has("solver"))
      settings.solver = in.choice_of("solver", InfillSolverKind::kSmooth, kInfillSolverNames);
    scene.infill = settings;
    in.finish(kAllKeys);
  }
  if (const toml::node* frames = root.table().get("keyframe")) {
    root.allow("keyframe");
    const toml::array* list = frames->as_array();
    if (!list || !list->is_array_of_tables())
      root.fail("keyframe", "expected [[keyframe]] tables, each with time and corners");
    for (const toml::node& item : *list) {
      TableReader in(*item.as_table(), "keyframe", detail::where(item.source()));
      Keyframe key;
      key.time_s = in.real("time", key.time_s, Bound::between(0.0, 1.0e6), "s");
      const toml::node* corners = in.table().get("corners");
      in.allow("corners");
      const toml::array* array = corners ? corners->as_array() : nullptr;
      if (!array || array->size() != 4)
        in.fail(
            "corners",
            "expected 4 corners [[x,y,z], ...] in the order (0,0), (0,K-1), (J-1,0), (J-1,K-1)");
      for (int c = 0; c < 4; ++c)
        key.corners_m[c] = in.vec3_item("corners", *array->get(c), "m", limits::kCoordinate_m);
      in.note("corners",
              fmt::format("[{}, {}, {}, {}]", detail::toml_vec3(key.corners_m[0]),
                          detail::toml_vec3(key.corners_m[1]), detail::toml_vec3(key.corners_m[2]),
                          detail::toml_vec3(key.corners_m[3])),
              "m", "4 corners [x, y, z], (0,0), (0,K-1), (J-1,0), (J-1,K-1)");
      check_corner_reach(in, key, scene.flag);
      in.finish(kAllKeys);
      if (!scene.keyframes.empty() && key.time_s <= scene.keyframes.back().time_s)
        in.fail("time", fmt::format("keyframes must be in increasing time; {} s follows {} s",
                                    key.time_s, scene.keyframes.back().time_s));
      scene.keyframes.push_back(key);
    }
  }
}

// The settings tables ([solver], [output], [limits]) are read when absent
// too, as empty tables: the same defaults, and every key the run uses is read
// (the KeyLog: `flag-sim scene` prints them).
const toml::table& empty_table() {
  static const toml::table empty;
  return empty;
}

void read_run_tables(TableReader& root, Scene& scene) {
  {
    const toml::table* t = root.subtable("solver");
    TableReader in(t ? *t : empty_table(), "solver", root.where_of("solver"));
    scene.solver.backend = in.choice_of("backend", scene.solver.backend, kBackendNames);
    scene.solver.substeps = int(in.integer("substeps", scene.solver.substeps, 1, 1'000'000));
    if (auto iterations = in.optional_integer("iterations", 1, 10'000))
      scene.solver.iterations = int(*iterations);
    scene.solver.linear = in.choice_of("linear", scene.solver.linear, kLinearSolverNames);
    scene.solver.max_step_strain_change = in.real(
        "max_step_strain_change", scene.solver.max_step_strain_change, Bound{0.0, 10.0, true}, "");
    scene.solver.wind_hold = in.real("wind_hold", scene.solver.wind_hold, Bound::between(0.0, 0.5),
                                     "fraction of the wind's response time");
    in.finish(kAllKeys);
  }
  {
    const toml::table* t = root.subtable("output");
    TableReader in(t ? *t : empty_table(), "output", root.where_of("output"));
    scene.output.file = in.string("file", scene.output.file);
    if (in.has("file") && scene.output.file.empty())
      in.fail("file", "an empty path; give a file name or leave the key out (out/<scene.name>.h5)");
    scene.output.every = int(in.integer("every", scene.output.every, 1, kMaxFrames));
    scene.output.flush_every =
        int(in.integer("flush_every", scene.output.flush_every, 1, kMaxFrames));
    scene.output.fields = in.choice_set("fields", scene.output.fields, {"strain", "velocity"});
    scene.output.dense = in.boolean("dense", scene.output.dense);
    scene.output.compression = int(in.integer("compression", scene.output.compression, 0, 9));
    scene.output.checkpoint = in.boolean("checkpoint", scene.output.checkpoint);
    in.finish(kAllKeys);
  }
  if (const toml::table* t = root.subtable("render")) {
    TableReader in(*t, "render", root.where_of("render"));
    Render render;
    render.style = in.choice_of("style", render.style, kRenderStyleNames);
    if (auto size = in.int_pair("size", limits::kImageSideMin, limits::kImageSideMax,
                                "[w, h] pixels", render.size_px))
      render.size_px = *size;
    render.texture = in.string("texture", render.texture);
    if (t->get("texture") && render.texture.empty())
      in.fail("texture", "an empty path; give a PNG or leave the key out");
    in.finish(kAllKeys);
    scene.render = render;
  }
  {
    const toml::table* t = root.subtable("limits");
    TableReader in(t ? *t : empty_table(), "limits", root.where_of("limits"));
    scene.limits.max_strain = in.real("max_strain", scene.limits.max_strain, Bound::positive(), "");
    scene.limits.max_speed_m_s =
        in.real("max_speed", scene.limits.max_speed_m_s, Bound{0.0, 1.0e6, true}, "m/s");
    in.finish(kAllKeys);
  }
}

Scene build_scene(const toml::table& root, std::string_view source_path,
                  bool mode_from_command_line) {
  Scene scene;
  const std::string top = fmt::format("{}:1:1", source_path);
  TableReader in(root, "", top);
  static const toml::table empty;
  const toml::table* scene_table = in.subtable("scene");
  TableReader scene_in(scene_table ? *scene_table : empty, "scene", top);
  read_scene_table(scene_in, scene, source_path);
  scene_in.finish(kAllKeys);

  const toml::table* flag_table = in.subtable("flag");
  TableReader flag_in(flag_table ? *flag_table : empty, "flag", top);
  read_flag_table(flag_in, scene.flag);
  flag_in.finish(kAllKeys);

  read_effect_tables(in, scene);
  read_infill_tables(in, scene);
  read_run_tables(in, scene);
  in.finish(kAllKeys);

  detail::check_consistency(scene, in, scene_in, flag_in, mode_from_command_line);

  std::ostringstream text;
  text << toml::toml_formatter(root) << "\n";
  scene.toml_text = text.str();
  return scene;
}

}  // namespace

std::string toml_string(std::string_view text) {
  std::string quoted = "\"";
  for (const unsigned char c : text) {
    if (c == '"' || c == '\\') quoted += '\\';
    if (c < 0x20 || c == 0x7f)
      quoted += fmt::format("\\u{:04x}", c);
    else
      quoted += char(c);
  }
  return quoted + "\"";
}

std::vector<Override> set_overrides(std::span<const std::string> assignments) {
  std::vector<Override> overrides;
  for (const std::string& assignment : assignments)
    overrides.push_back({assignment, "--set " + assignment});
  return overrides;
}

Scene parse_scene(std::string_view toml_text, std::string_view source_path,
                  std::span<const std::string> overrides) {
  return parse_scene(toml_text, source_path, set_overrides(overrides));
}

Scene load_scene_file(const std::string& path, std::span<const std::string> overrides) {
  return load_scene_file(path, set_overrides(overrides));
}

Scene parse_scene(std::string_view toml_text, std::string_view source_path,
                  std::span<const Override> overrides, std::vector<SceneKey>* keys) {
  check_nesting(toml_text, source_path);
  toml::table root;
  try {
    root = toml::parse(toml_text, source_path);
  } catch (const toml::parse_error& error) {
    throw UserError(
        fmt::format("{}: invalid TOML: {}", detail::where(error.source()), error.description()));
  }
  std::vector<std::pair<std::string, std::string>> labels;
  for (const Override& override : overrides)
    labels.emplace_back(apply_override(root, override), printable(override.typed, 300));
  const bool mode_from_command_line = std::any_of(
      labels.begin(), labels.end(),
      [](const auto& label) { return label.first == "scene.mode" || label.first == "scene"; });
  const detail::OverrideLabels scope(std::move(labels));
  if (!keys) return build_scene(root, source_path, mode_from_command_line);
  const detail::KeyLog log;
  Scene scene = build_scene(root, source_path, mode_from_command_line);
  keys->clear();
  for (const detail::KeyRecord& r : log.records())
    keys->push_back({r.key, r.value, r.unit, r.range, r.given});
  return scene;
}

Scene load_scene_file(const std::string& path, std::span<const Override> overrides,
                      std::vector<SceneKey>* keys) {
  // Only a regular file, and only as much as a scene can be: a FIFO would
  // block, /dev/zero would never end.
  constexpr std::uintmax_t kMaxSceneBytes = 1 << 20;
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (std::filesystem::is_directory(status))
    throw UserError(fmt::format("{}: is a directory, expected a scene file (.toml)", path));
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    throw UserError(fmt::format("{}: not a regular file, expected a scene file (.toml)", path));
  std::ifstream file(path, std::ios::binary);
  if (!file) throw UserError(fmt::format("{}: cannot open scene file (does it exist?)", path));
  if (const std::uintmax_t size = std::filesystem::file_size(path, ec);
      !ec && size > kMaxSceneBytes)
    throw UserError(fmt::format("{}: {} bytes, more than a scene file can be (at most {})", path,
                                size, kMaxSceneBytes));
  std::ostringstream text;
  text << file.rdbuf();
  return parse_scene(text.str(), path, overrides, keys);
}

}  // namespace flagsim
