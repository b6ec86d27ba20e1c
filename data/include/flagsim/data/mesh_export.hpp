#pragma once
// The dense lattice in the formats DCC tools read (`flag-sim export`):
// Blender's point cache PC2 (Mesh Cache modifier) for the motion, and
// Wavefront OBJ for the topology (quads, UVs, vertex normals).
//
// Coordinates are flag-sim's own: metres, y up (the pole along y). Blender's
// OBJ importer and Mesh Cache modifier both take Y as up when told so (their
// defaults: Forward -Z, Up Y for OBJ; set the modifier's axes to match).
#include <cstdint>
#include <cstdio>
#include <span>
#include <string>

#include "flagsim/core/vec3.hpp"

namespace flagsim::data {

/// PC2 ("POINTCACHE2\0" header, little-endian): char[12] signature, int32
/// version 1, int32 points, float32 start frame, float32 sample rate (frames
/// between samples), int32 samples; then samples x points x float32 xyz.
inline constexpr char kPc2Signature[12] = {'P', 'O', 'I', 'N', 'T', 'C',
                                           'A', 'C', 'H', 'E', '2', '\0'};
inline constexpr std::size_t kPc2HeaderBytes = 32;

class Pc2Writer {
 public:
  /// Creates (truncates) `path` and writes the header of `samples` samples of
  /// `points` points. Throws IoError when the file cannot be written.
  Pc2Writer(std::string path, int points, int samples, float start_frame, float sample_rate);
  ~Pc2Writer();
  Pc2Writer(const Pc2Writer&) = delete;
  Pc2Writer& operator=(const Pc2Writer&) = delete;

  /// Appends one sample: `positions` [points], m, stored as float32.
  void write_sample(std::span<const Vec3> positions_m);
  /// Closes the file; throws IoError unless every sample the header promised
  /// was written and reached the file.
  void finish();

 private:
  std::string path_;
  std::FILE* file_ = nullptr;
  int points_, samples_, written_ = 0;
};

/// The lattice [rows x cols] at `positions_m` as an OBJ: a vertex per node
/// (row-major, 1-based in the faces), its texture coordinate (u = k / (K - 1)
/// from the pole, v = 1 at the top row to 0 at the bottom), its normal (from
/// its neighbours along both fibers), and a quad per cell, counter-clockwise
/// seen from the side the normals point to. `comment` goes in a leading `#` line.
std::string obj_text(int rows, int cols, std::span<const Vec3> positions_m,
                     const std::string& comment);

}  // namespace flagsim::data
