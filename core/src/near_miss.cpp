#include "flagsim/core/near_miss.hpp"

#include <algorithm>
#include <vector>

namespace flagsim::detail {

int edit_distance(std::string_view a, std::string_view b) {
  // Optimal string alignment: insertions, deletions, substitutions and swaps of
  // two neighbouring letters ("wnid" -> "wind") each cost 1.
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::vector<int>> d(n + 1, std::vector<int>(m + 1, 0));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = int(i);
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = int(j);
  for (std::size_t i = 1; i <= n; ++i) {
    for (std::size_t j = 1; j <= m; ++j) {
      const int cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  }
  return d[n][m];
}

std::string closest_name(std::string_view typed, std::span<const std::string_view> candidates) {
  std::string best;
  int best_distance = 1 << 30;
  for (std::string_view candidate : candidates) {
    int distance = edit_distance(typed, candidate);
    const bool prefix = typed.size() >= 3 && candidate.starts_with(typed);
    if (prefix) distance = std::min(distance, 1);
    if (distance < best_distance) {
      best_distance = distance;
      best = std::string(candidate);
    }
  }
  const int allowed = std::max<int>(1, int(typed.size()) / 3);
  return best_distance <= allowed ? best : std::string();
}

}  // namespace flagsim::detail
