#include "frame_range.hpp"

#include <fmt/format.h>

#include <regex>

#include "flagsim/core/errors.hpp"
#include "flagsim/core/message.hpp"

namespace flagsim::app {

std::pair<int, int> parse_frame_range(const std::string& text) {
  static const std::regex pattern(R"(^\s*(\d{0,9})\s*:\s*(\d{0,9})\s*$)");
  std::smatch match;
  if (!std::regex_match(text, match, pattern))
    throw UserError(fmt::format(
        "--frames {}: expected A:B (frames A to B - 1, e.g. 0:30, 10:, :20)", printable(text)));
  const int first = match[1].length() ? std::stoi(match[1]) : 0;
  const int last = match[2].length() ? std::stoi(match[2]) : -1;
  if (last >= 0 && last <= first)
    throw UserError(
        fmt::format("--frames {}: the range is empty (B must be more than A)", printable(text)));
  return {first, last};
}

std::pair<int, int> resolve_frame_range(std::pair<int, int> range, int frames,
                                        const std::string& file) {
  const int first = range.first, last = range.second < 0 ? frames : range.second;
  if (first >= frames || last > frames)
    throw UserError(fmt::format("--frames {}:{}: {} has frames 0 to {}", first,
                                range.second < 0 ? std::string() : std::to_string(last), file,
                                frames - 1));
  return {first, last};
}

}  // namespace flagsim::app
