#pragma once
// Writes a run to HDF5 (contract: "Output file", format flag-sim/1).
//
// The file is created as OUT.h5.partial with status "running", one frame
// appended at a time (datasets grow along their first axis), flushed to disk
// every `flush_every` frames so that a killed run leaves a file readable up to
// the last flush, and renamed to OUT.h5 by finish(), which also writes the
// XDMF sidecar OUT.xdmf for ParaView.
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "flagsim/core/lattice.hpp"
#include "flagsim/core/named_number.hpp"
#include "flagsim/core/run_status.hpp"
#include "flagsim/data/checkpoint.hpp"

namespace flagsim::data {

inline constexpr const char* kFormat = "flag-sim/1";

/// Root attributes describing the run.
struct RunInfo {
  std::string mode;
  std::vector<std::string> effects;  ///< in pipeline order
  std::string scene_toml;            ///< the scene as run
  std::string version;
  std::uint64_t seed = 0;
  std::vector<std::string> stages;  ///< columns of /stats/stage_seconds
  /// Column of `stages` that receives the time write_frame() itself takes
  /// (positions and time), or -1.
  int output_stage = -1;
  /// Dense row / column index of each coarse row / column (hybrid mode); empty:
  /// no /coarse group.
  std::vector<int> coarse_rows, coarse_cols;
  /// Further numeric root attributes (substep_seconds, ...), each with a
  /// string root attribute NAME.units (HDF5 attributes carry no attributes).
  std::vector<NamedNumber> numbers;
  /// Further per-frame statistics, float64 [T] under /stats/NAME with attribute
  /// `units`: the stage's own (infill_converged, ...), in FrameStats::series order.
  struct Series {
    std::string name, units;
  };
  std::vector<Series> series;
  /// Per-node fields besides the positions ([output] fields): "strain", "velocity".
  std::vector<std::string> fields = {"strain", "velocity"};
  /// false ([output] dense = false, hybrid): no /frames/positions nor per-node
  /// fields, no XDMF; /coarse/trajectory instead (append_trajectory), and the
  /// root attribute `dense` = 0.
  bool dense = true;
  /// Values a simulated frame of the coarse physics remembers besides its
  /// nodes (the creases' rest and held angles, ClothState::memory); with
  /// `dense` false and a non-zero size, /coarse/memory [T, M] float64 beside
  /// /coarse/trajectory, so that refine draws the creases the run had.
  std::size_t coarse_memory_size = 0;
  /// Deflate level 0-9 of the per-node datasets ([output] compression; 0: none).
  int compression = 0;
};

/// Per-frame statistics.
struct FrameStats {
  double max_strain = 0.0;
  double mean_strain = 0.0;
  std::span<const double> stage_seconds;  ///< one per RunInfo::stages
  double wall_seconds = 0.0;  ///< since the last written frame, before this write (added)
  double kinetic_energy_j = 0.0;
  std::span<const double> series;  ///< one per RunInfo::series
};

/// One frame's per-node fields, each [J*K] row-major.
struct FrameFields {
  std::span<const Vec3> positions_m;     ///< /frames/positions, m (empty when not dense)
  std::span<const Vec3> velocities_m_s;  ///< /frames/velocity, m/s (when RunInfo::fields has it)
  std::span<const float> strain;  ///< /frames/strain: each node's largest link strain, 1 (ditto)
  std::span<const Vec3> coarse_m = {};  ///< [Jc*Kc] /coarse/positions, when RunInfo named them
};

class FrameWriter {
 public:
  /// Creates `path`.partial. Throws UserError if it cannot be created (a bad
  /// output path is the user's to fix) - nothing is left behind then.
  FrameWriter(std::string path, const Lattice& lattice, const RunInfo& info, int flush_every);
  ~FrameWriter();
  FrameWriter(const FrameWriter&) = delete;
  FrameWriter& operator=(const FrameWriter&) = delete;

