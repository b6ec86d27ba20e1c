// `flag-sim compare`: the hybrid against a full-lattice reference on the same
// dense lattice, same seed and start; and the tracking run that isolates the
// infill's own error (report.hpp, analysis/metrics.hpp).
#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "commands.hpp"
#include "flagsim/core/errors.hpp"
#include "flagsim/core/file_roles.hpp"
#include "interrupt.hpp"
#include "progress.hpp"
#include "report.hpp"
#include "run_record.hpp"

namespace flagsim::app {
namespace fs = std::filesystem;

void check_report_path(const std::string& path) {
  if (path.empty()) return;
  const fs::path parent = fs::path(path).has_parent_path() ? fs::path(path).parent_path() : ".";
  std::error_code ec;
  if (!fs::is_directory(parent, ec) || access(parent.c_str(), W_OK) != 0 ||
      fs::is_directory(path, ec))
    throw UserError(
        fmt::format("-o {}: cannot write a report there (does {} exist?)", path, parent.string()));
}

void write_report(const std::string& path, const std::vector<ReportRow>& rows) {
  if (path.empty()) return;
  std::ofstream out(path);
  out << csv_header() << "\n";
  for (const ReportRow& row : rows) out << csv_line(row) << "\n";
  if (!out) throw IoError(fmt::format("{}: writing the report failed", path));
}

std::vector<std::string> with_mode(std::vector<std::string> sets, const std::string& mode) {
  sets.push_back(fmt::format("scene.mode=\"{}\"", mode));
  return sets;
}

int compare_command(const CompareOptions& options) {
  if (options.reference != "mass-spring" && options.reference != "bullet")
    throw UserError(
        fmt::format("--reference {}: expected \"mass-spring\" or \"bullet\"", options.reference));
  if (!(options.horizon_s > 0.0))
    throw UserError(fmt::format("--horizon {}: expected a duration > 0 s", options.horizon_s));
  std::vector<std::string> sets = options.sets;
  if (options.frames) {
    if (*options.frames < 2)
      throw UserError(
          fmt::format("--frames {}: a comparison needs at least 2 frames", *options.frames));
    sets.push_back(fmt::format("scene.frames={}", *options.frames));
  }
  const Scene hybrid_scene = load_scene(options.scene_path, with_mode(sets, "hybrid"));
  const Scene reference_scene = load_scene(options.scene_path, with_mode(sets, options.reference));
  check_report_path(options.output);
  FileRoles files;
  files.input(options.scene_path, "the scene");
  files.output(options.output, "the report");
  files.check();

  const MetricWindow window{options.horizon_s};
  const InterruptGuard interrupt;  // a signal stops the run in progress: exit 130, no report
  // A progress line per run on a terminal: the full-lattice reference can take minutes.
  const bool show = Progress::wanted(false);
  Progress reference_progress(show, reference_scene.simulated_frames(),
                              fmt::format("reference ({})", options.reference));
  const RunRecord reference = record_run(reference_scene, &reference_progress);
  Progress hybrid_progress(show, hybrid_scene.simulated_frames(), "hybrid");
  const RunRecord hybrid = record_run(hybrid_scene, &hybrid_progress);
  Progress tracking_progress(show, int(hybrid.frames.size()), "tracking");
  const RunRecord tracking = record_tracking(hybrid_scene, hybrid, &tracking_progress);
  Scene tracking_scene = hybrid_scene;
  tracking_scene.mode = Mode::kMassSpring;

  std::vector<ReportRow> rows;
  rows.push_back(describe(reference_scene, reference, reference, nullptr, window));
  rows.back().label = fmt::format("reference ({})", options.reference);
  rows.push_back(describe(hybrid_scene, hybrid, reference, &tracking, window));
  rows.back().label = "hybrid";
  rows.push_back(describe(tracking_scene, tracking, reference, nullptr, window));
  rows.back().label = "tracking (coarse nodes driven)";
  for (std::size_t i = 0; i < rows.size(); ++i) rows[i].point = int(i);
  write_report(options.output, rows);
  fmt::print("{}", text_table(rows));
  fmt::print(
      "short horizon: the first {:.3g} s; flap, mean shape and wrinkles: the second half "
      "of the run; errors against the {} reference{}\n",
      options.horizon_s, options.reference,
      options.output.empty() ? "" : fmt::format(" -> {}", options.output));
  return int(ExitCode::kSuccess);
}

}  // namespace flagsim::app
