// `flag-sim compare`: the hybrid against a full-lattice reference on the same
// dense lattice, same seed and start; and the tracking run that isolates the
// infill's own error (report.hpp, analysis/metrics.hpp).
#include "compare_command.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <optional>

#include "flagsim/core/errors.hpp"
#include "flagsim/core/file_roles.hpp"
#include "interrupt.hpp"
#include "progress.hpp"
#include "report.hpp"
#include "run_record.hpp"
#include "scene_commands.hpp"

namespace flagsim::app {

std::vector<std::string> with_mode(std::vector<std::string> sets, Mode mode) {
  sets.push_back(fmt::format("scene.mode=\"{}\"", to_string(mode)));
  return sets;
}

// The full-lattice references `--reference` names, the first the one every
// error is measured against.
std::vector<Mode> references_of(const std::string& reference) {
  std::vector<Mode> every_reference;
  for (const NamedValue<Mode>& entry : kModeNames)
    if (is_full_lattice(entry.value)) every_reference.push_back(entry.value);
  if (reference == "all") return every_reference;
  const std::optional<Mode> mode = value_in(kModeNames, reference);
  if (!mode || !is_full_lattice(*mode)) {
    std::string choices;
    for (const Mode m : every_reference) choices += fmt::format("{}, ", to_string(m));
    choices.resize(choices.size() - 2);  // "mass-spring, bullet, implicit, xpbd"
    throw UserError(fmt::format("--reference {}: expected {} or all", reference, choices));
  }
  return {*mode};
}

// Implicit Euler and XPBD choose no step count of their own (accuracy, not
// stability, sets it): compare runs each at the scene's solver.substeps, then
// doubles them until its p99 strain is no worse than the hybrid's, at most
// kSubstepDoublings times. The mass-spring and Bullet references run at the
// count their stability limit sets.
constexpr int kSubstepDoublings = 8;

bool steps_by_accuracy(Mode mode) {
  return mode == Mode::kImplicit || mode == Mode::kXpbd;
}

struct ReferenceRun {
  Scene scene;
  RunRecord record;
  std::string label;
};

// The fastest complete reference run whose p99 strain is at most `p99`, or null.
const ReportRow* best_reference(const std::vector<ReportRow>& rows, double p99) {
  const ReportRow* best = nullptr;
  for (const ReportRow& row : rows)
    if (row.status == RunState::kComplete && row.p99_strain <= p99 &&
        (!best || row.ms_per_frame < best->ms_per_frame))
      best = &row;
  return best;
}

int compare_command(const CompareOptions& options) {
  const std::vector<Mode> modes = references_of(options.reference);
  if (!(options.horizon_s > 0.0))
    throw UserError(fmt::format("--horizon {}: expected a duration > 0 s", options.horizon_s));
  std::vector<std::string> sets = options.sets;
  if (options.frames) {
    if (*options.frames < 2)
      throw UserError(
          fmt::format("--frames {}: a comparison needs at least 2 frames", *options.frames));
    sets.push_back(fmt::format("scene.frames={}", *options.frames));
  }
  const Scene hybrid_scene = load_scene(options.scene_path, with_mode(sets, Mode::kHybrid));
  std::vector<Scene> reference_scenes;
  reference_scenes.reserve(modes.size());
  for (const Mode mode : modes)
    reference_scenes.push_back(load_scene(options.scene_path, with_mode(sets, mode)));
  check_report_path(options.output);
  FileRoles files;
  files.input(options.scene_path, "the scene");
  files.output(options.output, "the report");
  files.check();

  const MetricWindow window{options.horizon_s};
  const InterruptGuard interrupt;  // a signal stops the run in progress: exit 130, no report
  // A progress line per run on a terminal: the full-lattice references can take minutes.
  const bool show = Progress::wanted(false);
  Progress hybrid_progress(show, hybrid_scene.simulated_frames(), "hybrid");
  const RunRecord hybrid = record_run(hybrid_scene, &hybrid_progress);
  Progress tracking_progress(show, int(hybrid.frames.size()), "tracking");
  const RunRecord tracking = record_tracking(hybrid_scene, hybrid, &tracking_progress);
  const Scene tracking_scene = in_mode(hybrid_scene, Mode::kMassSpring);
  const double hybrid_p99 = describe(hybrid_scene, hybrid, hybrid, nullptr, window).p99_strain;

  std::vector<ReferenceRun> references;
  for (std::size_t m = 0; m < modes.size(); ++m) {
    Scene scene = reference_scenes[m];
    for (int doubling = 0;; ++doubling) {
      Progress progress(show, scene.simulated_frames(),
                        fmt::format("reference ({})", to_string(modes[m])));
      RunRecord record = record_run(scene, &progress);
      const bool good = record.status.state == RunState::kComplete &&
                        describe(scene, record, record, nullptr, window).p99_strain <= hybrid_p99;
      const int ran = record.substeps_per_frame;
      const std::string label =
          steps_by_accuracy(modes[m])
              ? fmt::format("reference ({} {} substeps/frame)", to_string(modes[m]), ran)
              : fmt::format("reference ({})", to_string(modes[m]));
      references.push_back({scene, std::move(record), label});
      if (!steps_by_accuracy(modes[m]) || good || doubling == kSubstepDoublings) break;
      scene = with_substeps(scene, 2 * ran);  // from what it ran at (XPBD's minimum may be higher)
    }
  }

  const RunRecord& primary = references.front().record;
  std::vector<ReportRow> rows;
  for (const ReferenceRun& run : references) {
    rows.push_back(describe(run.scene, run.record, primary, nullptr, window));
    rows.back().label = run.label;
  }
  const std::vector<ReportRow> reference_rows = rows;
  rows.push_back(describe(hybrid_scene, hybrid, primary, &tracking, window));
  rows.back().label = "hybrid";
  ReportRow& hybrid_row = rows.back();
  const ReportRow* best = best_reference(reference_rows, hybrid_p99);
  if (best) {
    hybrid_row.best_reference = best->label;
    if (hybrid_row.ms_per_frame > 0.0)
      hybrid_row.speedup_vs_best_reference = best->ms_per_frame / hybrid_row.ms_per_frame;
  }
  const std::string best_line =
      hybrid_row.speedup_vs_best_reference
          ? fmt::format(
                "hybrid: {:.3g}x faster than the fastest reference with p99 strain at "
                "most its {:.3g}%: {} ({:.1f} ms/frame)\n",
                *hybrid_row.speedup_vs_best_reference, 100 * hybrid_p99, hybrid_row.best_reference,
                best->ms_per_frame)
          : fmt::format("hybrid: no reference run reached its p99 strain of {:.3g}%{}\n",
                        100 * hybrid_p99,
                        modes.size() == 1 && !steps_by_accuracy(modes[0])
                            ? " (try --reference all: implicit and xpbd are run at more "
                              "substeps until they do)"
                            : "");
  rows.push_back(describe(tracking_scene, tracking, primary, nullptr, window));
  rows.back().label = "tracking (coarse nodes driven)";
  for (std::size_t i = 0; i < rows.size(); ++i) rows[i].point = int(i);
  write_report(options.output, rows);
  fmt::print("{}", text_table(rows));
  fmt::print("{}", best_line);
  fmt::print(
      "short horizon: the first {:.3g} s; flap, mean shape and wrinkles: the second half "
      "of the run; errors against the {} reference{}\n",
      options.horizon_s, to_string(modes.front()),
      options.output.empty() ? "" : fmt::format(" -> {}", options.output));
  return int(ExitCode::kSuccess);
}

}  // namespace flagsim::app
