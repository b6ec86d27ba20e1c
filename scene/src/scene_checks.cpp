#include "scene_checks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <utility>

#include "flagsim/core/errors.hpp"
#include "flagsim/core/limits.hpp"

namespace flagsim::detail {
namespace {

// 2^24 nodes: ~400 MB per double state vector, far past any lattice we mean to run.
constexpr double kMaxNodes = double(limits::kLatticeNodes);

[[noreturn]] void fail_at(const TableReader& root, std::string_view dotted,
                          const std::string& message) {
  const toml::node* node = root.table().at_path(dotted).node();
  const std::string place =
      node ? where_key(std::string(dotted), node->source()) : root.where_of("");
  throw UserError(fmt::format("{}: {}: {}", place, dotted, message));
}

// Coarse sizes n such that (fine - 1) is a multiple of (n - 1).
std::string dividing_sizes(int fine) {
  std::string list;
  for (int n = 2; n <= fine; ++n)
    if ((fine - 1) % (n - 1) == 0) list += fmt::format("{}{}", list.empty() ? "" : ", ", n);
  return list;
}

}  // namespace

std::optional<std::pair<const char*, std::string>> crease_problem(const Scene& scene) {
  if (!scene.flag.folds.empty() && !scene.creases)
    return std::pair{"flag.folds",
                     std::string("fold lines are creases: they need [creases] (how a crease sets "
                                 "and relaxes; an empty table takes the defaults)")};
  if (!scene.creases) return std::nullopt;
  if (!scene.bending)
    return std::pair{"creases",
                     std::string("a crease is a rest angle of the cloth's bending: add [bending] "
                                 "(its stiffness is the crease's)")};
  if (scene.mode == Mode::kHybrid && infill_solver_of(scene) == InfillSolverKind::kPaper)
    return std::pair{"creases",
                     std::string("the hybrid draws its crease lines with the smooth infill; "
                                 "infill.solver = \"paper\" has none yet")};
  return std::nullopt;
}

void check_consistency(Scene& scene, const TableReader& root, const TableReader& scene_in,
                       const TableReader& flag_in, bool mode_from_command_line) {
  const FlagSpec& flag = scene.flag;
  if (double(flag.fine_rows) * flag.fine_cols > kMaxNodes)
    flag_in.fail("fine", fmt::format("{} x {} = {:.0f} nodes is more than the {:.0f} allowed",
                                     flag.fine_rows, flag.fine_cols,
                                     double(flag.fine_rows) * flag.fine_cols, kMaxNodes));
  if (flag.coarse) {
    const auto [rows, cols] = *flag.coarse;
    const int fine[2] = {flag.fine_rows, flag.fine_cols};
    const int coarse[2] = {rows, cols};
    const char* axis[2] = {"rows", "columns"};
    for (int a = 0; a < 2; ++a) {
      if (coarse[a] > fine[a] || (fine[a] - 1) % (coarse[a] - 1) != 0)
        flag_in.fail("coarse",
                     fmt::format("[{}, {}] does not divide flag.fine = [{}, {}]: {} - 1 = {} is "
                                 "not a multiple of {} - 1; coarse {} that work: {}",
                                 rows, cols, fine[0], fine[1], fine[a], fine[a] - 1, coarse[a],
                                 axis[a], dividing_sizes(fine[a])));
    }
  }
  if (scene.mode == Mode::kHybrid && !flag.coarse)
    scene_in.fail("mode",
                  "hybrid mode needs flag.coarse = [Jc, Kc], the lattice the physics runs on");
  if (scene.pole && flag.pin == PinSet::kNone)
    fail_at(root, "pole", "a moving pole needs pinned nodes; set flag.pin (e.g. \"left\")");
  // The solids must leave the cloth's start outside them (the pole does: its
  // surface touches the pole edge, x = origin.x, and the flag lies at x >= it).
  if (scene.ground) {
    const double lowest = flag.origin_m.y() - flag.height_m;
    if (lowest < scene.ground->height_m)
      fail_at(root, "ground.height",
              fmt::format("the flag's bottom edge starts at y = {:g} m, below the ground at {:g} "
                          "m; lower the ground or raise flag.origin",
                          lowest, scene.ground->height_m));
  }
  // Tables the mode does not use: in a scene file, a mistake (each would be
  // silently ignored); with the mode chosen on the command line (--mode,
  // --set scene.mode, compare's reference), ignored and named in one note.
  std::vector<std::string> unused;
  const auto unused_setting = [&](const char* dotted, std::string named,
                                  const std::string& message) {
    if (!mode_from_command_line) fail_at(root, dotted, message);
    unused.push_back(std::move(named));
  };
  const auto unused_table = [&](const char* table, const std::string& message) {
    unused_setting(table, fmt::format("[{}]", table), message);
  };
  if (scene.mode == Mode::kInfill) {
    if (scene.keyframes.empty())
      scene_in.fail("mode", "infill mode needs [[keyframe]] tables with the corner positions");
    // No physics in infill mode: a physics table would be silently ignored.
    const std::pair<bool, const char*> physics[] = {
        {scene.wind.has_value(), "wind"},
        {scene.pole.has_value() || scene.solid_pole.has_value(), "pole"},
        // [bending] states a crease's rigidity ([creases]: the dense cloth's own creases).
        {scene.bending.has_value() && !scene.creases.has_value(), "bending"},
        {root.table().contains("gravity"), "gravity"},
        {scene.contact.has_value(), "contact"},  // self-contact is the physics'
        {root.table().contains("solver"), "solver"}};
    for (const auto& [present, table] : physics)
      if (present)
        unused_table(table,
                     "infill mode has no physics (the corners follow the keyframes); "
                     "remove the table or choose another scene.mode");
    if (mode_from_command_line) {
      scene.wind.reset();
      scene.pole.reset();
      scene.solid_pole.reset();
      if (!scene.creases) scene.bending.reset();
      scene.flag.folds.clear();
      scene.gravity.reset();
      scene.contact.reset();
      scene.solver = Solver{};
    }
    if (flag.coarse && (*flag.coarse)[0] * (*flag.coarse)[1] != 4)
      fail_at(root, "flag.coarse",
              "infill mode drives the 4 corners only: use [2, 2] or leave it out");
  } else if (!scene.keyframes.empty()) {
    unused_table(
        "keyframe",
        "[[keyframe]] drives the corners in infill mode only; set scene.mode = \"infill\"");
    scene.keyframes.clear();
  }
  if (is_full_lattice(scene.mode) && scene.infill) {
    unused_table("infill",
                 "[infill] settings need a mode with the infill (\"hybrid\" or \"infill\")");
    scene.infill.reset();
  }
  if (is_full_lattice(scene.mode) && scene.wrinkles) {
    unused_table("wrinkles",
                 "wrinkles are made by the infill (paper 3.5); they need scene.mode = \"hybrid\" "
                 "or \"infill\"");
    scene.wrinkles.reset();
  }
  // Only the hybrid has a coarse trajectory that reproduces its dense frames.
  if (scene.mode != Mode::kHybrid && !scene.output.dense) {
    unused_setting("output.dense", "output.dense = false",
                   fmt::format("output.dense = false keeps a hybrid run's coarse trajectory in "
                               "place of its dense frames; {} mode has none (its frames are its "
                               "physics or its keyframes): leave the key out",
                               to_string(scene.mode)));
    scene.output.dense = true;
  }
  // The implicit backend alone solves a linear system and halves its steps;
  // elsewhere these keys would be silently ignored.
  if (const std::optional<Backend> backend = backend_of(scene);
      backend && *backend != Backend::kImplicit) {
    const std::pair<const char*, const char*> implicit_only[] = {
        {"solver.linear", "has no linear solve"},
        {"solver.max_step_strain_change", "does not halve its steps"}};
    for (const auto& [key, lacks] : implicit_only)
      if (root.table().at_path(key))
        unused_setting(key, key,
                       fmt::format("the {} backend {}; {} applies to solver.backend = "
                                   "\"implicit\" or scene.mode = \"implicit\"",
                                   to_string(*backend), lacks, key));
  }
  // Only the spring-damper steps the wind with a hold (spring_damper.hpp).
  if (const std::optional<Backend> backend = backend_of(scene);
      backend && *backend != Backend::kSpringDamper && root.table().at_path("solver.wind_hold"))
    unused_setting("solver.wind_hold", "solver.wind_hold",
                   fmt::format("the {} backend evaluates the wind at every step; "
                               "solver.wind_hold applies to the spring-damper "
                               "(scene.mode = \"mass-spring\", or the hybrid's default backend)",
                               to_string(*backend)));
  // The direct solve probes the step's matrix over 2-link neighbourhoods
  // (implicit_euler.cpp); the wind on panels coarser than the cloth couples
  // nodes a panel or more apart, so its matrix would be wrong (issue 35).
  if (const std::optional<Backend> backend = backend_of(scene);
      backend && *backend == Backend::kImplicit && scene.solver.linear == LinearSolver::kCholesky &&
      scene.wind && scene.wind->model == AirModel::kPanels) {
    const bool hybrid = scene.mode == Mode::kHybrid && scene.flag.coarse;
    const int rows = hybrid ? (*scene.flag.coarse)[0] : scene.flag.fine_rows;
    const int cols = hybrid ? (*scene.flag.coarse)[1] : scene.flag.fine_cols;
    const double panel = scene.wind->panel_m;
    // As AirPanels does: the cloth is its own panel lattice unless it is finer both ways.
    if (air_panel_nodes(scene.flag.height_m, panel) < rows &&
        air_panel_nodes(scene.flag.width_m, panel) < cols)
      fail_at(
          root, "solver.linear",
          fmt::format("\"cholesky\" assembles the step's matrix from each node's two-link "
                      "neighbourhood, and the wind seen on panels of wind.panel = {:g} m "
                      "couples the {} x {} cloth's nodes farther apart than that; use "
                      "\"cg\", or a wind.panel no larger than the cloth's cells ({:.3g} m)",
                      panel, rows, cols,
                      std::min(scene.flag.width_m / (cols - 1), scene.flag.height_m / (rows - 1))));
  }
  // The vortex lattice's added mass is solved with the spring-damper
  // integrator's masses (vortex_wake.hpp); the other steppers would take it
  // explicitly, which is unstable.
  if (scene.wind && scene.wind->model == AirModel::kVortex) {
    if (const std::optional<Backend> backend = backend_of(scene);
        !backend || *backend != Backend::kSpringDamper)
      fail_at(root, "wind.model",
              fmt::format("\"vortex\" needs the spring-damper integrator (scene.mode = "
                          "\"hybrid\" or \"mass-spring\", solver.backend = \"spring-damper\"); "
                          "{} mode{} solves without the air's added mass",
                          to_string(scene.mode),
                          backend && scene.mode == Mode::kHybrid
                              ? fmt::format(" with the {} backend", to_string(*backend))
                              : std::string()));
    if (!(scene.wind->velocity_m_s.x() > 0.0))
      fail_at(root, "wind.velocity",
              "wind.model = \"vortex\" needs a wind along the flag, from the pole to the fly "
              "end (a positive x component)");
  }
  if (const auto problem = crease_problem(scene)) fail_at(root, problem->first, problem->second);
  if (!unused.empty())
    scene.notes.push_back(fmt::format("note: {} mode does not use {}: ignored",
                                      to_string(scene.mode), fmt::join(unused, ", ")));
  // Issue 33, item 6: a minimal scene's defaults are the schema's, not the
  // default scene's; said where the user meets them. (Gravity and wind act
  // only when their tables are there, by the contract.)
  if (!scene_in.has("mode") && !mode_from_command_line)
    scene.notes.push_back(fmt::format(
        "note: no scene.mode: {} mode on the full {} x {} lattice (the default scene is a "
        "hybrid; `flag-sim scene FILE` shows every default, `flag-sim help keys` lists them)",
        to_string(scene.mode), flag.fine_rows, flag.fine_cols));
  if (scene.wind && scene.wind->velocity_m_s.z() == 0.0 && !scene.wind->turbulence && !scene.pole &&
      flag.initial_perturbation_m == 0.0 && scene.mode != Mode::kInfill &&
      (!scene.gravity || scene.gravity->acceleration_m_s2.z() == 0.0))
    scene.notes.push_back(
        "note: flag.initial_perturbation = 0 in a steady wind along the flag's plane: the flag "
        "stays flat, nothing breaks its symmetry (the default scene starts from 0.005 m)");
}

}  // namespace flagsim::detail
