// `flag-sim compare`: the hybrid against a full-lattice reference on the same
// dense lattice, same seed and start; and the tracking run that isolates the
// infill's own error (report.hpp, analysis/metrics.hpp).
#include "compare_command.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

#include "flagsim/analysis/metrics.hpp"
#include "flagsim/core/errors.hpp"
#include "flagsim/os/file_roles.hpp"
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

// The frames of `run` at every other row and column: the nodes a lattice of
// (J + 1) / 2 x (K + 1) / 2 over the same flag has.
analysis::Frames every_other_node(const RunRecord& run) {
  const int rows = run.lattice.rows, cols = run.lattice.cols;
  analysis::Frames out;
  out.reserve(run.frames.size());
  for (const auto& frame : run.frames) {
    std::vector<Vec3> half;
    half.reserve(std::size_t((rows + 1) / 2) * std::size_t((cols + 1) / 2));
    for (int j = 0; j < rows; j += 2)
      for (int k = 0; k < cols; k += 2) half.push_back(frame[run.lattice.index(j, k)]);
    out.push_back(std::move(half));
  }
  return out;
}

// --seeds N: the hybrid and the reference over N seeds, and the reference
// against itself on the lattice of every other node. Converged when the two
// lattices' mean frequencies are within twice their standard error and their
// mean shapes (same seed) no farther apart than 1.5 x the seed-to-seed floor
// (two seeds of the finer lattice): then the lattice is not what the answer
// depends on. Returns the lines compare prints.
// The first seed's runs are the comparison's own (`base`, the hybrid's scene;
// `hybrid0`, `reference0`).
std::string seed_study(const CompareOptions& options, const std::vector<std::string>& sets,
                       Mode mode, int seeds, bool show, const Scene& base, const RunRecord& hybrid0,
                       const RunRecord& reference0) {
  const std::uint64_t first = base.seed;
  const auto with_seed = [&](std::vector<std::string> more, std::uint64_t seed) {
    more.push_back(fmt::format("scene.seed={}", seed));
    return more;
  };
  const int rows = base.flag.fine_rows, cols = base.flag.fine_cols;
  const bool halves = (rows - 1) % 2 == 0 && (cols - 1) % 2 == 0 && rows >= 5 && cols >= 5;
  std::vector<std::string> half_sets = with_mode(sets, mode);
  half_sets.push_back(fmt::format("flag.fine=[{},{}]", (rows + 1) / 2, (cols + 1) / 2));
  half_sets.push_back(fmt::format("flag.coarse=[{},{}]", (rows + 1) / 2, (cols + 1) / 2));
  // Per seed; a seed whose reference (or its coarser twin) did not complete is
  // left out of every figure, a run that does not flap out of the frequencies.
  std::vector<double> hybrid_f, reference_f, f_difference, half_f, hybrid_shape, lattice_shape,
      floor;
  int incomplete = 0, not_flapping = 0;
  for (int s = 0; s < seeds; ++s) {
    const std::uint64_t seed = first + std::uint64_t(s);
    const Scene hybrid_scene =
        load_scene(options.scene_path, with_seed(with_mode(sets, Mode::kHybrid), seed));
    const Scene reference_scene =
        load_scene(options.scene_path, with_seed(with_mode(sets, mode), seed));
    RunRecord hybrid_run, reference_run;
    if (s > 0) {
      Progress hybrid_progress(show, hybrid_scene.simulated_frames(),
                               fmt::format("seed {}: hybrid", seed));
      hybrid_run = record_run(hybrid_scene, &hybrid_progress);
      Progress reference_progress(show, reference_scene.simulated_frames(),
                                  fmt::format("seed {}: reference", seed));
      reference_run = record_run(reference_scene, &reference_progress);
    }
    const RunRecord& hybrid = s == 0 ? hybrid0 : hybrid_run;
    const RunRecord& reference = s == 0 ? reference0 : reference_run;
    std::optional<RunRecord> coarser;
    std::optional<Scene> half_scene;
    if (halves) {
      half_scene = load_scene(options.scene_path, with_seed(half_sets, seed));
      Progress half_progress(show, half_scene->simulated_frames(),
                             fmt::format("seed {}: reference, every other node", seed));
      coarser = record_run(*half_scene, &half_progress);
    }
    const auto complete = [](const RunRecord& run) {
      return run.status.state == RunState::kComplete;
    };
    if (!complete(hybrid) || !complete(reference) || (coarser && !complete(*coarser))) {
      ++incomplete;
      continue;
    }
    const int half = int(std::min(hybrid.frames.size(), reference.frames.size()) / 2);
    const double fh = flap_hz_of(hybrid_scene, hybrid), fr = flap_hz_of(reference_scene, reference);
    const double fc = coarser ? flap_hz_of(*half_scene, *coarser) : 0.0;
    if (fh > 0.0 && fr > 0.0 && (!coarser || fc > 0.0)) {
      hybrid_f.push_back(fh);
      reference_f.push_back(fr);
      f_difference.push_back(fh - fr);
      if (coarser) half_f.push_back(fc);
    } else {
      ++not_flapping;
    }
    hybrid_shape.push_back(analysis::mean_shape_rms(hybrid.frames, reference.frames, half));
    if (s > 0 && complete(reference0))
      floor.push_back(analysis::mean_shape_rms(reference.frames, reference0.frames, half));
    if (coarser)
      lattice_shape.push_back(
          analysis::mean_shape_rms(every_other_node(reference), coarser->frames, half));
  }
  const Spread fh = spread_of(hybrid_f), fr = spread_of(reference_f), fd = spread_of(f_difference),
               sh = spread_of(hybrid_shape), fl = spread_of(floor);
  const double flapping = double(hybrid_f.size());
  // Paired: the hybrid and the reference of one seed start from the same perturbation.
  const double f_error = fr.mean > 0.0 ? fd.mean / fr.mean : 0.0;
  const double f_error_se =
      fr.mean > 0.0 && flapping > 0 ? fd.sd / std::sqrt(flapping) / fr.mean : 0.0;
  std::string left_out;
  if (incomplete > 0)
    left_out += fmt::format("; {} seed(s) left out: a run did not complete", incomplete);
  if (not_flapping > 0)
    left_out +=
        fmt::format("; {} seed(s) out of the frequencies: a run did not flap", not_flapping);
  std::string text = fmt::format(
      "seeds {} .. {} ({}), mean +- seed-to-seed sd: flap f hybrid {:.2f} +- {:.2f} Hz, "
      "reference {:.2f} +- {:.2f} Hz, hybrid error {:+.1f}% +- {:.1f}% (standard error, "
      "paired by seed); mean shape hybrid to reference {:.1f} +- {:.1f} mm, reference seed to "
      "seed {:.1f} mm (the floor){}\n",
      first, first + std::uint64_t(seeds) - 1, seeds, fh.mean, fh.sd, fr.mean, fr.sd, 100 * f_error,
      100 * f_error_se, 1e3 * sh.mean, 1e3 * sh.sd, 1e3 * fl.mean, left_out);
  if (!halves)
    return text + fmt::format(
                      "reference convergence: not judged ({} x {} has no lattice of every other "
                      "node: give an odd number of nodes along both sides)\n",
                      rows, cols);
  const Spread fc = spread_of(half_f), lc = spread_of(lattice_shape);
  const double f_apart = std::abs(fr.mean - fc.mean);
  const double f_allowed = 2.0 * std::sqrt(fr.sd * fr.sd + fc.sd * fc.sd) / std::sqrt(flapping);
  const bool f_converged = f_apart <= f_allowed;
  const bool shape_converged = lc.mean <= 1.5 * fl.mean;
  // Judged only with a spread to judge by: two flapping seeds at least, and
  // seeds that change the answer (else "within the seed error" means nothing).
  const std::string verdict =
      hybrid_f.size() < 2 || floor.empty()
          ? "not judged (fewer than two complete, flapping seeds: --seeds 3 or more)"
      : !(f_allowed > 0.0) || !(fl.mean > 0.0)
          ? "not judged (the seeds do not change the flap: no spread to judge by)"
      : f_converged && shape_converged
          ? "converged (the lattice does not change the answer beyond the seeds)"
          : "NOT converged (the errors above are against a lattice-dependent answer)";
  return text + fmt::format(
                    "reference convergence ({} {} x {} against {} x {}, same seeds): f {:.2f} "
                    "vs {:.2f} Hz, {:.2f} apart, {} twice the standard error ({:.2f}); mean "
                    "shapes {:.1f} mm apart, {} 1.5 x the floor: {}\n",
                    to_string(mode), rows, cols, (rows + 1) / 2, (cols + 1) / 2, fr.mean, fc.mean,
                    f_apart, f_converged ? "within" : "NOT within", f_allowed, 1e3 * lc.mean,
                    shape_converged ? "within" : "NOT within", verdict);
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
  const int seeds = int(options.seeds.value_or(1));
  if (options.seeds && (*options.seeds < 1 || *options.seeds > 64))
    throw UserError(fmt::format("--seeds {}: expected 1 to 64 seeds", *options.seeds));
  const Scene hybrid_scene = load_scene(options.scene_path, with_mode(sets, Mode::kHybrid));
  std::vector<Scene> reference_scenes;
  reference_scenes.reserve(modes.size());
  for (const Mode mode : modes)
    reference_scenes.push_back(load_scene(options.scene_path, with_mode(sets, mode)));
  CreatedDirectories directories;  // -o in a new directory: made, and removed if nothing is written
  check_report_path(options.output, &directories);
  FileRoles files;
  files.input(options.scene_path, "the scene");
  files.output(options.output, "the report");
  files.check();

  const MetricWindow window{options.horizon_s};
  const InterruptGuard interrupt;  // a signal stops the run in progress: exit 130, no report
  // A progress line per run on a terminal: the full-lattice references can take minutes.
  const bool show = Progress::wanted(options.quiet);
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
  const std::string seed_lines = seeds > 1 ? seed_study(options, sets, modes.front(), seeds, show,
                                                        hybrid_scene, hybrid, primary)
                                           : std::string();
  write_report(options.output, rows);
  fmt::print("{}", text_table(rows));
  fmt::print("{}", best_line);
  fmt::print(
      "short horizon: the first {:.3g} s; flap, mean shape and wrinkles: the second half "
      "of the run; errors against the {} reference{}\n",
      options.horizon_s, to_string(modes.front()),
      options.output.empty() ? "" : fmt::format(" -> {}", options.output));
  fmt::print("{}", seed_lines);
  return int(ExitCode::kSuccess);
}

}  // namespace flagsim::app
