#include "flagsim/scene/scene.hpp"

#include <fmt/format.h>

#include <cassert>
#include <cmath>
#include <numbers>
#include <string>

#include "flagsim/core/errors.hpp"
#include "flagsim/core/limits.hpp"
#include "flagsim/scene/material.hpp"
#include "scene_checks.hpp"

namespace flagsim {

int Scene::simulated_frames() const {
  // t = 0 is frame 0; the last frame is the one at (or just before) duration.
  return int(std::floor(duration_s * fps + 1e-9)) + 1;
}

Lattice Scene::fine_lattice() const {
  return Lattice::rectangle(flag.fine_rows, flag.fine_cols, flag.width_m, flag.height_m,
                            flag.origin_m);
}

const char* to_string(Mode mode) {
  return name_in(kModeNames, mode).data();
}
const char* to_string(PinSet pin) {
  return name_in(kPinNames, pin).data();
}
const char* to_string(FoldAxis axis) {
  return name_in(kFoldAxisNames, axis).data();
}
const char* to_string(InfillSolverKind kind) {
  return name_in(kInfillSolverNames, kind).data();
}
const char* to_string(Backend backend) {
  return name_in(kBackendNames, backend).data();
}
const char* to_string(LinearSolver linear) {
  return name_in(kLinearSolverNames, linear).data();
}
const char* to_string(RenderStyle style) {
  return name_in(kRenderStyleNames, style).data();
}

std::optional<Backend> backend_of(const Scene& scene) {
  switch (scene.mode) {
    case Mode::kHybrid:
      return scene.solver.backend;
    case Mode::kMassSpring:
      return Backend::kSpringDamper;
    case Mode::kBullet:
      return Backend::kBullet;
    case Mode::kImplicit:
      return Backend::kImplicit;
    case Mode::kXpbd:
      return Backend::kXpbd;
    case Mode::kInfill:
      return std::nullopt;
  }
  return std::nullopt;
}

std::string backend_name_of(const Scene& scene) {
  const std::optional<Backend> backend = backend_of(scene);
  return backend ? to_string(*backend) : "";
}

InfillSolverKind infill_solver_of(const Scene& scene) {
  if (scene.infill && scene.infill->solver) return *scene.infill->solver;
  return scene.mode == Mode::kInfill ? InfillSolverKind::kPaper : InfillSolverKind::kSmooth;
}

int paper_relax_sweeps_of(const Scene& scene) {
  if (scene.infill && scene.infill->relax_iterations) return *scene.infill->relax_iterations;
  // Infill mode: one cell spans the whole flag, so 3.4 needs many passes; it
  // stops early once converged (twisted.toml at 33 x 49: 0.78% max strain with
  // 1000, 1.7% with 200). Hybrid: on the default scene at 129 x 193 a frame
  // needs ~1400 Gauss-Seidel passes on average, a few frames over 5000; 8000
  // kept the dense strain under 1% on every frame.
  return scene.mode == Mode::kInfill ? 1000 : 8000;
}

Scene in_mode(const Scene& scene, Mode mode) {
  Scene variant = scene;
  variant.mode = mode;
  return variant;
}

Scene with_substeps(const Scene& scene, int substeps) {
  Scene variant = scene;
  variant.solver.substeps = substeps;
  return variant;
}

Scene with_resolved_backend(const Scene& scene) {
  Scene variant = scene;
  if (const std::optional<Backend> backend = backend_of(scene)) variant.solver.backend = *backend;
  return variant;
}

Scene on_coarse_lattice(const Scene& scene) {
  assert(scene.flag.coarse.has_value());
  Scene coarse = scene;
  coarse.flag.fine_rows = (*scene.flag.coarse)[0];
  coarse.flag.fine_cols = (*scene.flag.coarse)[1];
  coarse.flag.coarse.reset();
  return coarse;
}

void check_scene(const Scene& scene) {
  const auto fail = [](const char* key, const std::string& what) {
    throw UserError(fmt::format("scene: {}: {}", key, what));
  };
  const auto positive = [&](const char* key, double value, const char* unit) {
    if (!(value > 0.0 && std::isfinite(value)))
      fail(key, fmt::format("{} {}: expected a positive finite number", value, unit));
  };
  const FlagSpec& flag = scene.flag;
  const auto side = [&](const char* key, int n) {
    if (n < 2 || n > limits::kLatticeSide)
      fail(key, fmt::format("{} nodes a side: expected 2 to {}", n, limits::kLatticeSide));
  };
  side("flag.fine (rows)", flag.fine_rows);
  side("flag.fine (columns)", flag.fine_cols);
  if (double(flag.fine_rows) * flag.fine_cols > double(limits::kLatticeNodes))
    fail("flag.fine", fmt::format("{} x {} nodes: more than the {} allowed", flag.fine_rows,
                                  flag.fine_cols, limits::kLatticeNodes));
  if (flag.coarse) {
    const auto [rows, cols] = *flag.coarse;
    if (rows < 2 || cols < 2 || rows > flag.fine_rows || cols > flag.fine_cols ||
        (flag.fine_rows - 1) % (rows - 1) != 0 || (flag.fine_cols - 1) % (cols - 1) != 0)
      fail("flag.coarse", fmt::format("[{}, {}] does not divide flag.fine = [{}, {}] (each side's "
                                      "links a multiple of the coarse side's)",
                                      rows, cols, flag.fine_rows, flag.fine_cols));
  }
  if (scene.mode == Mode::kHybrid && !flag.coarse)
    fail("flag.coarse", "hybrid mode needs the lattice the physics runs on");
  if (scene.mode == Mode::kInfill && scene.keyframes.empty())
    fail("keyframe", "infill mode needs keyframes with the corner positions");
  positive("flag.size (width)", flag.width_m, "m");
  positive("flag.size (height)", flag.height_m, "m");
  positive("flag.areal_density", flag.areal_density_kg_m2, "kg/m^2");
  positive("flag.stretch_modulus", flag.stretch_modulus_n_m, "N/m");
  positive("scene.fps", scene.fps, "1/s");
  positive("scene.duration", scene.duration_s, "s");
  if (scene.fps > limits::kFps)
    fail("scene.fps", fmt::format("{}: at most {}", scene.fps, limits::kFps));
  const auto non_negative = [&](const char* key, double value, const char* unit) {
    if (!(value >= 0.0 && std::isfinite(value)))
      fail(key, fmt::format("{} {}: expected 0 or a positive finite number", value, unit));
  };
  non_negative("flag.shear_modulus", flag.shear_modulus_n_m, "N/m");
  non_negative("flag.damping", flag.damping_per_s, "1/s");
  if (!flag.origin_m.allFinite()) fail("flag.origin", "expected finite coordinates (m)");
  if (scene.solver.substeps < 1)
    fail("solver.substeps", fmt::format("{}: expected 1 or more", scene.solver.substeps));
  if (scene.output.every < 1)
    fail("output.every", fmt::format("{}: expected 1 or more", scene.output.every));
  if (scene.simulated_frames() > limits::kFrames)
    fail("scene.duration", fmt::format("{} frames: more than the {} allowed",
                                       scene.simulated_frames(), limits::kFrames));
  // The yarn's keys, where stated: [bending]'s, then [wrinkles]'.
  const auto yarn = [&](const char* radius_key, const std::optional<double>& radius_m,
                        const char* modulus_key, const std::optional<double>& modulus_pa) {
    if (radius_m) positive(radius_key, *radius_m, "m");
    if (modulus_pa) positive(modulus_key, *modulus_pa, "Pa");
  };
  if (scene.bending) {
    non_negative("bending.stiffness", scene.bending->rigidity_j, "N m");
    yarn("bending.fiber_radius", scene.bending->fiber_radius_m, "bending.fiber_modulus",
         scene.bending->fiber_modulus_pa);
  }
  if (scene.wrinkles)
    yarn("wrinkles.fiber_radius", scene.wrinkles->fiber_radius_m, "wrinkles.fiber_modulus",
         scene.wrinkles->fiber_modulus_pa);
  (void)material_of(scene);  // one material: [bending] and [wrinkles] agree on the yarn
  for (const Fold& fold : flag.folds) {
    if (!(fold.at > 0.0 && fold.at < 1.0))
      fail("flag.folds",
           fmt::format("at = {}: a fold line lies inside the flag, 0 < at < 1", fold.at));
    if (!(fold.angle_rad != 0.0 && std::abs(fold.angle_rad) <= std::numbers::pi))
      fail("flag.folds", fmt::format("angle = {} rad: expected -pi to pi, not 0", fold.angle_rad));
    if (!(fold.from >= 0.0 && fold.from < fold.to && fold.to <= 1.0))
      fail("flag.folds",
           fmt::format("from = {}, to = {}: expected 0 <= from < to <= 1", fold.from, fold.to));
  }
  if (scene.creases) {
    const Creases& creases = *scene.creases;
    if (!(creases.yield_angle_rad >= 0.0 && creases.yield_angle_rad <= std::numbers::pi))
      fail("creases.yield_angle", fmt::format("{} rad: expected 0 to pi", creases.yield_angle_rad));
    positive("creases.set_time", creases.set_time_s, "s");
    positive("creases.relax_time", creases.relax_time_s, "s");
    positive("creases.width", creases.width_m, "m");
  }
  if (const auto problem = detail::crease_problem(scene)) fail(problem->first, problem->second);
}

}  // namespace flagsim
