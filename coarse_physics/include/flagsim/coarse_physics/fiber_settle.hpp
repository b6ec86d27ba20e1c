#pragma once
// After a projection moved some nodes of a lattice laid anew each frame (the
// infill's dense one: out of a solid, Obstacles::settle; apart from another
// layer, the hybrid's dense self-contact pass), the fibers around the moved
// nodes take their lengths again, so that a push is spread along its fibers
// rather than left in a few links' stretch (issue 31).
//
// The box of nodes within `reach` links of a moved one (a node not where
// `before_m` has it) is relaxed by Gauss-Seidel sweeps over its row and
// column links and the links from outside into it: each link is brought to
// target(a, b, rest_m) (a, b its nodes' indices, rest_m its rest length), the
// box's free nodes moving (relative inverse mass 1), the `fixed` ones (may be
// empty) and those outside the box not (0). Each sweep is followed by
// reproject(ja, jb, ka, kb) over the box and one link around it (rows ja..jb,
// columns ka..kb), which puts back what the sweep undid; at most `rounds`
// sweeps, fewer once reproject returns false.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>

#include "flagsim/core/lattice.hpp"
#include "flagsim/core/vec3.hpp"

namespace flagsim::physics {

template <class Target, class Reproject>
void settle_fibers(const Lattice& lattice, std::span<Vec3> x_m, std::span<const Vec3> before_m,
                   std::span<const std::uint8_t> fixed, int rounds, int reach, Target target,
                   Reproject reproject) {
  const int J = lattice.rows, K = lattice.cols;
  int j0 = J, j1 = -1, k0 = K, k1 = -1;
  for (int j = 0; j < J; ++j) {
    for (int k = 0; k < K; ++k) {
      const std::size_t i = lattice.index(j, k);
      if (x_m[i] == before_m[i]) continue;
      j0 = std::min(j0, j), j1 = std::max(j1, j), k0 = std::min(k0, k), k1 = std::max(k1, k);
    }
  }
  j0 = std::max(0, j0 - reach), j1 = std::min(J - 1, j1 + reach);
  k0 = std::max(0, k0 - reach), k1 = std::min(K - 1, k1 + reach);
  // Inverse masses, relative: the box's free nodes 1, the rest 0.
  const auto w = [&](int j, int k) {
    if (j < j0 || j > j1 || k < k0 || k > k1) return 0.0;
    return fixed.empty() || !fixed[lattice.index(j, k)] ? 1.0 : 0.0;
  };
  const auto fiber = [&](int ja, int ka, int jb, int kb, double rest_m) {
    const double wa = w(ja, ka), wb = w(jb, kb);
    if (wa + wb == 0.0) return;
    const std::size_t a = lattice.index(ja, ka), b = lattice.index(jb, kb);
    const double length_target = target(a, b, rest_m);
    const Vec3 d = x_m[b] - x_m[a];
    const double length = d.norm();
    if (length == 0.0) return;
    const Vec3 correction = (length - length_target) / ((wa + wb) * length) * d;
    x_m[a] += wa * correction;
    x_m[b] -= wb * correction;
  };
  // The box and one link around it (links from a node outside into the box).
  const int ja = std::max(0, j0 - 1), jb = std::min(J - 1, j1 + 1);
  const int ka = std::max(0, k0 - 1), kb = std::min(K - 1, k1 + 1);
  for (int round = 0; round < rounds; ++round) {
    for (int j = ja; j <= jb; ++j) {
      for (int k = ka; k <= kb; ++k) {
        if (k < kb) fiber(j, k, j, k + 1, lattice.spacing_x_m);
        if (j < jb) fiber(j, k, j + 1, k, lattice.spacing_y_m);
      }
    }
    if (!reproject(ja, jb, ka, kb)) break;
  }
}

}  // namespace flagsim::physics
