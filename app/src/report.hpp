#pragma once
// The rows `compare` and `sweep` write: one run each, its cost and its error
// against the reference run (contract: "Compare and sweep reports").
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "flagsim/core/run_status.hpp"
#include "flagsim/os/file_roles.hpp"
#include "flagsim/scene/scene.hpp"
#include "run_record.hpp"

namespace flagsim::app {

struct ReportRow {
  int point = 0;
  std::string label;  ///< "hybrid", "reference", "tracking", "coarse=9x13 substeps=1 relax=8000"
  std::string mode, backend, fine, coarse;
  int substeps = 0, relax_iterations = 0, frames = 0;
  double ms_per_frame = 0, physics_ms = 0, infill_ms = 0, max_strain = 0, p99_strain = 0;
  // Against the reference; empty where it does not apply.
  std::optional<double> short_horizon_rms_m, tracking_rms_m, flap_hz, flap_rel_error,
      mean_shape_rms_m, wrinkle_wavelength_m;
  RunState status = RunState::kComplete;
  std::string infill_solver;  ///< "smooth" or "paper"; empty without an infill
  /// compare, on the hybrid's row: the fastest full-lattice reference run
  /// whose p99 strain is no worse than the hybrid's (its label), and its
  /// ms/frame over the hybrid's; empty where no reference run qualified.
  std::string best_reference;
  std::optional<double> speedup_vs_best_reference;
  std::uint64_t seed = 0;  ///< the run's scene.seed (sweep --seeds: one row per point and seed)
  /// [pole] radius, m, when the pole is a solid (sweep --pole-radius); empty otherwise.
  std::optional<double> pole_radius_m;
  /// [contact] thickness, m, when the cloth keeps its layers apart (sweep
  /// --contact-thickness); empty otherwise.
  std::optional<double> contact_thickness_m;
};

/// Where the metrics look: the short horizon (first `horizon_s`), and the
/// second half of the run for the statistics (flap, mean shape, wrinkles).
struct MetricWindow {
  double horizon_s = 0.5;
};

/// The row of `run` (of `scene`), errors against `reference` (may be the run
/// itself), the infill's own error against `tracking` when given.
ReportRow describe(const Scene& scene, const RunRecord& run, const RunRecord& reference,
                   const RunRecord* tracking, const MetricWindow& window);

/// Mean and sample standard deviation of seed-to-seed values (compare and sweep --seeds).
struct Spread {
  double mean = 0.0, sd = 0.0;
};
/// The spread of `values`: 0 / 0 when empty, sd 0 with fewer than two.
Spread spread_of(const std::vector<double>& values);

/// The flap frequency of `run` (of `scene`), Hz: zero crossings of the fly
/// end's out-of-plane position over the second half (0 when it does not flap).
double flap_hz_of(const Scene& scene, const RunRecord& run);

std::string csv_header();
std::string csv_line(const ReportRow& row);
/// Rows of a CSV this module wrote (for merging sweep points). Throws UserError naming the file.
std::vector<std::string> csv_rows(const std::string& path);

/// A row back from a line csv_line wrote (one csv_rows accepted), for the
/// table a sweep prints; numbers as printed (6 significant digits).
ReportRow parse_csv_line(const std::string& line);

/// The short human-readable table printed to stdout.
std::string text_table(const std::vector<ReportRow>& rows);

/// Checks that a report can be written at `path` (its directory is writable,
/// `path` not a directory); empty is fine. A missing directory is made through
/// `directories` (which removes it again if the command fails before writing
/// there), as `run` makes its output's; without it, it is an error. Throws UserError.
void check_report_path(const std::string& path, CreatedDirectories* directories = nullptr);
/// The rows as CSV at `path` (csv_header, then a csv_line each); empty: nothing. Throws IoError.
void write_report(const std::string& path, const std::vector<ReportRow>& rows);

}  // namespace flagsim::app
