#include "flagsim/core/message.hpp"

#include <fmt/format.h>

namespace flagsim {

std::string printable(const std::string& text, std::size_t limit) {
  std::string out;
  for (unsigned char c : text.substr(0, limit))
    out += c < 0x20 || c == 0x7f ? fmt::format("\\x{:02x}", c) : std::string(1, char(c));
  return text.size() > limit ? out + "..." : out;
}

std::string one_line(const std::string& message, std::size_t limit) {
  std::string line;
  bool after_break = false;
  for (const unsigned char c : message) {
    if (c == '\n' || c == '\r') {
      after_break = true;
      continue;
    }
    if (after_break) {
      after_break = false;
      if (c == ' ' || c == '\t') {
        after_break = true;  // the indentation of the next line
        continue;
      }
      if (!line.empty() && line.back() != ' ') line += ' ';
    }
    if (line.size() >= limit) return line + "...";
    line += c < 0x20 || c == 0x7f ? fmt::format("\\x{:02x}", c) : std::string(1, char(c));
  }
  return line;
}

}  // namespace flagsim
