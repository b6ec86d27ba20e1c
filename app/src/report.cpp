#include "report.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "flagsim/core/errors.hpp"
#include "flagsim/core/message.hpp"
#include "flagsim/os/staged_file.hpp"

namespace flagsim::app {
namespace {

std::string lattice_text(int rows, int cols) {
  return fmt::format("{}x{}", rows, cols);
}

std::string optional_text(const std::optional<double>& value) {
  return value ? fmt::format("{:.6g}", *value) : std::string();
}

// The node whose flapping is measured: the middle of the edge opposite the
// pinned one (the fly end), the middle of the cloth when no edge is pinned.
std::size_t fly_end_node(const Lattice& l, PinSet pin) {
  switch (pin) {
    case PinSet::kLeft:
      return l.index(l.rows / 2, l.cols - 1);
    case PinSet::kRight:
      return l.index(l.rows / 2, 0);
    case PinSet::kTop:
      return l.index(l.rows - 1, l.cols / 2);
    case PinSet::kCorners:
    case PinSet::kNone:
      break;
  }
  return l.index(l.rows / 2, l.cols / 2);
}

// The fly end's out-of-plane position over the second half.
std::vector<double> fly_end_signal(const RunRecord& run, PinSet pin) {
  const Lattice& l = run.lattice;
  const std::size_t node = fly_end_node(l, pin);
  std::vector<double> z;
  for (std::size_t t = run.frames.size() / 2; t < run.frames.size(); ++t)
    z.push_back(run.frames[t][node].z());
  return z;
}

}  // namespace

Spread spread_of(const std::vector<double>& values) {
  Spread s;
  if (values.empty()) return s;
  for (const double v : values) s.mean += v / double(values.size());
  if (values.size() < 2) return s;
  double sum = 0.0;
  for (const double v : values) sum += (v - s.mean) * (v - s.mean);
  s.sd = std::sqrt(sum / double(values.size() - 1));
  return s;
}

double flap_hz_of(const Scene& scene, const RunRecord& run) {
  return analysis::flap_frequency_hz(fly_end_signal(run, scene.flag.pin), scene.fps);
}

ReportRow describe(const Scene& scene, const RunRecord& run, const RunRecord& reference,
                   const RunRecord* tracking, const MetricWindow& window) {
  ReportRow row;
  row.seed = scene.seed;
  if (scene.solid_pole) row.pole_radius_m = scene.solid_pole->radius_m;
  if (scene.contact) row.contact_thickness_m = scene.contact->thickness_m;
  row.mode = to_string(scene.mode);
  row.backend = backend_name_of(scene);
  row.fine = lattice_text(run.lattice.rows, run.lattice.cols);
  row.coarse = run.coarse_rows.empty()
                   ? std::string()
                   : lattice_text(int(run.coarse_rows.size()), int(run.coarse_cols.size()));
  row.substeps = run.substeps_per_frame;
  const bool has_infill = scene.mode == Mode::kHybrid || scene.mode == Mode::kInfill;
  if (has_infill) row.infill_solver = to_string(infill_solver_of(scene));
  // The cap the paper solver ran with; the smooth solver has no such knob.
  if (has_infill && infill_solver_of(scene) == InfillSolverKind::kPaper)
    row.relax_iterations = paper_relax_sweeps_of(scene);
  row.frames = int(run.frames.size());
  row.ms_per_frame = run.ms_per_frame;
  row.physics_ms = run.physics_ms;
  row.infill_ms = run.infill_ms;
  const analysis::StrainDistribution strain =
      analysis::strain_distribution(run.lattice, run.frames);
  row.max_strain = strain.max;
  row.p99_strain = strain.p99;
  row.status = run.status.state;
  const int horizon = std::max(1, int(std::lround(window.horizon_s * scene.fps)));
  const int half = int(std::min(run.frames.size(), reference.frames.size()) / 2);
  row.short_horizon_rms_m = analysis::short_horizon_rms(run.frames, reference.frames, horizon);
  row.mean_shape_rms_m = analysis::mean_shape_rms(run.frames, reference.frames, half);
  row.flap_hz = flap_hz_of(scene, run);
  const double reference_hz = flap_hz_of(scene, reference);
  if (reference_hz > 0.0) row.flap_rel_error = std::abs(*row.flap_hz - reference_hz) / reference_hz;
  row.wrinkle_wavelength_m = analysis::wrinkle_wavelength_m(run.lattice, run.frames, half);
  if (tracking && !run.coarse_rows.empty()) {
    // Every node but the driven (coarse) ones, over every frame both have.
    std::vector<std::uint8_t> keep(run.lattice.node_count(), 1);
    for (int j : run.coarse_rows)
      for (int k : run.coarse_cols) keep[run.lattice.index(j, k)] = 0;
    const std::size_t frames = std::min(run.frames.size(), tracking->frames.size());
    double sum = 0.0;
    for (std::size_t t = 1; t < frames; ++t) {
      const double r = analysis::rms_distance(run.frames[t], tracking->frames[t], keep);
      sum += r * r;
    }
    row.tracking_rms_m = frames > 1 ? std::sqrt(sum / double(frames - 1)) : 0.0;
  }
  return row;
}

std::string csv_header() {
  return "point,label,mode,backend,fine,coarse,substeps,relax_iterations,frames,ms_per_frame,"
         "physics_ms,infill_ms,max_strain,p99_strain,short_horizon_rms_m,tracking_rms_m,flap_hz,"
         "flap_rel_error,mean_shape_rms_m,wrinkle_wavelength_m,status,infill_solver,best_reference,"
         "speedup_vs_best_reference,seed,pole_radius_m,contact_thickness_m";
}

std::string csv_line(const ReportRow& r) {
  return fmt::format(
      "{},{},{},{},{},{},{},{},{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{},{},{},{},{},{},{},{},{},{},"
      "{},{},{}",
      r.point, r.label, r.mode, r.backend, r.fine, r.coarse, r.substeps, r.relax_iterations,
      r.frames, r.ms_per_frame, r.physics_ms, r.infill_ms, r.max_strain, r.p99_strain,
      optional_text(r.short_horizon_rms_m), optional_text(r.tracking_rms_m),
      optional_text(r.flap_hz), optional_text(r.flap_rel_error), optional_text(r.mean_shape_rms_m),
      optional_text(r.wrinkle_wavelength_m), to_string(r.status), r.infill_solver, r.best_reference,
      optional_text(r.speedup_vs_best_reference), r.seed, optional_text(r.pole_radius_m),
      optional_text(r.contact_thickness_m));
}

std::vector<std::string> csv_rows(const std::string& path) {
  // A regular file of at most 64 MiB (a point's row is about 300 bytes): a
  // FIFO, /dev/zero or a huge sparse file is refused before a line is read.
  constexpr std::size_t kMaxCsvBytes = std::size_t(64) << 20;
  std::istringstream in(read_file_capped(path, kMaxCsvBytes, "--merge"));
  std::string line;
  if (!std::getline(in, line) || line != csv_header())
    throw UserError(
        fmt::format("{}: not a flag-sim sweep or compare CSV (header differs)", printable(path)));
  // Every row as this module writes it: the header's number of fields, the
  // first a point number (digits only), so that merging can trust them.
  const auto fields = [](const std::string& text) {
    return std::count(text.begin(), text.end(), ',') + 1;
  };
  const auto header_fields = fields(csv_header());
  std::vector<std::string> rows;
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    const std::string point = line.substr(0, line.find(','));
    if (fields(line) != header_fields || point.empty() || point.size() > 9 ||
        !std::all_of(point.begin(), point.end(), [](char c) { return c >= '0' && c <= '9'; }))
      throw UserError(
          fmt::format("{}:{}: not a row of a flag-sim sweep CSV ({} fields, the first a "
                      "point number, expected)",
                      printable(path), number, header_fields));
    try {  // every number a number, now: not an internal error at the table
      parse_csv_line(line);
    } catch (const UserError& e) {
      throw UserError(fmt::format("{}:{}: {}", printable(path), number, e.what()));
    }
    rows.push_back(line);
  }
  return rows;
}

