#pragma once
// `--frames` of the commands that read an output file (render, export), read
// as Python reads an index or a slice of the file's frames.
#include <limits>
#include <string>
#include <utility>

namespace flagsim::app {

/// The end of a slice left open ("10:"): to the last frame.
inline constexpr int kToEnd = std::numeric_limits<int>::max();
/// Every frame (no --frames).
inline constexpr std::pair<int, int> kAllFrames = {0, kToEnd};

/// Frames A .. B - 1 of "A:B" ("0:30", "10:", ":20", "-10:", ":-1"), or the one
/// frame N of "N" ("100", "-1": the last), 0-based as numbered in the file; a
/// negative index counts from the end. Throws UserError naming the flag.
std::pair<int, int> parse_frame_range(const std::string& text);

/// The range against a file of `frames` frames: [first, last) with negative
/// indices and an open end resolved; throws UserError when it reaches past
/// the file or holds no frame.
std::pair<int, int> resolve_frame_range(std::pair<int, int> range, int frames,
                                        const std::string& file);

}  // namespace flagsim::app
