#pragma once
// What a run file keeps to be continued (`flag-sim run --resume`): the whole
// simulation state after one frame, in float64 as the simulation holds it, and
// how far the file's frames had come when it was taken.
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

namespace flagsim::data {

/// /checkpoint in an output file. Each part is a float64 [n] dataset of that
/// name; the counts are root attributes of the group.
struct Checkpoint {
  struct Part {
    std::string name;
    std::span<const double> view;    ///< to write: a view of the simulation's own state
    std::string units;               ///< its dataset's `units`
    std::vector<double> owned = {};  ///< what a reader read (no view into it: copies stay safe)
    std::span<const double> values() const { return view.data() ? view : std::span(owned); }
  };
  int frame = 0;              ///< the simulated frame the state is at (t = frame / fps)
  int written_frames = 0;     ///< /frames/time's length then (this frame's row included)
  int trajectory_frames = 0;  ///< /coarse/trajectory's length then (0 in a dense file)
  std::vector<Part> parts;

  /// The part named `name`, or nullptr.
  const Part* part(const std::string& name) const {
    for (const Part& p : parts)
      if (p.name == name) return &p;
    return nullptr;
  }
};

/// The checksum each part's dataset carries (attribute `checksum`): FNV-1a
/// over its values' 64-bit words. A checkpoint whose bits changed is refused,
/// not continued into a run that blows up or, worse, does not.
inline std::uint64_t checkpoint_checksum(std::span<const double> values) {
  std::uint64_t hash = 14695981039346656037ull;
  for (const double value : values) {
    std::uint64_t word = 0;
    std::memcpy(&word, &value, sizeof word);
    hash = (hash ^ word) * 1099511628211ull;
  }
  return hash;
}

}  // namespace flagsim::data
