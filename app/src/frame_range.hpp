#pragma once
// `--frames A:B` of the commands that read an output file (render, export).
#include <string>
#include <utility>

namespace flagsim::app {

/// Frames A .. B - 1 as Python reads a slice ("0:30", "10:", ":20"), 0-based as
/// numbered in the file; B = -1: to the end. Throws UserError naming the flag.
std::pair<int, int> parse_frame_range(const std::string& text);

/// The range against a file of `frames` frames: [first, last) with last
/// resolved; throws UserError when it reaches past the file.
std::pair<int, int> resolve_frame_range(std::pair<int, int> range, int frames,
                                        const std::string& file);

}  // namespace flagsim::app
