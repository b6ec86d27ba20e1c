#include "run_record.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "flagsim/coarse_physics/spring_damper.hpp"
#include "flagsim/core/divergence.hpp"
#include "flagsim/core/stage_times.hpp"
#include "flagsim/core/strain.hpp"
#include "flagsim/hybrid/simulation.hpp"
#include "progress.hpp"

namespace flagsim::app {
namespace {

bool is_infill_stage(const std::string& name) {
  return name == "coarse_slack" || name.starts_with("infill_");
}

// Adds a frame's stage times to the record's sums (frame 0 has none).
void add_times(RunRecord& record, const StageTimes& times) {
  for (std::size_t s = 0; s < times.names().size(); ++s) {
    const double ms = 1e3 * times.seconds()[s];
    record.ms_per_frame += ms;
    (is_infill_stage(times.names()[s]) ? record.infill_ms : record.physics_ms) += ms;
  }
}

// The progress line after frame `frame`, from the times summed so far.
void report_progress(Progress* progress, const RunRecord& record, int frame) {
  if (progress) progress->update(frame, frame / record.fps, record.ms_per_frame / std::max(frame, 1));
}

void average_times(RunRecord& record) {
  const double n = std::max<double>(1.0, double(record.frames.size()) - 1.0);
  record.ms_per_frame /= n;
  record.physics_ms /= n;
  record.infill_ms /= n;
}

// Records why frame `frame` cannot be trusted, if it cannot (`why`, as the run
// loop computes it); false then.
bool frame_is_good(RunRecord& record, const Scene& scene, const std::optional<std::string>& why,
                   int frame) {
  if (!why) return true;
  record.status = "diverged";
  record.status_reason =
      fmt::format("at t = {:.4g} s (frame {}): {}", frame / scene.fps, frame, *why);
  return false;
}

}  // namespace

RunRecord record_run(const Scene& scene, Progress* progress) {
  const std::unique_ptr<hybrid::Simulation> simulation = hybrid::make_simulation(scene);
  StageTimes times;
  simulation->register_stages(times);
  RunRecord record;
  record.lattice = simulation->lattice();
  record.fps = scene.fps;
  std::tie(record.coarse_rows, record.coarse_cols) = simulation->coarse_indices();
  for (const NamedNumber& number : simulation->numbers())
    if (number.name == "substeps_per_frame") record.substeps_per_frame = int(number.value);
  const int frames = scene.simulated_frames();
  for (int frame = 0; frame < frames; ++frame) {
    times.reset();
    if (frame > 0) simulation->advance_frame(&times);
    const StrainStats strain = link_strain(record.lattice, simulation->positions());
    if (!frame_is_good(record, scene, hybrid::frame_divergence(*simulation, scene, strain), frame))
      break;
    if (frame > 0) add_times(record, times);
    report_progress(progress, record, frame);
    record.frames.emplace_back(simulation->positions().begin(), simulation->positions().end());
    const auto coarse = simulation->coarse_positions();
    if (!coarse.empty()) record.coarse.emplace_back(coarse.begin(), coarse.end());
  }
  if (progress) progress->done();
  average_times(record);
  return record;
}

RunRecord record_tracking(const Scene& scene, const RunRecord& hybrid, Progress* progress) {
  Scene full = scene;
  full.mode = Mode::kMassSpring;
  physics::SpringDamperSolver solver(full);
  physics::ClothState state = solver.initial_state(full.seed);
  RunRecord record;
  record.lattice = solver.model().lattice;
  record.fps = full.fps;
  record.substeps_per_frame = solver.substeps_per_frame();
  // Coarse node c sits at dense (rows[c / Kc], cols[c % Kc]).
  std::vector<std::size_t> nodes;
  for (int jr : hybrid.coarse_rows)
    for (int kc : hybrid.coarse_cols) nodes.push_back(record.lattice.index(jr, kc));
  const double fps = full.fps;
  const int last = int(hybrid.coarse.size()) - 1;
  solver.drive(nodes, [&](std::size_t which, double t) {
    const double f = std::clamp(t * fps, 0.0, double(last));
    const int a = std::min(int(f), std::max(last - 1, 0)), b = std::min(a + 1, last);
    const double w = f - a;
    return Vec3((1.0 - w) * hybrid.coarse[std::size_t(a)][which] +
                w * hybrid.coarse[std::size_t(b)][which]);
  });
  // The start is the hybrid's frame 0 (its coarse nodes, with their slack,
  // and the infill between them), at rest.
  state.x_m = hybrid.frames[0];
  std::fill(state.v_m_s.begin(), state.v_m_s.end(), Vec3::Zero());
  StageTimes times;
  solver.register_stages(times);
  const int frames = int(hybrid.frames.size());
  for (int frame = 0; frame < frames; ++frame) {
    times.reset();
    if (frame > 0) solver.advance_frame(state, &times);
    const StrainStats strain = link_strain(record.lattice, state.x_m);
    if (!frame_is_good(record, full, divergence_reason(state.x_m, state.v_m_s, strain, full.limits),
                       frame))
      break;
    if (frame > 0) add_times(record, times);
    report_progress(progress, record, frame);
    record.frames.push_back(state.x_m);
  }
  if (progress) progress->done();
  average_times(record);
  return record;
}

}  // namespace flagsim::app
