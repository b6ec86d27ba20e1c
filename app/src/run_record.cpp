#include "run_record.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string_view>
#include <tuple>

#include "flagsim/coarse_physics/spring_damper.hpp"
#include "flagsim/core/errors.hpp"
#include "flagsim/core/stage_times.hpp"
#include "flagsim/sim/divergence.hpp"
#include "flagsim/sim/frame_runner.hpp"
#include "flagsim/sim/simulation.hpp"
#include "progress.hpp"

namespace flagsim::app {
namespace fs = std::filesystem;
namespace {

// Adds a frame's stage times to the record's sums (frame 0 has none).
void add_times(RunRecord& record, const StageTimes& times) {
  for (std::size_t s = 0; s < times.names().size(); ++s) {
    const double ms = 1e3 * times.seconds()[s];
    record.ms_per_frame += ms;
    (times.groups()[s] == StageGroup::kInfill ? record.infill_ms : record.physics_ms) += ms;
  }
}

void average_times(RunRecord& record) {
  const double n = std::max<double>(1.0, double(record.frames.size()) - 1.0);
  record.ms_per_frame /= n;
  record.physics_ms /= n;
  record.infill_ms /= n;
}

// A run's frames into its record, with each frame's stage times.
class RecordSink final : public sim::FrameSink {
 public:
  RecordSink(RunRecord& record, StageTimes& times) : record_(record), times_(times) {}
  bool take(const sim::Simulation& simulation, const sim::CheckedFrame& frame) override {
    if (frame.index > 0) add_times(record_, times_);
    times_.reset();
    record_.frames.emplace_back(simulation.positions().begin(), simulation.positions().end());
    const auto coarse = simulation.coarse_positions();
    if (!coarse.empty()) record_.coarse.emplace_back(coarse.begin(), coarse.end());
    return true;
  }

 private:
  RunRecord& record_;
  StageTimes& times_;
};

// The mass-spring cloth with some nodes driven (compare's tracking run), as a
// Simulation the frame loop can step: the driven nodes go where the hybrid's
// coarse nodes went, every other node under the scene's forces.
class TrackingSimulation final : public sim::Simulation {
 public:
  TrackingSimulation(const Scene& full, const RunRecord& hybrid)
      : solver_(full), state_(solver_.initial_state()) {
    const Lattice& lattice = solver_.model().lattice;
    // Coarse node c sits at dense (rows[c / Kc], cols[c % Kc]).
    std::vector<std::size_t> nodes;
    for (int jr : hybrid.coarse_rows)
      for (int kc : hybrid.coarse_cols) nodes.push_back(lattice.index(jr, kc));
    const double fps = full.fps;
    const int last = int(hybrid.coarse.size()) - 1;
    solver_.drive(nodes, [&hybrid, fps, last](std::size_t which, double t) {
      const double f = std::clamp(t * fps, 0.0, double(last));
      const int a = std::min(int(f), std::max(last - 1, 0)), b = std::min(a + 1, last);
      const double w = f - a;
      return Vec3((1.0 - w) * hybrid.coarse[std::size_t(a)][which] +
                  w * hybrid.coarse[std::size_t(b)][which]);
    });
    // The start is the hybrid's frame 0 (its coarse nodes, with their slack,
    // and the infill between them), at rest.
    state_.x_m = hybrid.frames[0];
    std::fill(state_.v_m_s.begin(), state_.v_m_s.end(), Vec3::Zero());
  }
  const Lattice& lattice() const override { return solver_.model().lattice; }
  std::vector<std::string> effects() const override { return solver_.effects(); }
  std::vector<NamedNumber> numbers() const override {
    return {{"substeps_per_frame", double(solver_.substeps_per_frame()), "1", true}};
  }
  void register_stages(StageTimes& times) override { solver_.register_stages(times); }
  void advance_frame(StageTimes* times) override {
    solver_.advance_frame(state_, times);
    ++frame_;
  }
  std::span<const Vec3> positions() const override { return state_.x_m; }
  std::span<const Vec3> velocities() const override { return state_.v_m_s; }
  double kinetic_energy_j() const override { return solver_.kinetic_energy(state_); }
  std::string stepping_summary() const override {
    return fmt::format("{} substeps/frame, driven", solver_.substeps_per_frame());
  }
  sim::SimulationState state() const override { return {frame_, state_, {}, {}, {}, {}}; }
  void set_state(const sim::SimulationState& state) override {
    if (state.physics.x_m.size() != state_.x_m.size() ||
        state.physics.v_m_s.size() != state_.v_m_s.size())
      throw UserError("set_state: the tracking run's state has another size");
    state_ = state.physics;
    frame_ = state.frame;
  }

