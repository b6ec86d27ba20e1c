#pragma once
// Four doubles side by side, for the loops that compute many independent
// values with the same arithmetic (fibers, triangles, links): GCC's vector
// extension, two SSE2 registers on any x86-64, one AVX register in a function
// cloned for AVX2 (FLAGSIM_LANES_CLONES below), picked at run time. Element-wise IEEE operations
// only, no fused multiply-add: the same bits on either path, and the same bits as the same
// operations on one double at a time.
//
// The helpers are always inlined: left out of line, one would run the default
// target's code (two SSE2 halves) inside an AVX2 clone, and pass its vectors
// through memory. A source using them ignores -Wpsabi (lanes are passed by
// value only between inlined helpers, never across an ABI boundary).
#include <cstddef>
#include <span>
#include <vector>

#include "flagsim/core/vec3.hpp"

// Put before a function whose loops use lanes: GCC builds it twice, for AVX2
// and for any x86-64, and picks one at run time. Clang (the fuzz build) gets
// the one plain build: clang 14 rejects an always-inlined helper taking or
// returning lanes inside an AVX2 clone (err_avx_calling_convention, although
// the call is inlined), and the arithmetic is element-wise IEEE either way, so
// the same bits.
#if defined(__clang__)
#define FLAGSIM_LANES_CLONES
#else
#define FLAGSIM_LANES_CLONES __attribute__((target_clones("avx2", "default")))
#endif

namespace flagsim::lanes {

inline constexpr int kWidth = 4;
using Lanes = double __attribute__((vector_size(kWidth * sizeof(double))));
static_assert(sizeof(Lanes) == kWidth * sizeof(double));

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
/// kWidth doubles from `p` (any alignment).
[[gnu::always_inline]] inline Lanes load(const double* p) {
  Lanes v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
/// kWidth doubles to `p` (any alignment).
[[gnu::always_inline]] inline void store(double* p, Lanes v) {
  __builtin_memcpy(p, &v, sizeof v);
}
/// `value` in every lane.
[[gnu::always_inline]] inline Lanes splat(double value) {
  return Lanes{} + value;
}
/// The x, y and z of the kWidth vectors from `v` on, one coordinate a vector.
[[gnu::always_inline]] inline void gather(const Vec3* v, Lanes& x, Lanes& y, Lanes& z) {
  for (int l = 0; l < kWidth; ++l) {
    x[l] = v[l].x();
    y[l] = v[l].y();
    z[l] = v[l].z();
  }
}
/// |v[l]|^2 for the kWidth vectors from `v` on: the operations of
/// Vec3::squaredNorm in its order, so the same bits.
[[gnu::always_inline]] inline Lanes squared_norms(const Vec3* v) {
  Lanes x, y, z;
  gather(v, x, y, z);
  return x * x + y * y + z * z;
}
/// |next[l] - here[l]|^2 for the kWidth links from here[l] to next[l]: the
/// operations of (next - here).squaredNorm() in their order, so the same bits.
[[gnu::always_inline]] inline Lanes squared_lengths(const Vec3* here, const Vec3* next) {
  Lanes hx, hy, hz, nx, ny, nz;
  gather(here, hx, hy, hz);
  gather(next, nx, ny, nz);
  const Lanes dx = nx - hx, dy = ny - hy, dz = nz - hz;
  return dx * dx + dy * dy + dz * dz;
}
#pragma GCC diagnostic pop

/// `from`'s x, y and z into one array each (the loops above read a coordinate
/// of consecutive nodes); `to` holds at least from.size() values per coordinate.
inline void split(std::span<const Vec3> from, std::vector<double> (&to)[3]) {
  for (std::size_t i = 0; i < from.size(); ++i)
    for (int axis = 0; axis < 3; ++axis) to[axis][i] = from[i][axis];
}
/// The arrays back into `to`, node by node.
inline void join(const std::vector<double> (&from)[3], std::span<Vec3> to) {
  for (std::size_t i = 0; i < to.size(); ++i) to[i] = Vec3(from[0][i], from[1][i], from[2][i]);
}

}  // namespace flagsim::lanes