  /// Appends one frame. The time spent writing is added to the output stage's
  /// column of this frame. Throws IoError on failure, std::invalid_argument
  /// when a field's size does not match the lattice (or the coarse layout).
  void write_frame(double time_s, const FrameFields& fields, const FrameStats& stats);
  /// Appends one simulated frame's coarse nodes [Jc*Kc] m, float64 as the infill
  /// took them, to /coarse/trajectory (files with RunInfo::dense false; every
  /// simulated frame, also those output.every leaves out), and the physics'
  /// memory of that frame [RunInfo::coarse_memory_size] to /coarse/memory.
  /// Throws IoError.
  void append_trajectory(std::span<const Vec3> coarse_m, std::span<const double> memory = {});
  /// Sets the root attributes `status` and (when it has one) `status_reason`,
  /// writes the XDMF views, flushes, closes, renames the file to its final
  /// name and writes the XDMF sidecar. Throws IoError.
  void finish(const RunStatus& status);

  /// Says why the next frame should not be written, or nullopt when it may be:
  /// the disk holding the file, or the process's file size limit, has less room
  /// than the frames not yet flushed plus one more, twice, plus 1 MiB for HDF5's
  /// metadata. HDF5 cannot undo a flush that ran out of space half-way (the
  /// file is then unreadable), so the run stops while the file is still whole.
  std::optional<std::string> out_of_room() const;

  /// True when the next write_frame flushes the file to disk (every
  /// `flush_every` frames): the moment to write_checkpoint first, so that the
  /// file a killed run leaves can still be continued.
  bool flushes_next() const { return (frames_ + 1) % flush_every_ == 0; }
  /// Writes /checkpoint, replacing the one before (a part that changed size is
  /// made anew); it reaches the disk with the next flush or finish(). Throws IoError.
  void write_checkpoint(const Checkpoint& checkpoint);
  /// Appends the first `frames` frames of the run file `source` (every dataset
  /// this file has under /frames, /stats and /coarse) and the first
  /// `trajectory_frames` rows of its coarse trajectory, as stored, bit for bit
  /// (`run --resume`). Throws UserError when `source` lacks one of them or holds
  /// it in another shape or type, IoError when writing fails.
  void copy_frames(const std::string& source, int frames, int trajectory_frames);

  /// Closes and removes the .partial file (and the directories the writer made
  /// for it): for a command that fails with nothing to keep (exit 2). The
  /// writer takes no further call.
  void discard() noexcept;

  int frames_written() const { return frames_; }
  /// The mean of /stats/wall_seconds over the written frames after the first
  /// (frame 0 is the initial state), ms: the ms/frame `flag-sim info` reports.
  double ms_per_frame() const {
    return frames_ > 1 ? 1000.0 * wall_after_first_s_ / double(frames_ - 1) : 0.0;
  }
  const std::string& path() const { return path_; }
  std::string partial_path() const { return path_ + ".partial"; }

 private:
  struct Impl;
  bool write_coarse_layout(std::int64_t root, const RunInfo& info);  // root: an hid_t
  std::unique_ptr<Impl> impl_;
  std::string path_;
  Lattice lattice_;
  int flush_every_;
  int frames_ = 0;
  double wall_after_first_s_ = 0.0;  ///< the wall_seconds written after frame 0
  int trajectory_frames_ = 0;
};

/// The XDMF text for the frames of `h5_name` (a path relative to the sidecar)
/// with the given frame times: per time step the geometry and a point array
/// for each of `fields` ("velocity", "strain"), each read from the frame's
/// view (write_xdmf_views).
std::string xdmf_text(const std::string& h5_name, const Lattice& lattice,
                      std::span<const double> times_s, std::span<const std::string> fields);

/// Where one frame's view of /frames/FIELD lies: "/xdmf/FIELD/FRAME".
std::string xdmf_view_path(const char* field, std::size_t frame);

/// Writes, into the open file `file_id` (an hid_t), the group /xdmf: for the
/// positions and each of `fields`, and each of `frames` frames, a virtual
/// dataset [J, K(, 3)] float32 that is that frame of /frames/FIELD. False on failure.
bool write_xdmf_views(std::int64_t file_id, const Lattice& lattice, std::size_t frames,
                      std::span<const std::string> fields);

}  // namespace flagsim::data