 private:
  physics::SpringDamperSolver solver_;
  physics::ClothState state_;
  int frame_ = 0;
};

// The frames of `simulation` for `scene` into a record (with the lattice, the
// coarse nodes' places and the stepping), through the frame loop.
void record_frames(sim::Simulation& simulation, const Scene& scene, int frames, RunRecord& record,
                   Progress* progress) {
  record.lattice = simulation.lattice();
  record.fps = scene.fps;
  std::tie(record.coarse_rows, record.coarse_cols) = simulation.coarse_indices();
  for (const NamedNumber& number : simulation.numbers())
    if (number.name == "substeps_per_frame") record.substeps_per_frame = int(number.value);
  StageTimes times;
  simulation.register_stages(times);
  RecordSink sink(record, times);
  std::vector<sim::FrameSink*> sinks = {&sink};
  if (progress) sinks.push_back(progress);
  const sim::FrameRunResult result = sim::run_frames(simulation, scene, 0, frames, sinks, {&times});
  if (progress) progress->done();
  switch (result.end) {
    case sim::FrameRunEnd::kInterruptedDuring:
    case sim::FrameRunEnd::kInterruptedAfter:  // the run is not finished: a record of it
                                               // would measure something else
      throw Interrupted(fmt::format("stopped by a signal in frame {} of {} of scene \"{}\"",
                                    result.frame, frames, scene.name));
    case sim::FrameRunEnd::kDiverged:
      record.status = {RunState::kDiverged,
                       fmt::format("at t = {:.4g} s (frame {}): {}", result.frame / scene.fps,
                                   result.frame, describe(*result.divergence, scene))};
      break;
    case sim::FrameRunEnd::kComplete:
    case sim::FrameRunEnd::kStoppedBySink:
      break;
  }
  average_times(record);
}

}  // namespace

RunRecord record_run(const Scene& scene, Progress* progress) {
  const std::unique_ptr<sim::Simulation> simulation = sim::make_simulation(scene);
  RunRecord record;
  record.scene_toml = scene.toml_text;
  record_frames(*simulation, scene, scene.simulated_frames(), record, progress);
  return record;
}

RunRecord record_tracking(const Scene& scene, const RunRecord& hybrid, Progress* progress) {
  const Scene full = in_mode(scene, Mode::kMassSpring);
  TrackingSimulation simulation(full, hybrid);
  RunRecord record;
  record_frames(simulation, full, int(hybrid.frames.size()), record, progress);
  return record;
}

namespace {

constexpr char kRecordMagic[16] = "flag-sim-rec-03";  // with its NUL: 16 bytes

// Plain little-endian bytes of the host (x86-64, as the rest of flag-sim's binary I/O).
class RecordOut {
 public:
  explicit RecordOut(const std::string& path) : out_(path, std::ios::binary | std::ios::trunc) {}
  template <typename T>
  void put(const T& value) {
    out_.write(reinterpret_cast<const char*>(&value), sizeof value);
  }
  void put_string(const std::string& text) {
    put<std::uint64_t>(text.size());
    out_.write(text.data(), std::streamsize(text.size()));
  }
  void put_frames(const analysis::Frames& frames) {
    put<std::uint64_t>(frames.size());
    for (const std::vector<Vec3>& frame : frames) {
      put<std::uint64_t>(frame.size());
      out_.write(reinterpret_cast<const char*>(frame.data()),
                 std::streamsize(frame.size() * sizeof(Vec3)));
    }
  }
  void put_ints(const std::vector<int>& values) {
    put<std::uint64_t>(values.size());
    for (int v : values) put<std::int32_t>(v);
  }
  bool close() {
    out_.close();
    return bool(out_);
  }

