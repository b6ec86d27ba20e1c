#pragma once
// Suggestions for misspelt names ("did you mean ...?").
#include <span>
#include <string>
#include <string_view>

namespace flagsim::detail {

/// Edit distance (Levenshtein plus swaps of neighbouring letters) of two ASCII strings.
int edit_distance(std::string_view a, std::string_view b);

/// The candidate closest to `typed`, if it is close enough to be a plausible
/// typo (edit distance <= 1/3 of the length, at least 1, or a prefix); else "".
std::string closest_name(std::string_view typed, std::span<const std::string_view> candidates);

}  // namespace flagsim::detail
