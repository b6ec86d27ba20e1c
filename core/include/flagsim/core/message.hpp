#pragma once
// Text that goes into one line of a message (error:, note:, interrupted:):
// whatever a user gave (a key, a name, a --set value) is quoted without its
// control characters and cut to a sane length.
#include <cstddef>
#include <string>

#include "flagsim/core/limits.hpp"

namespace flagsim {

/// `text` for one line of a message: control characters as \xNN, cut to
/// `limit` bytes with "..." after.
std::string printable(const std::string& text, std::size_t limit = 80);

/// `text` with every byte sequence that is not UTF-8 replaced by U+FFFD:
/// what a file says (a status reason, a stage name) made fit for JSON.
std::string valid_utf8(const std::string& text);

/// `text` fit for a terminal: valid_utf8, and C0/C1 control characters (ESC,
/// CSI, ...) written as \xNN or \u00NN, so a file cannot move the cursor or
/// recolour the screen. Not cut.
std::string terminal_safe(const std::string& text);

/// A whole message as one line: line breaks (and the indentation after them)
/// become one space, other control characters \xNN, and the result is cut to
/// `limit` bytes with "..." after. What the command line prints after "error: ".
std::string one_line(const std::string& message, std::size_t limit = limits::kMessageBytes);

/// "1 frame", "2 frames", "0 frames": a count and its noun, singular only for one.
std::string counted(long long count, const std::string& noun);

}  // namespace flagsim
