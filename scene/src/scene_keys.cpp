#include "flagsim/scene/scene_keys.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>

namespace flagsim {
namespace {

// The one hand-written part: what each key means. A test checks that every
// key the parser reads is here.
constexpr KeyMeaning kMeanings[] = {
    {"scene.name", "label copied into the output; absent: the file's name"},
    {"scene.mode",
     "hybrid (physics on flag.coarse, the paper's infill on flag.fine), mass-spring, bullet, "
     "implicit, xpbd (physics on every fine node) or infill (corners from [[keyframe]])"},
    {"scene.fps", "output frames per second"},
    {"scene.duration", "simulated time"},
    {"scene.frames", "output frames, t = 0 included (instead of duration; run --frames sets it)"},
    {"scene.seed", "every random choice (turbulence, initial perturbation) derives from it"},
    {"flag.size", "rest width (pole to fly end) and height"},
    {"flag.origin", "rest position of node (0, 0), the top of the pole edge"},
    {"flag.fine", "the dense lattice: J rows, K columns of nodes"},
    {"flag.coarse", "the lattice the physics runs on in hybrid mode (must divide flag.fine)"},
    {"flag.areal_density", "cloth mass per area"},
    {"flag.stretch_modulus", "in-plane (2D) stretch stiffness"},
    {"flag.shear_modulus", "in-plane shear stiffness; absent: a tenth of flag.stretch_modulus"},
    {"flag.damping", "velocity damping rate"},
    {"flag.pin", "the nodes held: left (the pole edge), right, top, corners or none"},
    {"flag.initial_perturbation",
     "seeded smooth out-of-plane shape at t = 0 (a flat flag in a wind along its plane never "
     "starts to flap without one)"},
    {"flag.folds",
     "fold lines present at t = 0, as if the flag had been stored folded: a list of "
     "{ axis, at, angle } (needs [creases])"},
    {"flag.folds.axis",
     "row (the fold line runs along a row, bending the columns) or col (along a column, "
     "bending the rows)"},
    {"flag.folds.at", "where the fold line lies: a fraction of the height (row) or width (col)"},
    {"flag.folds.from",
     "where along its line the fold starts: a fraction of the width (row) or height (col)"},
    {"flag.folds.to", "where along its line the fold ends (from < to)"},
    {"flag.folds.angle",
     "the crease's rest angle, rad: + toward the front (a valley seen from it), - toward the "
     "back; pi: folded flat on itself"},
    {"pole.motion", "how the pinned nodes move: sine"},
    {"pole.axis", "direction of the pole's motion"},
    {"pole.amplitude", "amplitude of the pole's motion"},
    {"pole.frequency", "frequency of the pole's motion"},
    {"pole.radius",
     "the pole as a solid cylinder touching the pinned edge (optional; with no motion key it "
     "stands still)"},
    {"pole.friction", "Coulomb friction of the cloth on the solid pole"},
    {"ground.height", "a solid horizontal plane at this y that no node goes below"},
    {"ground.friction", "Coulomb friction of the cloth on the ground"},
    {"contact.thickness",
     "self-contact (full-lattice and hybrid modes): parts of the cloth not neighbours in it (2 "
     "thicknesses apart at rest) stay this far apart, or a quarter of the lattice's spacing if "
     "more; in hybrid mode the coarse physics' layers and the dense lattice's"},
    {"gravity.acceleration", "gravity; without [gravity] there is none"},
    {"wind.velocity", "mean wind; without [wind] there is none"},
    {"wind.drag", "normal-force coefficient of a flat plate"},
    {"wind.lift", "lift coefficient (the panel wind's quasi-steady lift)"},
    {"wind.friction", "skin-friction coefficient of both faces, on the planform area"},
    {"wind.lift_at_pole",
     "true: lift on the air panels at the held edge too (the pole's wake); default false"},
    {"wind.panel",
     "side of the panels the air sees the cloth on (waves shorter than two are "
     "not driven); absent: a sixth of flag.size[0]"},
    {"wind.model",
     "panels (quasi-steady force on panels) or vortex (experimental unsteady vortex lattice; "
     "docs/flag_physics.md)"},
    {"wind.air_density", "air density"},
    {"wind.gusts.amplitude", "gusts: the wind speed swings by this fraction of its mean"},
    {"wind.gusts.period", "gusts: period of the swing"},
    {"wind.turbulence.intensity", "turbulence: along-wind std over the mean speed"},
    {"wind.turbulence.length_scale", "turbulence: integral length scale (von Karman spectrum)"},
    {"creases.yield_angle",
     "a fold sharper than this sets into a crease (the cloth's rest angle there); one below "
     "it leaves nothing"},
    {"creases.set_time", "how fast a fold held past the yield sets (time constant)"},
    {"creases.relax_time",
     "how fast a crease relaxes while the cloth is held flatter than it and pulled hard (time "
     "constant; slower under less tension, none without)"},
    {"creases.width",
     "width of a crease's hinge (the yarns bent past their yield): how much of the tension "
     "across a crease works on it"},
    {"bending.stiffness",
     "bending rigidity D of the cloth in the physics (absent: 1e-4, or pi E r^3 / 8 from the "
     "yarn); without [bending]: none"},
    {"bending.fiber_radius",
     "r of the cloth's yarn (the paper's eqs. (1)-(10)), also [wrinkles]' yarn; with "
     "`stiffness`, E = 8 D / (pi r^3)"},
    {"bending.fiber_modulus",
     "E of the cloth's yarn, instead of `stiffness`: D = pi E r^3 / 8 (yarns side by side)"},
    {"wrinkles.fiber_radius",
     "r of the paper's eqs. (1)-(10) (absent: [bending]'s yarn, else 1 mm); without "
     "[wrinkles]: no step 3.5"},
    {"wrinkles.fiber_modulus",
     "E of the paper's eqs. (1)-(10) (absent: [bending]'s yarn, else 1 GPa)"},
    {"wrinkles.k_prime", "k' of eq. (13) per unit length, N/m (absent: 1)"},
    {"wrinkles.tolerance",
     "step 3.5 leaves a fiber alone when |E - e| / max(E, e) is below this (absent: 0, every "
     "fiber re-laid)"},
    {"wrinkles.rounds", "alternations of steps 3.5 and 3.4 (absent: 2)"},
    {"infill.relax_iterations",
     "most passes of the paper solver's step 3.4 (absent: 8000 in hybrid mode, 1000 in infill "
     "mode)"},
    {"infill.solver", "smooth or paper; absent: smooth in hybrid mode, paper in infill mode"},
    {"keyframe.time", "infill mode: the time of a [[keyframe]]"},
    {"keyframe.corners",
     "infill mode: the 4 corners at that time, (0,0), (0,K-1), (J-1,0), (J-1,K-1); linear in "
     "time between keyframes"},
    {"solver.backend", "the physics in hybrid mode: spring-damper, bullet, implicit or xpbd"},
    {"solver.substeps",
     "fewest substeps per frame (the explicit backends and XPBD choose more from their stability "
     "limits); implicit Euler's steps per frame"},
    {"solver.iterations",
     "Bullet's solver passes (absent: 10), implicit Euler's Newton iterations (1), XPBD's "
     "constraint passes (1)"},
    {"solver.linear", "implicit backend only: cg or cholesky"},
    {"solver.max_step_strain_change",
     "implicit backend only: a step changing a link's strain by more is taken as two halves"},
    {"solver.wind_hold",
     "spring-damper only: the wind's force is held over substeps for at most this fraction of its "
     "fastest velocity response (absent: 0.1); 0: evaluated every substep"},
    {"output.file", "output file; absent: out/<scene.name>.h5 (run -o wins)"},
    {"output.every", "keep every n-th simulated frame"},
    {"output.flush_every", "frames written between flushes to disk"},
    {"output.fields", "per-node fields beside the positions: strain, velocity"},
    {"output.dense",
     "false (hybrid): keep the coarse trajectory only; flag-sim refine recomputes the frames"},
    {"output.compression", "HDF5 deflate level of the per-node datasets, 0 (none) to 9"},
    {"output.checkpoint",
     "keep the state (/checkpoint) at the first frame, once a second and at the end, for run "
     "--resume"},
    {"render.style", "how render draws the frames: wireframe, shaded or textured"},
    {"render.size", "render's image size"},
    {"render.texture", "PNG for the textured style"},
    {"limits.max_strain", "past it the run stops as diverged (exit 3), good frames kept"},
    {"limits.max_speed", "a node faster than this is a numerical blow-up (diverged)"},
};

std::string_view meaning_of(std::string_view key) {
  for (const KeyMeaning& m : kMeanings)
    if (m.key == key) return m.meaning;
  return {};
}

// "wind.gusts.period" -> table "wind.gusts", name "period".
std::pair<std::string, std::string> split_key(const std::string& key) {
  const std::size_t dot = key.rfind('.');
  return {key.substr(0, dot), key.substr(dot + 1)};
}

bool table_present(const Scene& scene, const std::string& table) {
  if (table == "pole") return scene.pole.has_value() || scene.solid_pole.has_value();
  if (table == "ground") return scene.ground.has_value();
  if (table == "contact") return scene.contact.has_value();
  if (table == "gravity") return scene.gravity.has_value();
  if (table == "wind" || table.starts_with("wind.")) return scene.wind.has_value();
  if (table == "bending") return scene.bending.has_value();
  if (table == "wrinkles") return scene.wrinkles.has_value();
  if (table == "creases") return scene.creases.has_value();
  if (table == "infill") return scene.infill.has_value();
  if (table == "keyframe") return !scene.keyframes.empty();
  if (table == "render") return scene.render.has_value();
  if (table == "solver") return scene.mode != Mode::kInfill;  // no physics, no solver
  return true;  // scene, flag, output, limits: always read
}

// A default the scene file may not state: keys its mode or backend does not use.
bool default_printable(const Scene& scene, const std::string& key) {
  const bool implicit = scene.mode == Mode::kImplicit ||
                        (scene.mode == Mode::kHybrid && scene.solver.backend == Backend::kImplicit);
  if (key == "solver.linear" || key == "solver.max_step_strain_change") return implicit;
  if (key == "solver.backend") return scene.mode == Mode::kHybrid;
  if (key == "solver.wind_hold")
    return scene.wind &&
           (scene.mode == Mode::kMassSpring ||
            (scene.mode == Mode::kHybrid && scene.solver.backend == Backend::kSpringDamper));
  return true;
}

}  // namespace

std::span<const KeyMeaning> key_meanings() {
  return kMeanings;
}

std::string effective_scene_toml(const Scene& scene, std::span<const SceneKey> keys) {
  std::string out =
      "# The scene as flag-sim takes it: every key its run uses, \"default\" where the scene\n"
      "# leaves a key to its default (flag-sim help keys: what each key means).\n";
  std::string table;
  // flag.folds' entries, gathered into one line of [flag]: folds = [{ ... }, ...].
  std::string folds;
  const auto end_folds = [&] {
    if (!folds.empty()) out += fmt::format("folds = [{} }}]\n", folds);
    folds.clear();
  };
  for (const SceneKey& k : keys) {
    const auto [where, name] = split_key(k.key);
    if (where == "flag.folds") {  // a new fold at each fold's first key, axis
      folds += fmt::format("{}{} = {}", name == "axis" ? (folds.empty() ? "{ " : " }, { ") : ", ",
                           name, k.value);
      continue;
    }
    end_folds();
    if (!table_present(scene, where)) continue;
    if (!k.given && !default_printable(scene, k.key)) continue;
    // A new [[keyframe]] at each keyframe's first key; other tables once.
    const bool keyframe_start = where == "keyframe" && name == "time";
    if (where != table || keyframe_start) {
      out += where == "keyframe" ? "\n[[keyframe]]\n" : fmt::format("\n[{}]\n", where);
      table = where;
    }
    if (k.value.empty()) {  // an optional key that is not set
      // scene.frames is duration's other spelling: nothing to say when unset.
      if (k.key != "scene.frames")
        out += fmt::format("# {} (not set): {}\n", name, meaning_of(k.key));
      continue;
    }
    const std::string line = fmt::format("{} = {}", name, k.value);
    std::string note = k.unit;
    if (!k.given) note += note.empty() ? "default" : "; default";
    out += note.empty() ? line + "\n" : fmt::format("{:<34}# {}\n", line, note);
  }
  end_folds();
  return out;
}

std::string keys_reference() {
  // The parser's own reads: an empty scene (every scene, flag and settings key
  // at its default), one with every optional table present (their keys'
  // defaults), and an infill scene (the keyframe keys).
  const std::string every_table =
      "[scene]\nmode = \"hybrid\"\n[flag]\ncoarse = [9, 13]\n[pole]\n[ground]\n[gravity]\n[wind]\n"
      "[wind.gusts]\n[wind.turbulence]\n[bending]\n[wrinkles]\n[creases]\n[infill]\n[render]\n";
  const std::string infill =
      "[scene]\nmode = \"infill\"\n[[keyframe]]\ntime = 0.0\n"
      "corners = [[0.0, 2.0, 0.0], [1.5, 2.0, 0.0], [0.0, 1.0, 0.0], [1.5, 1.0, 0.0]]\n";
  std::map<std::string, SceneKey, std::less<>> read;
  const std::string solid_pole = "[pole]\nradius = 0.03\n";  // the keys of a standing pole
  // Self-contact, in a full-lattice mode (the hybrid's is the same table).
  const std::string contact = "[scene]\nmode = \"mass-spring\"\n[contact]\n";
  for (const std::string& text : {std::string(), every_table, infill, solid_pole, contact}) {
    std::vector<SceneKey> keys;
    parse_scene(text, "<keys>", std::span<const Override>(), &keys);
    for (const SceneKey& k : keys)
      if (auto it = read.find(k.key); it == read.end() || (it->second.given && !k.given))
        read.insert_or_assign(k.key, k);
  }
  std::string out =
      "Every scene key: KEY = DEFAULT (unit; what it accepts), then what it means.\n"
      "A table's keys are read only when the table is in the scene ([wind], [gravity], ...);\n"
      "flag-sim scene FILE prints a scene with the value of every key its run uses.\n";
  std::string table;
  for (const KeyMeaning& m : kMeanings) {
    const std::string key(m.key);
    const auto [where, name] = split_key(key);
    if (where != table) {
      out += where == "keyframe"     ? "\n[[keyframe]]\n"
             : where == "flag.folds" ? "\n[flag] folds = [{ axis, at, angle }, ...], each:\n"
                                     : fmt::format("\n[{}]\n", where);
      table = where;
    }
    const auto it = read.find(key);
    std::string head = key;
    if (key == "scene.name") {  // its default is the file's own name
      head += " (a string)";
    } else if (it != read.end()) {
      const SceneKey& k = it->second;
      // Optional keys have no value when absent (their meaning says what then).
      head += k.given ? " (no default)" : k.value.empty() ? " (optional)" : " = " + k.value;
      head += fmt::format(" ({}{}{})", k.unit, k.unit.empty() ? "" : "; ", k.range);
    }
    out += fmt::format("  {}\n      {}\n", head, m.meaning);
  }
  return out;
}

}  // namespace flagsim