 private:
  std::ofstream out_;
};

class RecordIn {
 public:
  RecordIn(const std::string& path, std::uintmax_t size)
      : in_(path, std::ios::binary), path_(path), left_(size) {}
  bool good() const { return bool(in_); }
  template <typename T>
  T get() {
    T value{};
    read(&value, sizeof value);
    return value;
  }
  std::string get_string() {
    std::string text(count(1), '\0');
    read(text.data(), text.size());
    return text;
  }
  analysis::Frames get_frames() {
    analysis::Frames frames(count(sizeof(std::uint64_t)));
    for (std::vector<Vec3>& frame : frames) {
      frame.resize(count(sizeof(Vec3)));
      read(frame.data(), frame.size() * sizeof(Vec3));
    }
    return frames;
  }
  std::vector<int> get_ints() {
    std::vector<int> values(count(sizeof(std::int32_t)));
    for (int& v : values) v = get<std::int32_t>();
    return values;
  }
  bool at_end() const { return left_ == 0; }

 private:
  // A count of items of `item_bytes` each, never more than the file still holds.
  std::size_t count(std::size_t item_bytes) {
    const auto n = get<std::uint64_t>();
    if (n > left_ / item_bytes) fail();
    return std::size_t(n);
  }
  void read(void* into, std::size_t bytes) {
    if (bytes > left_ || !in_.read(static_cast<char*>(into), std::streamsize(bytes))) fail();
    left_ -= bytes;
  }
  [[noreturn]] void fail() const {
    throw UserError(fmt::format("{}: not a whole flag-sim run record", path_));
  }
  std::ifstream in_;
  std::string path_;
  std::uintmax_t left_;
};

}  // namespace

void save_record(const RunRecord& record, const std::string& path) {
  const std::string partial = path + ".partial";
  RecordOut out(partial);
  out.put(kRecordMagic);
  const Lattice& l = record.lattice;
  out.put<std::int32_t>(l.rows);
  out.put<std::int32_t>(l.cols);
  out.put(l.spacing_x_m);
  out.put(l.spacing_y_m);
  for (int c = 0; c < 3; ++c) out.put(l.origin_m[c]);
  out.put(record.fps);
  out.put<std::int32_t>(record.substeps_per_frame);
  out.put(record.ms_per_frame);
  out.put(record.physics_ms);
  out.put(record.infill_ms);
  out.put<std::int32_t>(std::int32_t(record.status.state));
  out.put_string(record.status.reason);
  out.put_string(record.scene_toml);
  out.put_ints(record.coarse_rows);
  out.put_ints(record.coarse_cols);
  out.put_frames(record.frames);
  out.put_frames(record.coarse);
  std::error_code ec;
  if (!out.close()) {
    fs::remove(partial, ec);
    throw IoError(fmt::format("{}: writing the run record failed (disk full?)", partial));
  }
  fs::rename(partial, path, ec);
  if (ec) throw IoError(fmt::format("{}: cannot rename to {}: {}", partial, path, ec.message()));
}

RunRecord load_record(const std::string& path) {
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  RecordIn in(path, ec ? 0 : size);
  if (ec || !in.good()) throw UserError(fmt::format("{}: cannot read the run record", path));
  const auto magic = in.get<std::array<char, 16>>();
  if (std::string_view(magic.data(), 16) != std::string_view(kRecordMagic, sizeof kRecordMagic))
    throw UserError(fmt::format("{}: not a flag-sim run record", path));
  RunRecord record;
  Lattice& l = record.lattice;
  l.rows = in.get<std::int32_t>();
  l.cols = in.get<std::int32_t>();
  l.spacing_x_m = in.get<double>();
  l.spacing_y_m = in.get<double>();
  for (int c = 0; c < 3; ++c) l.origin_m[c] = in.get<double>();
  record.fps = in.get<double>();
  record.substeps_per_frame = in.get<std::int32_t>();
  record.ms_per_frame = in.get<double>();
  record.physics_ms = in.get<double>();
  record.infill_ms = in.get<double>();
  const auto state = in.get<std::int32_t>();
  if (state < int(RunState::kRunning) || state > int(RunState::kInterrupted))
    throw UserError(fmt::format("{}: not a whole flag-sim run record", path));
  record.status.state = RunState(state);
  record.status.reason = in.get_string();
  record.scene_toml = in.get_string();
  record.coarse_rows = in.get_ints();
  record.coarse_cols = in.get_ints();
  record.frames = in.get_frames();
  record.coarse = in.get_frames();
  const bool shaped = l.rows >= 2 && l.cols >= 2 &&
                      std::all_of(record.frames.begin(), record.frames.end(),
                                  [&](const auto& f) { return f.size() == l.node_count(); });
  if (!in.at_end() || !shaped)
    throw UserError(fmt::format("{}: not a whole flag-sim run record", path));
  return record;
}

}  // namespace flagsim::app
