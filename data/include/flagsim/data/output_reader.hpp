#pragma once
// Reads a flag-sim output file back (for `flag-sim info`, tests and, later,
// rendering). Foreign or unreadable files are the user's to fix: UserError.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "flagsim/core/vec3.hpp"
#include "flagsim/data/checkpoint.hpp"

namespace flagsim::data {

class OutputReader {
 public:
  /// Opens `path` read-only. Throws UserError if it is missing, not HDF5, or
  /// not a flag-sim file (root attribute format = "flag-sim/1").
  explicit OutputReader(const std::string& path);
  ~OutputReader();
  OutputReader(const OutputReader&) = delete;
  OutputReader& operator=(const OutputReader&) = delete;

  /// A string root attribute ("" if absent).
  std::string attribute(const char* name) const;
  /// A numeric root attribute, or `fallback`.
  double number_attribute(const char* name, double fallback) const;
  long long seed() const;

  int rows() const { return rows_; }
  int cols() const { return cols_; }
  int frame_count() const { return frames_; }
  /// false for a file of [output] dense = false: no dense frames (positions()
  /// and the per-node fields throw), the coarse trajectory instead.
  bool dense() const { return dense_; }
  /// Frames in /coarse/trajectory (every simulated frame); 0 in a dense file.
  int trajectory_frames() const { return trajectory_frames_; }
  /// The coarse nodes the infill took at simulated frame n, [Jc*Kc] m, float64
  /// as stored; empty past the trajectory.
  std::vector<Vec3> coarse_trajectory(int frame) const;
  /// What the coarse physics remembered at simulated frame n (the creases'
  /// angles, /coarse/memory); empty past the trajectory or in a file without
  /// it (no creases, or written before it was kept).
  std::vector<double> coarse_memory(int frame) const;

  std::vector<double> times_s() const;
  /// Positions of frame t, [J*K] m (stored as float32).
  std::vector<Vec3> positions(int frame) const;
  /// Velocities of frame t, [J*K] m/s; empty in files written before /frames/velocity.
  std::vector<Vec3> velocities(int frame) const;
  /// Each node's largest link strain in frame t, [J*K]; empty in files written before
  /// /frames/strain.
  std::vector<double> node_strain(int frame) const;
  std::vector<Vec3> rest_positions() const;
  /// Hybrid runs: positions of the coarse nodes at frame t [Jc*Kc] and their
  /// dense rows / columns; empty when the file has no /coarse group.
  std::vector<Vec3> coarse_positions(int frame) const;
  std::vector<int> coarse_rows() const;
  std::vector<int> coarse_cols() const;
  /// A [T] float series under /stats ("max_strain", "wall_seconds", ...).
  std::vector<double> stat(const char* name) const;
  /// /stats/stage_seconds as [T][S], and the stage names.
  std::vector<std::vector<double>> stage_seconds() const;
  std::vector<std::string> stage_names() const;
  /// /checkpoint (FrameWriter::write_checkpoint), or nullopt in a file without
  /// one. Throws UserError when it is there but damaged.
  std::optional<Checkpoint> checkpoint() const;

  /// Makes the reads `info`, `render`, `export` and the others make (every
  /// attribute and series they read, the first and last frame): the test read
  /// a child runs before the file is opened here (isolated_read.hpp).
  void read_what_commands_read() const;

 private:
  /// One frame of a per-node field under /frames ([T, J, K] for 1 component,
  /// [T, J, K, components] otherwise), shape checked first; empty when absent.
  std::vector<double> frame_field(const char* name, int frame, int components) const;
  /// One frame [Jc*Kc] of a /coarse series ([T, Jc, Kc, 3]), shape checked; empty when absent
  /// or past its end.
  std::vector<Vec3> coarse_frame(const char* name, int frame) const;
  void open_coarse_only();

  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string path_;
  int rows_ = 0, cols_ = 0, frames_ = 0, trajectory_frames_ = 0;
  bool dense_ = true;
};

}  // namespace flagsim::data
