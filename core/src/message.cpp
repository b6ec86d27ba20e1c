#include "flagsim/core/message.hpp"

#include <fmt/format.h>

namespace flagsim {

std::string printable(const std::string& text, std::size_t limit) {
  std::string out;
  for (unsigned char c : text.substr(0, limit))
    out += c < 0x20 || c == 0x7f ? fmt::format("\\x{:02x}", c) : std::string(1, char(c));
  return text.size() > limit ? out + "..." : out;
}

namespace {

// The length of the UTF-8 sequence at text[i] (1 to 4), or 0 when it is not one.
std::size_t utf8_length(const std::string& text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return (unsigned char)text[k]; };
  const unsigned char c = byte(i);
  if (c < 0x80) return 1;
  std::size_t n = 0;
  unsigned int low = 0;  // the smallest code point of that length (no overlong forms)
  unsigned int code = 0;
  if ((c & 0xe0) == 0xc0) {
    n = 2, low = 0x80, code = c & 0x1fu;
  } else if ((c & 0xf0) == 0xe0) {
    n = 3, low = 0x800, code = c & 0x0fu;
  } else if ((c & 0xf8) == 0xf0) {
    n = 4, low = 0x10000, code = c & 0x07u;
  } else {
    return 0;
  }
  if (i + n > text.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    if ((byte(i + k) & 0xc0) != 0x80) return 0;
    code = (code << 6) | (byte(i + k) & 0x3fu);
  }
  if (code < low || code > 0x10ffff || (code >= 0xd800 && code <= 0xdfff)) return 0;
  return n;
}

}  // namespace

std::string valid_utf8(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = utf8_length(text, i);
    if (n == 0) {
      out += "\xef\xbf\xbd";  // U+FFFD
      ++i;
    } else {
      out.append(text, i, n);
      i += n;
    }
  }
  return out;
}

std::string terminal_safe(const std::string& text) {
  const std::string valid = valid_utf8(text);
  std::string out;
  for (std::size_t i = 0; i < valid.size(); ++i) {
    const unsigned char c = (unsigned char)valid[i];
    if (c < 0x20 || c == 0x7f) {
      out += fmt::format("\\x{:02x}", c);
    } else if (c == 0xc2 && i + 1 < valid.size() && (unsigned char)valid[i + 1] < 0xa0) {
      out += fmt::format("\\u{:04x}", (unsigned char)valid[i + 1]);  // C1: U+0080 .. U+009F
      ++i;
    } else {
      out += char(c);
    }
  }
  return out;
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

std::string counted(long long count, const std::string& noun) {
  return std::to_string(count) + " " + noun + (count == 1 ? "" : "s");
}

}  // namespace flagsim
