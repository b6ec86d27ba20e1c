#pragma once
// Small fibers for the infill step tests.
#include <vector>

#include "flagsim/core/vec3.hpp"

namespace flagsim::infill::test {

/// A straight fiber of `segments` segments of 0.1 m along x, from the origin.
inline std::vector<Vec3> straight(int segments = 8) {
  std::vector<Vec3> x;
  for (int i = 0; i <= segments; ++i) x.emplace_back(0.1 * i, 0.0, 0.0);
  return x;
}

}  // namespace flagsim::infill::test
