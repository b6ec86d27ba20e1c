// `flag-sim run`: scene -> solver -> frames on disk, with divergence checks,
// interruption and the progress line.
#include "run_command.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <tuple>

#include "flagsim/core/errors.hpp"
#include "flagsim/core/message.hpp"
#include "flagsim/core/version.hpp"
#include "flagsim/data/frame_writer.hpp"
#include "flagsim/data/output_reader.hpp"
#include "flagsim/os/file_roles.hpp"
#include "flagsim/scene/scene_parser.hpp"
#include "flagsim/sim/divergence.hpp"
#include "flagsim/sim/frame_runner.hpp"
#include "flagsim/sim/simulation.hpp"
#include "interrupt.hpp"
#include "progress.hpp"
#include "render_command.hpp"
#include "scene_commands.hpp"

namespace flagsim::app {
namespace {

// The scene keys run's own flags set, each quoted as the user typed it.
std::vector<Override> overrides_of(const RunOptions& options) {
  std::vector<Override> overrides = set_overrides(options.sets);
  if (options.mode)
    overrides.push_back(
        {fmt::format("scene.mode={}", toml_string(*options.mode)), "--mode " + *options.mode});
  if (options.seed) {
    // As typed, not through a fixed-width parse that would clamp 2^64 - 1 to 2^63 - 1.
    const std::string& seed = *options.seed;
    const bool digits =
        !seed.empty() && seed.size() <= 19 &&
        std::all_of(seed.begin(), seed.end(), [](char c) { return c >= '0' && c <= '9'; });
    if (!digits || (seed.size() == 19 && seed > "9223372036854775807"))
      throw UserError(fmt::format("--seed {}: expected an integer from 0 to 9223372036854775807",
                                  printable(seed)));
    overrides.push_back({fmt::format("scene.seed={}", seed), "--seed " + seed});
  }
  if (options.frames)
    overrides.push_back({fmt::format("scene.frames={}", *options.frames),
                         fmt::format("--frames {}", *options.frames)});
  return overrides;
}

std::string output_path_of(const RunOptions& options, const Scene& scene) {
  if (!options.output_path.empty()) return options.output_path;
  if (!scene.output.file.empty()) return scene.output.file;
  check_file_name_part(scene.name, fmt::format("scene.name \"{}\"", printable(scene.name)));
  return fmt::format("out/{}.h5", scene.name);
}

// The XDMF sidecar FrameWriter::finish writes beside `h5_path`.
std::string sidecar_of(const std::string& h5_path) {
  return std::filesystem::path(h5_path).replace_extension(".xdmf").string();
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// What refine may change (--set): the dense lattice, the infill and the output;
// every other key is the physics the trajectory already holds.
void check_refine_override(const Override& set) {
  const std::string_view text = set.assignment;
  const std::string_view key = text.substr(0, text.find('='));
  const auto starts = [&](std::string_view prefix) {
    return key.substr(0, prefix.size()) == prefix;
  };
  if (key == "flag.fine" || starts("infill.") || starts("wrinkles.") || starts("limits.") ||
      (starts("output.") && key != "output.dense" && key != "output.file"))
    return;
  throw UserError(fmt::format(
      "{}: refine recomputes the dense frames from the stored coarse trajectory and takes only "
      "flag.fine, infill.*, wrinkles.*, limits.* and output.* (not dense, file); {} is the "
      "physics: run the scene again",
      set.typed, printable(std::string(key))));
}

// The state as a checkpoint's parts (run --resume): float64 as the simulation
// holds it, each part a view of `state` (which must outlive the checkpoint).
std::span<const double> flat(std::span<const Vec3> vectors) {
  static_assert(sizeof(Vec3) == 3 * sizeof(double));
  return {vectors.empty() ? nullptr : vectors.front().data(), 3 * vectors.size()};
}

// A file without dense frames (output.dense = false) keeps no dense state
// either: resume fills it again from the coarse trajectory, as refine does.
data::Checkpoint checkpoint_of(const sim::SimulationState& state, int written_frames,
                               int trajectory_frames) {
  data::Checkpoint checkpoint;
  checkpoint.frame = state.frame;
  checkpoint.written_frames = written_frames;
  checkpoint.trajectory_frames = trajectory_frames;
  checkpoint.parts = {{"physics_positions", flat(state.physics.x_m), "m"},
                      {"physics_velocities", flat(state.physics.v_m_s), "m/s"},
                      {"physics_time", {&state.physics.time_s, 1}, "s"}};
  if (!state.physics.memory.empty())  // the creases' rest angles
    checkpoint.parts.push_back({"physics_memory", state.physics.memory, "rad"});
  if (trajectory_frames == 0) {
    checkpoint.parts.push_back({"dense_positions", flat(state.dense_m), "m"});
    checkpoint.parts.push_back({"dense_velocities", flat(state.dense_v_m_s), "m/s"});
    checkpoint.parts.push_back({"infill_memory", state.infill_memory, "m"});
  }
  if (const auto& wind = state.wind) {
    checkpoint.parts.push_back({"wind_mean", flat({&wind->mean_m_s, 1}), "m/s"});
    checkpoint.parts.push_back({"wind_offset", flat({&wind->offset_m, 1}), "m"});
    checkpoint.parts.push_back({"wind_since", {&wind->since_s, 1}, "s"});
  }
  return checkpoint;
}

sim::SimulationState state_of(const data::Checkpoint& checkpoint, const std::string& file) {
  const auto values = [&](const char* name, std::size_t multiple) {
    const data::Checkpoint::Part* part = checkpoint.part(name);
    const std::span<const double> found = part ? part->values() : std::span<const double>();
    if (!part || found.size() % multiple != 0)
      throw UserError(fmt::format("{}: /checkpoint/{} is {}", file, name,
                                  part ? "damaged (its length)" : "missing"));
    if (!std::all_of(found.begin(), found.end(), [](double v) { return std::isfinite(v); }))
      throw UserError(
          fmt::format("{}: /checkpoint/{} is damaged (a value not finite)", file, name));
    return found;
  };
  const auto vectors = [&](const char* name) {
    const std::span<const double> flat_values = values(name, 3);
    std::vector<Vec3> result(flat_values.size() / 3);
    for (std::size_t i = 0; i < result.size(); ++i)
      result[i] = Vec3(flat_values[3 * i], flat_values[3 * i + 1], flat_values[3 * i + 2]);
    return result;
  };
  const auto scalar = [&](const char* name) {
    const std::span<const double> one = values(name, 1);
    if (one.size() != 1)
      throw UserError(fmt::format("{}: /checkpoint/{} is damaged (its length)", file, name));
    return one[0];
  };
  sim::SimulationState state;
  state.frame = checkpoint.frame;
  state.physics.x_m = vectors("physics_positions");
  state.physics.v_m_s = vectors("physics_velocities");
  state.physics.time_s = scalar("physics_time");
  if (checkpoint.part("physics_memory")) {
    const std::span<const double> memory = values("physics_memory", 1);
    state.physics.memory.assign(memory.begin(), memory.end());
  }
  if (checkpoint.trajectory_frames == 0) {  // else the coarse trajectory gives them (resume_state)
    state.dense_m = vectors("dense_positions");
    state.dense_v_m_s = vectors("dense_velocities");
    const std::span<const double> memory = values("infill_memory", 1);
    state.infill_memory.assign(memory.begin(), memory.end());
  }
  if (checkpoint.part("wind_mean")) {
    const std::vector<Vec3> mean = vectors("wind_mean"), offset = vectors("wind_offset");
    if (mean.size() != 1 || offset.size() != 1)
      throw UserError(fmt::format("{}: /checkpoint/wind_* is damaged (its length)", file));
    state.wind = physics::WindField::Drift{mean[0], offset[0], scalar("wind_since")};
  }
  return state;
}

// The state run --resume continues from. A coarse-only file's dense lattice
// is the infill's over the stored trajectory, replayed to the checkpoint's
// frame (bit for bit what the run held, as refine's frames are).
sim::SimulationState resume_state(const Scene& scene, const data::Checkpoint& checkpoint,
                                  const data::OutputReader& source, const std::string& file) {
  sim::SimulationState state = state_of(checkpoint, file);
  if (checkpoint.trajectory_frames == 0) return state;
  if (checkpoint.trajectory_frames != checkpoint.frame + 1 ||
      source.trajectory_frames() < checkpoint.trajectory_frames)
    throw UserError(
        fmt::format("{}: /checkpoint names {} coarse trajectory frames, the file holds {}", file,
                    checkpoint.trajectory_frames, source.trajectory_frames()));
  const std::unique_ptr<sim::Simulation> replay = sim::make_replay(
      scene, [&source](int frame, std::vector<Vec3>& nodes, std::vector<double>& memory) {
        nodes = source.coarse_trajectory(frame);
        memory = source.coarse_memory(frame);
      });
  for (int frame = 1; frame <= checkpoint.frame; ++frame) replay->advance_frame(nullptr);
  sim::SimulationState dense = replay->state();
  state.dense_m = std::move(dense.dense_m);
  state.dense_v_m_s = std::move(dense.dense_v_m_s);
  state.infill_memory = std::move(dense.infill_memory);
  return state;
}

// What `run --resume` takes besides the file: the duration (--frames, --set
// scene.duration), -o, --quiet and --render; the rest is the run's own.
void check_resume_options(const RunOptions& options) {
  const auto refuse = [&](const std::string& what) {
    throw UserError(fmt::format(
        "{}: run --resume continues the run in {} with its own scene; it takes --frames, --set "
        "scene.duration=T, -o, --quiet and --render (to run another scene, leave out --resume)",
        what, options.resume_input));
  };
  if (!options.scene_path.empty()) refuse(options.scene_path);
  if (options.mode) refuse("--mode " + *options.mode);
  if (options.seed) refuse("--seed " + *options.seed);
  for (const std::string& set : options.sets)
    if (set.substr(0, set.find('=')) != "scene.duration") refuse("--set " + set);
  if (options.resume_input.size() > 8 && options.resume_input.ends_with(".partial"))
    throw UserError(fmt::format(
        "{}: the unfinished file of a run that was killed (or is still running); when no run "
        "writes it, rename it to {} and continue that",
        options.resume_input, options.resume_input.substr(0, options.resume_input.size() - 8)));
}

// Wall time between two checkpoints written before flushes (run --resume).
constexpr double kCheckpointSeconds = 1.0;

// A coarse-trajectory file's state, as its status attribute says.
RunStatus status_of(const data::OutputReader& source) {
  const std::optional<RunState> state = value_in(kRunStateNames, source.attribute("status"));
  return {state.value_or(RunState::kInterrupted), source.attribute("status_reason")};
}

// The run's file as a sink of its frames: the coarse trajectory of every
// frame, every output.every-th frame with its statistics, and the checkpoints.
class FileSink final : public sim::FrameSink {
 public:
  FileSink(const Scene& scene, data::FrameWriter& writer, StageTimes& times, int output_stage,
           bool refining, bool resuming, std::size_t series)
      : scene_(scene),
        writer_(writer),
        times_(times),
        output_stage_(output_stage),
        refining_(refining),
        checkpointed_(resuming),
        series_(series) {}

  bool take(const sim::Simulation& simulation, const sim::CheckedFrame& frame) override {
    if (!scene_.output.dense)
      writer_.append_trajectory(simulation.coarse_positions(), simulation.coarse_memory());
    max_strain_ = std::max(max_strain_, frame.strain.max);
    if (frame.index % scene_.output.every != 0) return true;
    if (auto room = writer_.out_of_room()) {  // stop while the file is whole
      full_ = *room;
      return false;
    }
    if (const std::optional<infill::FillReport> report = simulation.infill_report()) {
      series_ = {report->converged ? 1.0 : 0.0, report->residual, double(report->iterations),
                 report->coarse_offset_m};
      unconverged_frames_ += report->converged ? 0 : 1;
      worst_residual_ = std::max(worst_residual_, report->residual);
    }
    const data::FrameStats stats{frame.strain.max,
                                 frame.strain.mean,
                                 times_.seconds(),
                                 seconds_since(since_write_),
                                 simulation.kinetic_energy_j(),
                                 series_};
    // The state this frame ends in, for a run that stops inside a later frame
    // (a signal, SIGKILL): at the first frame (which fixes where its datasets
    // lie in the file), then before a flush once a second of wall time has
    // passed (1.2 MB on the default scene takes 1-4 ms), and at the end.
    if (scene_.output.checkpoint && !refining_ &&
        (!checkpointed_ ||
         (writer_.flushes_next() && seconds_since(last_checkpoint_) >= kCheckpointSeconds))) {
      checkpointed_ = true;
      last_checkpoint_ = std::chrono::steady_clock::now();
      ScopedStageTimer timer(times_, output_stage_);
      const sim::SimulationState now = simulation.state();
      writer_.write_checkpoint(checkpoint_of(now, writer_.frames_written() + 1,
                                             scene_.output.dense ? 0 : frame.index + 1));
    }
    // Frame times are n / fps exactly, not the sum of the substeps.
    writer_.write_frame(frame.time_s,
                        {simulation.positions(), simulation.velocities(), frame.node_strain,
                         simulation.coarse_positions()},
                        stats);
    times_.reset();
    since_write_ = std::chrono::steady_clock::now();
    return true;
  }

  double max_strain() const { return max_strain_; }
  int unconverged_frames() const { return unconverged_frames_; }
  double worst_residual() const { return worst_residual_; }
  /// Why take() refused a frame: the disk is full.
  const std::string& full() const { return full_; }

 private:
  const Scene& scene_;
  data::FrameWriter& writer_;
  StageTimes& times_;
  int output_stage_;
  bool refining_;
  bool checkpointed_;  // run --resume: the resumed file's checkpoint is copied
  std::chrono::steady_clock::time_point since_write_ = std::chrono::steady_clock::now();
  std::chrono::steady_clock::time_point last_checkpoint_ = std::chrono::steady_clock::now();
  std::vector<double> series_;  // the infill's account of the frame (RunInfo::series)
  double max_strain_ = 0.0, worst_residual_ = 0.0;
  int unconverged_frames_ = 0;
  std::string full_;
};

}  // namespace

int run_command(const RunOptions& options) {
  if (options.frames && *options.frames < 1)
    throw UserError(fmt::format("--frames {}: expected at least 1 frame", *options.frames));
  const bool refining = !options.refine_input.empty();
  const bool resuming = !options.resume_input.empty();
  std::optional<data::OutputReader> source;  // refine's or resume's input
  std::optional<data::Checkpoint> resume_point;
  if (resuming) {
    check_resume_options(options);
    source.emplace(options.resume_input);
    if (const RunStatus ran = status_of(*source); ran.diverged())
      throw UserError(fmt::format(
          "{}: its run diverged ({}); continuing it would diverge again: change the scene and "
          "run it again",
          options.resume_input, ran.reason));
    resume_point = source->checkpoint();
    if (!resume_point)
      throw UserError(fmt::format(
          "{}: holds no checkpoint to continue from (its scene has output.checkpoint = false, "
          "its run was stopped before its first flush, or an older flag-sim wrote it); run its "
          "scene again with the longer duration",
          options.resume_input));
  }
  if (refining) {
    source.emplace(options.refine_input);
    if (source->trajectory_frames() == 0)
      throw UserError(fmt::format(
          "{}: holds no coarse trajectory to refine (a hybrid run with output.dense = false "
          "keeps one)",
          options.refine_input));
  }
  std::vector<Override> overrides = overrides_of(options);
  if (refining) {
    for (const Override& set : overrides) check_refine_override(set);
    overrides.push_back({"output.dense=true", "refine"});
  }
  const Scene scene =
      resuming   ? parse_scene(source->attribute("scene"), options.resume_input, overrides)
      : refining ? parse_scene(source->attribute("scene"), options.refine_input, overrides)
      : options.scene_text
          ? parse_scene(*options.scene_text,
                        options.scene_path.empty() ? "<scene text>" : options.scene_path, overrides)
          : load_scene(options.scene_path, overrides);
  // run --resume: the frames after the checkpoint's, to the (new) duration.
  const int first_frame = resuming ? resume_point->frame + 1 : 0;
  if (resuming) {
    // scene.frames (run --frames) wins over scene.duration: a --set of it would change nothing.
    const auto frames_at = [&](const char* duration) {
      return parse_scene(source->attribute("scene"), options.resume_input,
                         std::vector<std::string>{duration})
          .simulated_frames();
    };
    const bool fixed_frames = frames_at("scene.duration=1") == frames_at("scene.duration=2");
    if (fixed_frames && !options.sets.empty())
      throw UserError(fmt::format(
          "--set {}: the scene in {} fixes its length with scene.frames (run --frames); "
          "continue it with --frames N",
          options.sets.front(), options.resume_input));
    if (scene.simulated_frames() <= first_frame)
      throw UserError(fmt::format(
          "{}: already holds frames 0 to {} (t = 0 .. {:.4g} s) of its {}-frame scene; give "
          "--frames or --set scene.duration=T beyond them to continue it",
          options.resume_input, first_frame - 1, (first_frame - 1) / scene.fps,
          scene.simulated_frames()));
  }
  if (refining && scene.mode != Mode::kHybrid)
    throw UserError(fmt::format("{}: its scene is in {} mode; refine takes a hybrid run's file",
                                options.refine_input, to_string(scene.mode)));
  // A render is checked before the run: a bad --size must not cost a simulation.
  std::optional<RenderPlan> render_plan;
  if (!options.render.empty()) {
    RenderRequest request;
    request.output = options.render;
    request.size = options.render_size;
    request.style = options.render_style;
    request.texture = options.render_texture;
    request.color = options.render_color;
    request.output_flag = "--render";
    render_plan = plan_render(request, &scene, scene.fps / scene.output.every);
    render_plan->quiet = options.quiet;
  } else if (options.render_size || options.render_style || options.render_texture ||
             options.render_color) {
    throw UserError("--size, --style, --texture and --color go with --render OUT.mp4|DIR");
  }

  // Nothing the run writes may be a file it reads, or another file it writes.
  // run --resume writes back to its file unless -o says otherwise: a new file
  // OUT.h5.partial with the old frames and the new, renamed over OUT.h5 at the
  // end, so OUT.h5 stays as it was until then.
  const std::string output_path = resuming && options.output_path.empty()
                                      ? options.resume_input
                                      : output_path_of(options, scene);
  FileRoles files;
  files.input(options.scene_path, "the scene");
  if (resuming && !same_file(options.resume_input, output_path))
    files.input(options.resume_input, "the run to continue");
  if (refining) files.input(options.refine_input, "the coarse trajectory");
  if (options.render_texture) files.input(*options.render_texture, "--texture");
  if (scene.render) files.input(scene.render->texture, "render.texture");
  files.output(output_path, "the output");
  files.output(output_path + ".partial", "the output's .partial file");
  files.output(sidecar_of(output_path), "the output's XDMF sidecar");
  if (!options.render.empty())  // every frame the run will write, by its number in the file
    add_render_outputs(files, options.render, "--render", 0,
                       (scene.simulated_frames() - 1) / scene.output.every + 1);
  files.check();

  // From here a signal is exit 130: during the set-up (seconds on a large
  // lattice) nothing is written yet, later the frames so far are kept.
  InterruptGuard interrupt;
  const std::unique_ptr<sim::Simulation> simulation =
      refining ? sim::make_replay(
                     scene,
                     [&source](int frame, std::vector<Vec3>& nodes, std::vector<double>& memory) {
                       nodes = source->coarse_trajectory(frame);
                       memory = source->coarse_memory(frame);
                     })
               : sim::make_simulation(scene);
  if (resuming) {
    try {
      simulation->set_state(resume_state(scene, *resume_point, *source, options.resume_input));
    } catch (const UserError& e) {
      throw UserError(fmt::format("{}: its checkpoint does not fit its scene ({})",
                                  options.resume_input, e.what()));
    }
  }
  if (InterruptGuard::requested())
    throw Interrupted("run stopped by a signal during its set-up; nothing was written");
  StageTimes times;
  simulation->register_stages(times);
  const int checks_stage = times.add("checks", StageGroup::kRunLoop);
  const int output_stage = times.add("output", StageGroup::kRunLoop);

  data::RunInfo info;
  info.mode = to_string(scene.mode);
  info.fields = scene.output.fields;
  info.dense = scene.output.dense;
  info.coarse_memory_size = simulation->coarse_memory().size();
  info.compression = scene.output.compression;
  info.effects = simulation->effects();
  info.scene_toml = scene.toml_text;
  info.version = std::string(version());
  info.seed = scene.seed;
  info.stages = times.names();
  info.output_stage = output_stage;
  std::tie(info.coarse_rows, info.coarse_cols) = simulation->coarse_indices();
  info.numbers = simulation->numbers();
  info.numbers.push_back({"fps", scene.fps, "1/s"});
  // The infill's own account of each frame: whether it reached its tolerance, never silently.
  const bool has_infill = simulation->infill_report().has_value();
  if (has_infill)
    info.series = {{"infill_converged", "1"},
                   {"infill_residual", "1"},
                   {"infill_iterations", "1"},
                   {"coarse_offset", "m"}};
  int unconverged_frames = 0;
  double worst_residual = 0.0;
  const Lattice& lattice = simulation->lattice();
  data::FrameWriter writer(output_path, lattice, info, scene.output.flush_every);
  double max_strain_seen = 0.0;
  if (resuming) {  // the frames up to the checkpoint's, as they are, and the checkpoint
    try {
      writer.copy_frames(options.resume_input, resume_point->written_frames,
                         resume_point->trajectory_frames);
    } catch (const UserError&) {  // a damaged frame: nothing is left behind
      writer.discard();
      throw;
    }
    writer.write_checkpoint(*resume_point);
    const auto first = [&](const char* name) {
      std::vector<double> values = source->stat(name);
      values.resize(std::min(values.size(), std::size_t(resume_point->written_frames)));
      return values;
    };
    for (double strain : first("max_strain")) max_strain_seen = std::max(max_strain_seen, strain);
    if (has_infill) {
      const std::vector<double> converged = first("infill_converged");
      const std::vector<double> residual = first("infill_residual");
      for (double c : converged) unconverged_frames += c == 0.0 ? 1 : 0;
      for (double r : residual) worst_residual = std::max(worst_residual, r);
    }
  }
  // refine: the frames the trajectory holds (fewer than the scene's when its run stopped early).
  const int frames = refining ? std::min(scene.simulated_frames(), source->trajectory_frames())
                              : scene.simulated_frames();
  Progress progress(Progress::wanted(options.quiet), frames);
  RunStatus status;  // complete unless a frame says otherwise
  bool out_of_room = false;
  FileSink file(scene, writer, times, output_stage, refining, resuming, info.series.size());
  sim::FrameSink* const sinks[] = {&file, &progress};
  const sim::FrameRunResult result =
      sim::run_frames(*simulation, scene, first_frame, frames, sinks,
                      {&times, checks_stage, scene.output.has_field("strain")});
  // A frame cut short by a signal: the simulation is not at a frame.
  const bool cut_short = result.end == sim::FrameRunEnd::kInterruptedDuring;
  const double at_s = result.frame / scene.fps;
  switch (result.end) {
    case sim::FrameRunEnd::kComplete:
      break;
    case sim::FrameRunEnd::kDiverged:
      status = {RunState::kDiverged,
                fmt::format("at t = {:.4g} s (frame {}): {}", at_s, result.frame,
                            describe(*result.divergence, scene))};
      break;
    case sim::FrameRunEnd::kInterruptedDuring:
      status = {RunState::kInterrupted,
                fmt::format("signal received during frame {} (t = {:.4g} s), which is not written",
                            result.frame, at_s)};
      break;
    case sim::FrameRunEnd::kInterruptedAfter:
      status = {RunState::kInterrupted,
                fmt::format("signal received after frame {} (t = {:.4g} s)", result.frame, at_s)};
      break;
    case sim::FrameRunEnd::kStoppedBySink:  // the file sink: the disk is full
      status = {RunState::kInterrupted, fmt::format("stopped before frame {} (t = {:.4g} s): {}",
                                                    result.frame, at_s, file.full())};
      out_of_room = true;
      break;
  }
  max_strain_seen = std::max(max_strain_seen, file.max_strain());
  unconverged_frames += file.unconverged_frames();
  worst_residual = std::max(worst_residual, file.worst_residual());
  progress.done();
  const bool refined = refining && status.complete();
  if (refined) {  // the run's own ending, and where the frames came from
    const RunStatus ran = status_of(*source);
    status = {ran.state, fmt::format("refined from {}, {} frames written; its run: {}",
                                     options.refine_input, writer.frames_written(), ran.reason)};
  } else if (status.complete()) {  // every file says why it ended, a complete one too
    status.reason = fmt::format("all {} frames simulated (t = 0 .. {:.4g} s), {} written", frames,
                                (frames - 1) / scene.fps, writer.frames_written());
    if (resuming)
      status.reason +=
          fmt::format("; frames {} on by run --resume of {}", first_frame, options.resume_input);
  }
  // The state the run ends in, when it ended at a whole frame.
  if (scene.output.checkpoint && !refining && !cut_short && !out_of_room && !status.diverged()) {
    const sim::SimulationState end = simulation->state();
    if (end.frame >= first_frame)  // else the checkpoint copied from the resumed file stands
      writer.write_checkpoint(
          checkpoint_of(end, writer.frames_written(), scene.output.dense ? 0 : end.frame + 1));
  }
  writer.finish(status);

  // The file's own figure (what `info` prints): the mean wall time of a
  // written frame after the first (frame 0 is the initial state and the file's creation).
  const double ms_per_frame = writer.ms_per_frame();
  // Rendered from the file, as `flag-sim render` would: the camera frames the
  // whole run, and the renderer never reaches into the simulation.
  std::string rendered;
  if (render_plan && !status.interrupted() && writer.frames_written() > 0)
    rendered = render_file(writer.path(), *render_plan);
  if (out_of_room) {
    fmt::print(stderr, "error: {}: {}; the {} frames written are kept\n", writer.path(),
               status.reason, writer.frames_written());
    return int(ExitCode::kIoFailure);
  }
  if (refined) {  // the file keeps the run's status; refine itself succeeded
    if (!options.summary) return 0;
    fmt::print("refined: {} of {} x {} nodes from {}, {:.2f} ms/frame (the run: {}) -> {}\n",
               counted(writer.frames_written(), "frame"), lattice.rows, lattice.cols,
               options.refine_input, ms_per_frame, to_string(status.state), writer.path());
    if (!rendered.empty()) fmt::print("{}\n", rendered);
    return 0;
  }
  if (status.diverged()) {
    fmt::print(stderr, "error: simulation diverged {}; {} good frames kept in {}\n", status.reason,
               writer.frames_written(), writer.path());
    if (!rendered.empty()) fmt::print("{}\n", rendered);
    return int(status.exit_code());
  }
  fmt::print("{}: {} of {} x {} nodes ({}), {:.2f} ms/frame, {}, max strain {:.3f}% -> {}\n",
             to_string(status.state), counted(writer.frames_written(), "frame"), lattice.rows,
             lattice.cols, to_string(scene.mode), ms_per_frame, simulation->stepping_summary(),
             100.0 * max_strain_seen, writer.path());
  for (const std::string& note : scene.notes) fmt::print("{}\n", note);
  if (!scene.output.dense)
    fmt::print(
        "note: output.dense = false: {} keeps the coarse trajectory, not the dense frames; "
        "`flag-sim refine {} -o DENSE.h5` recomputes them\n",
        writer.path(), writer.path());
  if (auto note = sim::wrinkle_resolution_note(scene)) fmt::print("{}\n", *note);
  if (unconverged_frames > 0 && worst_residual > 0.0)
    fmt::print(
        "note: the infill did not reach its tolerance in {} of {} frames (worst link {:.3f}% "
        "beyond it; /stats/infill_converged)\n",
        unconverged_frames, writer.frames_written(), 100.0 * worst_residual);
  else if (unconverged_frames > 0)  // stopped at a cap, every link within the tolerance anyway
    fmt::print(
        "note: the infill stopped at its cap in {} of {} frames (3.4's infill.relax_iterations "
        "passes, or 3.1's steps), yet every link ended within its tolerance: "
        "/stats/infill_converged marks those frames 0, /stats/infill_residual is 0 there\n",
        unconverged_frames, writer.frames_written());
  if (!rendered.empty()) fmt::print("{}\n", rendered);
  return int(status.exit_code());
}

}  // namespace flagsim::app