ReportRow parse_csv_line(const std::string& line) {
  std::vector<std::string> cells;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    cells.push_back(
        line.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  // Each cell a whole number as written by csv_line ("nan" and "inf" included), else UserError.
  const auto parse = [&](std::size_t i) {
    const std::string& cell = cells[i];
    char* end = nullptr;
    const double value = std::strtod(cell.c_str(), &end);
    if (end != cell.c_str() + cell.size()) {
      const std::string header = csv_header();
      std::size_t at = 0;
      for (std::size_t c = 0; c < i && at != std::string::npos; ++c) at = header.find(',', at) + 1;
      const std::string name = header.substr(at, header.find(',', at) - at);
      throw UserError(
          fmt::format("column {} ({}) is \"{}\", not a number", i + 1, name, printable(cell, 40)));
    }
    return value;
  };
  const auto number = [&](std::size_t i) {
    return cells.size() > i && !cells[i].empty() ? parse(i) : 0.0;
  };
  const auto optional = [&](std::size_t i) -> std::optional<double> {
    if (cells.size() <= i || cells[i].empty()) return std::nullopt;
    return parse(i);
  };
  const auto text = [&](std::size_t i) { return cells.size() > i ? cells[i] : std::string(); };
  ReportRow r;
  r.point = int(number(0));
  r.label = text(1);
  r.mode = text(2);
  r.backend = text(3);
  r.fine = text(4);
  r.coarse = text(5);
  const auto integer = [&](std::size_t i) {
    const double value = number(i);
    if (!(std::abs(value) < 2.0e9))
      throw UserError(fmt::format("column {} is {}, not a count", i + 1, printable(cells[i], 40)));
    return int(value);
  };
  r.substeps = integer(6);
  r.relax_iterations = integer(7);
  r.frames = integer(8);
  r.ms_per_frame = number(9);
  r.physics_ms = number(10);
  r.infill_ms = number(11);
  r.max_strain = number(12);
  r.p99_strain = number(13);
  r.short_horizon_rms_m = optional(14);
  r.tracking_rms_m = optional(15);
  r.flap_hz = optional(16);
  r.flap_rel_error = optional(17);
  r.mean_shape_rms_m = optional(18);
  r.wrinkle_wavelength_m = optional(19);
  const std::optional<RunState> status = value_in(kRunStateNames, text(20));
  if (!status)
    throw UserError(fmt::format("a report row's status \"{}\": expected {}", text(20),
                                fmt::join(names_in(kRunStateNames), ", ")));
  r.status = *status;
  r.infill_solver = text(21);
  r.best_reference = text(22);
  r.speedup_vs_best_reference = optional(23);
  const std::string seed = text(24);
  if (seed.empty() || seed.size() > 20 ||
      !std::all_of(seed.begin(), seed.end(), [](char c) { return c >= '0' && c <= '9'; }))
    throw UserError(fmt::format("column 25 (seed) is \"{}\", not a seed", printable(seed, 40)));
  errno = 0;
  r.seed = std::strtoull(seed.c_str(), nullptr, 10);
  if (errno == ERANGE)
    throw UserError(fmt::format("column 25 (seed) is {}, past 2^64", printable(seed, 40)));
  r.pole_radius_m = optional(25);
  r.contact_thickness_m = optional(26);
  return r;
}

std::string text_table(const std::vector<ReportRow>& rows) {
  auto mm = [](const std::optional<double>& v) {
    return v ? fmt::format("{:.1f}", 1e3 * *v) : std::string("-");
  };
  std::string out = fmt::format(
      "{:<40} {:>9} {:>8} {:>8} {:>7} {:>6} {:>9} {:>9} {:>6} {:>9} {:>8}\n", "run", "ms/frame",
      "physics", "infill", "max%", "p99%", "short mm", "track mm", "flapHz", "shape mm", "wrinkle");
  for (const ReportRow& r : rows)
    out += fmt::format(
        "{:<40} {:>9.1f} {:>8.1f} {:>8.1f} {:>7.2f} {:>6.2f} {:>9} {:>9} {:>6} {:>9} {:>8}\n",
        r.label, r.ms_per_frame, r.physics_ms, r.infill_ms, 100 * r.max_strain, 100 * r.p99_strain,
        mm(r.short_horizon_rms_m), mm(r.tracking_rms_m),
        r.flap_hz ? fmt::format("{:.2f}", *r.flap_hz) : "-", mm(r.mean_shape_rms_m),
        r.wrinkle_wavelength_m ? fmt::format("{:.3f}", *r.wrinkle_wavelength_m) : "-");
  return out;
}

void check_report_path(const std::string& path, CreatedDirectories* directories) {
  namespace fs = std::filesystem;
  if (path.empty()) return;
  const fs::path parent = fs::path(path).has_parent_path() ? fs::path(path).parent_path() : ".";
  std::error_code ec;
  if (directories && !fs::exists(fs::symlink_status(parent, ec)) &&
      !directories->create(parent.string(), ec))
    throw UserError(fmt::format("-o {}: cannot create its directory {}: {}", printable(path),
                                printable(parent.string()), ec.message()));
  if (!fs::is_directory(parent, ec) || access(parent.c_str(), W_OK) != 0 ||
      fs::is_directory(path, ec))
    throw UserError(
        fmt::format("-o {}: cannot write a report there ({} is not a writable "
                    "directory, or the path is one)",
                    printable(path), printable(parent.string())));
}

void write_report(const std::string& path, const std::vector<ReportRow>& rows) {
  if (path.empty()) return;
  // Whole or not at all: a full disk leaves nothing under the report's name (exit 4).
  std::string text = csv_header() + "\n";
  for (const ReportRow& row : rows) text += csv_line(row) + "\n";
  write_file_whole(path, text);
}

}  // namespace flagsim::app
