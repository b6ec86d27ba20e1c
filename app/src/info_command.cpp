// `flag-sim info OUT.h5 [--json]`: what a run was and how it went, as text for
// people or as one JSON object for scripts (the same facts, named the same).
#include "info_command.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numeric>
#include <optional>
#include <sstream>

#include "flagsim/core/errors.hpp"
#include "flagsim/core/message.hpp"
#include "flagsim/data/isolated_read.hpp"
#include "flagsim/data/output_reader.hpp"

namespace flagsim::app {
namespace {

// What `info` reports, read once from the file.
struct RunSummary {
  std::string file, status, reason, mode, effects, version;
  long long seed = 0;
  int rows = 0, cols = 0, frames = 0;
  bool dense = true;           ///< false: output.dense = false, the coarse trajectory only
  int trajectory_frames = 0;   ///< simulated frames in /coarse/trajectory
  bool crease_angles = false;  ///< /coarse/memory beside it ([creases])
  double t_first_s = 0.0, t_last_s = 0.0;
  double substeps = 0.0, substep_s = 0.0, stable_substep_s = 0.0;
  bool has_strain = false;
  double max_strain = 0.0, mean_strain = 0.0;
  bool has_timing = false;
  double ms_per_frame = 0.0;
  std::vector<std::pair<std::string, double>> stage_ms;  ///< mean over frames 1.., ms
  bool has_infill = false;
  int converged_frames = 0, infill_frames = 0;
  double median_iterations = 0.0, median_offset_m = 0.0, max_offset_m = 0.0;
  int checkpoint_frame = -1;      ///< the frame /checkpoint holds the state of; -1: none
  std::string checkpoint_damage;  ///< why /checkpoint cannot be read (run --resume refuses it)
  double fps = 0.0;
};

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::nth_element(values.begin(), values.begin() + long(values.size() / 2), values.end());
  return values[values.size() / 2];
}

RunSummary summarise(const std::string& path) {
  const data::OutputReader reader(path);
  RunSummary s;
  s.file = path;
  s.status = reader.attribute("status");
  s.reason = reader.attribute("status_reason");
  s.mode = reader.attribute("mode");
  s.effects = reader.attribute("effects");
  s.version = reader.attribute("version");
  s.seed = reader.seed();
  s.rows = reader.rows();
  s.cols = reader.cols();
  s.frames = reader.frame_count();
  s.dense = reader.dense();
  s.trajectory_frames = reader.trajectory_frames();
  s.crease_angles = !reader.coarse_memory(0).empty();
  try {  // a damaged checkpoint leaves the frames readable: said below, not an error here
    if (const std::optional<data::Checkpoint> checkpoint = reader.checkpoint())
      s.checkpoint_frame = checkpoint->frame;
  } catch (const UserError& e) {
    s.checkpoint_damage = e.what();
  }
  s.fps = reader.number_attribute("fps", 0.0);
  const std::vector<double> times = reader.times_s();
  if (!times.empty()) {
    s.t_first_s = times.front();
    s.t_last_s = times.back();
  }
  s.substeps = reader.number_attribute("substeps_per_frame", 0.0);
  s.substep_s = reader.number_attribute("substep_seconds", 0.0);
  s.stable_substep_s = reader.number_attribute("stable_substep_seconds", 0.0);
  const std::vector<double> max_strain = reader.stat("max_strain");
  const std::vector<double> mean_strain = reader.stat("mean_strain");
  if (!max_strain.empty()) {
    s.has_strain = true;
    s.max_strain = *std::max_element(max_strain.begin(), max_strain.end());
    s.mean_strain = std::accumulate(mean_strain.begin(), mean_strain.end(), 0.0) /
                    double(std::max<std::size_t>(1, mean_strain.size()));
  }
  const std::vector<double> wall = reader.stat("wall_seconds");
  // Frame 0 is the initial state (no physics): left out of the averages.
  if (wall.size() > 1) {
    s.has_timing = true;
    s.ms_per_frame =
        1000.0 * std::accumulate(wall.begin() + 1, wall.end(), 0.0) / double(wall.size() - 1);
    const std::vector<std::string> names = reader.stage_names();
    const auto stages = reader.stage_seconds();
    for (std::size_t i = 0; i < names.size(); ++i) {
      double sum = 0.0;
      for (std::size_t t = 1; t < stages.size(); ++t) sum += stages[t][i];
      s.stage_ms.emplace_back(names[i],
                              1000.0 * sum / double(std::max<std::size_t>(1, stages.size() - 1)));
    }
  }
  const std::vector<double> converged = reader.stat("infill_converged");
  if (!converged.empty()) {
    s.has_infill = true;
    s.infill_frames = int(converged.size());
    s.converged_frames = int(std::count(converged.begin(), converged.end(), 1.0));
    s.median_iterations = median(reader.stat("infill_iterations"));
    const std::vector<double> offsets = reader.stat("coarse_offset");
    s.median_offset_m = median(offsets);
    s.max_offset_m = offsets.empty() ? 0.0 : *std::max_element(offsets.begin(), offsets.end());
  }
  return s;
}

// Everything a file says, as valid UTF-8 (for JSON) or also without control
// characters (for a terminal): a file cannot recolour the screen or break a parser.
RunSummary cleaned(RunSummary s, std::string (*clean)(const std::string&)) {
  for (std::string* text :
       {&s.file, &s.status, &s.reason, &s.mode, &s.effects, &s.version, &s.checkpoint_damage})
    *text = clean(*text);
  for (auto& stage : s.stage_ms) stage.first = clean(stage.first);
  return s;
}

std::string text_of(const RunSummary& s) {
  std::string text;
  const auto out = std::back_inserter(text);
  fmt::format_to(out, "file      {}\n", s.file);
  fmt::format_to(out, "status    {}\n", s.status);
  if (!s.reason.empty()) fmt::format_to(out, "reason    {}\n", s.reason);
  fmt::format_to(out, "mode      {}\n", s.mode);
  fmt::format_to(out, "lattice   {} x {} ({} nodes)\n", s.rows, s.cols, s.rows * s.cols);
  if (s.frames == 0)
    fmt::format_to(out, "frames    0\n");
  else
    fmt::format_to(out, "frames    {}, t = {:.4g} .. {:.4g} s\n", s.frames, s.t_first_s,
                   s.t_last_s);
  if (!s.dense)
    fmt::format_to(out,
                   "stored    the coarse trajectory only (output.dense = false, {} simulated "
                   "frames{}); `flag-sim refine {} -o DENSE.h5` recomputes the dense frames\n",
                   s.trajectory_frames, s.crease_angles ? ", with each one's crease angles" : "",
                   s.file);
  fmt::format_to(out, "effects   {}\n", s.effects);
  fmt::format_to(out, "seed      {}\n", s.seed);
  fmt::format_to(out, "version   {}\n", s.version);
  if (s.substeps > 0)
    fmt::format_to(out, "substeps  {:.0f} per frame of {:.3g} s (stability limit {:.3g} s)\n",
                   s.substeps, s.substep_s, s.stable_substep_s);
  if (s.has_strain)
    fmt::format_to(out, "strain    max {:.3f}%, mean {:.3f}% (over all frames)\n",
                   100.0 * s.max_strain, 100.0 * s.mean_strain);
  if (s.has_infill)
    fmt::format_to(
        out,
        "infill    converged in {} of {} frames, {:.0f} iterations in the median frame, coarse "
        "counterparts {:.1f} mm off (median), {:.1f} mm (max)\n",
        s.converged_frames, s.infill_frames, s.median_iterations, 1e3 * s.median_offset_m,
        1e3 * s.max_offset_m);
  // What run --resume can do with the file (nothing for a diverged run: it would diverge again).
  if (s.status != "diverged") {
    if (!s.checkpoint_damage.empty())
      fmt::format_to(out, "resume    not possible: {}\n", s.checkpoint_damage);
    else if (s.checkpoint_frame >= 0 && s.fps > 0.0)
      fmt::format_to(out,
                     "resume    its state at frame {} (t = {:.4g} s): `flag-sim run --resume {} "
                     "--frames N` continues the run\n",
                     s.checkpoint_frame, s.checkpoint_frame / s.fps, s.file);
    else
      fmt::format_to(out,
                     "resume    no checkpoint (output.checkpoint = false, or an older flag-sim): "
                     "not to be continued\n");
  }
  if (s.has_timing) {
    std::string split;
    for (const auto& [name, ms] : s.stage_ms)
      split += fmt::format("{}{} {:.2f}", split.empty() ? "" : ", ", name, ms);
    fmt::format_to(out, "timing    {:.2f} ms/frame ({})\n", s.ms_per_frame, split);
  }
  return text;
}

// A JSON string literal (RFC 8259: quote, backslash and control characters escaped).
std::string json_string(const std::string& text) {
  std::string out = "\"";
  for (const unsigned char c : text) {
    if (c == '"' || c == '\\')
      out += fmt::format("\\{}", char(c));
    else if (c < 0x20)
      out += fmt::format("\\u{:04x}", c);
    else
      out += char(c);
  }
  return out + "\"";
}

// A JSON number: shortest round-trip form; null for NaN and infinities.
std::string json_number(double x) {
  return std::isfinite(x) ? fmt::format("{}", x) : "null";
}

std::string json_of(const RunSummary& s) {
  std::vector<std::string> effects;
  std::stringstream list(s.effects);
  for (std::string effect; std::getline(list, effect, ',');)
    if (!effect.empty()) effects.push_back(json_string(effect));
  std::string out = "{";
  const auto field = [&out](const char* key, const std::string& value) {
    out += fmt::format("{}\"{}\": {}", out.size() > 1 ? ", " : "", key, value);
  };
  field("file", json_string(s.file));
  field("status", json_string(s.status));
  field("status_reason", json_string(s.reason));
  field("mode", json_string(s.mode));
  field("lattice", fmt::format("{{\"rows\": {}, \"cols\": {}, \"nodes\": {}}}", s.rows, s.cols,
                               s.rows * s.cols));
  field("frames", fmt::format("{}", s.frames));
  field("dense", s.dense ? "true" : "false");
  field("time_s", fmt::format("[{}, {}]", json_number(s.t_first_s), json_number(s.t_last_s)));
  field("effects", fmt::format("[{}]", fmt::join(effects, ", ")));
  field("seed", fmt::format("{}", s.seed));
  field("version", json_string(s.version));
  if (s.substeps > 0) {
    field("substeps_per_frame", fmt::format("{:.0f}", s.substeps));
    field("substep_seconds", json_number(s.substep_s));
    field("stable_substep_seconds", json_number(s.stable_substep_s));
  }
  if (s.has_strain)
    field("strain", fmt::format("{{\"max\": {}, \"mean\": {}}}", json_number(s.max_strain),
                                json_number(s.mean_strain)));
  if (s.has_infill)
    field("infill",
          fmt::format("{{\"converged_frames\": {}, \"frames\": {}, "
                      "\"median_iterations\": {}, \"coarse_offset_m\": {{\"median\": {}, "
                      "\"max\": {}}}}}",
                      s.converged_frames, s.infill_frames, json_number(s.median_iterations),
                      json_number(s.median_offset_m), json_number(s.max_offset_m)));
  field("checkpoint_frame",
        s.checkpoint_frame >= 0 ? fmt::format("{}", s.checkpoint_frame) : "null");
  if (s.has_timing) {
    std::vector<std::string> stages;
    for (const auto& [name, ms] : s.stage_ms)
      stages.push_back(fmt::format("{}: {}", json_string(name), json_number(ms)));
    field("ms_per_frame", json_number(s.ms_per_frame));
    field("stage_ms", fmt::format("{{{}}}", fmt::join(stages, ", ")));
  }
  return out + "}\n";
}

}  // namespace

int info_command(const std::string& path, bool json) {
  // Read and formatted in a child, printed here (data/isolated_read.hpp): a
  // damaged file that crashes HDF5 is one error line, never a crash.
  const std::string text = data::run_isolated(path, [&path, json] {
    const RunSummary summary = summarise(path);
    return json ? json_of(cleaned(summary, valid_utf8)) : text_of(cleaned(summary, terminal_safe));
  });
  fmt::print("{}", text);
  return int(ExitCode::kSuccess);
}

}  // namespace flagsim::app
