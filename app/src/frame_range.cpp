#include "frame_range.hpp"

#include <fmt/format.h>

#include <regex>

#include "flagsim/core/errors.hpp"
#include "flagsim/core/message.hpp"

namespace flagsim::app {
namespace {

// The range as the user could have typed it.
std::string text_of(std::pair<int, int> range) {
  if (range.second != kToEnd && range.second == range.first + 1 && range.first >= 0)
    return std::to_string(range.first);
  return fmt::format("{}:{}", range.first,
                     range.second == kToEnd ? std::string() : std::to_string(range.second));
}

}  // namespace

std::pair<int, int> parse_frame_range(const std::string& text) {
  static const std::regex slice(R"(^\s*(-?\d{1,9})?\s*:\s*(-?\d{1,9})?\s*$)");
  static const std::regex index(R"(^\s*(-?\d{1,9})\s*$)");
  std::smatch match;
  if (std::regex_match(text, match, index)) {  // one frame, as a[N]
    const int n = std::stoi(match[1]);
    return {n, n == -1 ? kToEnd : n + 1};
  }
  if (!std::regex_match(text, match, slice))
    throw UserError(fmt::format(
        "--frames {}: expected N (one frame; -1 the last) or A:B (frames A to B - 1, e.g. 0:30, "
        "10:, :20, -10:)",
        printable(text)));
  const int first = match[1].matched ? std::stoi(match[1]) : 0;
  const int last = match[2].matched ? std::stoi(match[2]) : kToEnd;
  // Empty whatever the file's length when both count from the same end.
  if (last != kToEnd && (first < 0) == (last < 0) && last <= first)
    throw UserError(
        fmt::format("--frames {}: the range is empty (B must be more than A)", printable(text)));
  return {first, last};
}

std::pair<int, int> resolve_frame_range(std::pair<int, int> range, int frames,
                                        const std::string& file) {
  const int first = range.first < 0 ? range.first + frames : range.first;
  const int last = range.second == kToEnd ? frames
                   : range.second < 0     ? range.second + frames
                                          : range.second;
  if (first < 0 || first >= frames || last > frames || last <= first)
    throw UserError(fmt::format("--frames {}: {} has frames 0 to {}{}", text_of(range), file,
                                frames - 1, last <= first ? " (the range holds none)" : ""));
  return {first, last};
}

}  // namespace flagsim::app
