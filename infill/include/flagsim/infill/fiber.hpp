#pragma once
// A fiber: a straight run of lattice nodes (part of a row or a column), the
// unit the paper's steps work on. Node i of the fiber is positions[first + i * stride].
#include <cstddef>
#include <span>

#include "flagsim/core/vec3.hpp"

namespace flagsim::infill {

struct Fiber {
  std::size_t first = 0;      ///< flat index of node 0
  std::ptrdiff_t stride = 1;  ///< flat index step between nodes (1 along a row, K along a column)
  int segments = 1;           ///< nodes - 1; node 0 and node `segments` are the fiber's ends
  double rest_spacing_m = 0;  ///< S, rest distance of neighbours

  std::size_t node(int i) const { return std::size_t(std::ptrdiff_t(first) + i * stride); }
  double rest_length_m() const { return segments * rest_spacing_m; }
  /// Polyline length through the fiber's nodes, m.
  double length_m(std::span<const Vec3> positions_m) const;
};

}  // namespace flagsim::infill
