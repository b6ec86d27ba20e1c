#pragma once
// Self-intersections of a lattice's triangle mesh, for the contact tests
// (issue 31): an exact triangle-triangle test of its own, independent of the
// solver's contact code. The mesh is the lattice's two triangles per cell,
// (j, k)-(j, k+1)-(j+1, k+1) and (j, k)-(j+1, k+1)-(j+1, k), the split the
// renderer and the solver use. Two triangles that share a node are adjacent
// and not tested.
//
// The test is Moeller's (1997, "A fast triangle-triangle intersection test"):
// each triangle's corners against the other's plane (signed distances, exact
// signs where a corner is off the plane by more than a rounding bound), then
// the two intervals the planes' line cuts from the triangles; coplanar pairs
// by edge crossings and containment in their plane. Broad phase: a uniform
// grid of cells the size of the longest triangle edge, each triangle in the
// cells its box touches.
#include <cstddef>
#include <span>
#include <vector>

#include "flagsim/core/lattice.hpp"
#include "flagsim/core/vec3.hpp"

namespace flagsim::testing {

/// Whether triangles (p0, p1, p2) and (q0, q1, q2) intersect (touching counts).
bool triangles_intersect(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& q0,
                         const Vec3& q1, const Vec3& q2);

/// A pair of intersecting triangles: triangle t is cell t / 2 (row-major over
/// the (J-1) x (K-1) cells), half t % 2.
struct TrianglePair {
  std::size_t a = 0, b = 0;
};

/// Every pair of non-adjacent triangles of the lattice's mesh at `x_m` that
/// intersect (at most `limit` of them).
std::vector<TrianglePair> self_intersections(const Lattice& lattice, std::span<const Vec3> x_m,
                                             std::size_t limit = 100);

}  // namespace flagsim::testing
