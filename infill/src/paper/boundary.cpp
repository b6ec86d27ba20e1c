#include "flagsim/infill/paper/boundary.hpp"

#include <cmath>
#include <numbers>

#include "flagsim/infill/paper/initial_move.hpp"
#include "flagsim/infill/paper/length_search.hpp"

namespace flagsim::infill {

void move_edge(const Fiber& fiber, std::ptrdiff_t before_node, std::ptrdiff_t after_node,
               const Vec3& normal, std::span<Vec3> positions_m, std::span<const Vec3> previous_m,
               double length_tolerance) {
  if (before_node < 0 && after_node < 0) {  // alone on its line: the paper's fiber steps
    weighted_initial_move(fiber, positions_m, previous_m);
    length_search(fiber, positions_m, previous_m, length_tolerance);
    return;
  }
  // The way the coarse line bends here: the midpoint of the uniform
  // Catmull-Rom curve through p_before, p0, p1, p_after (a missing neighbour
  // is the straight continuation of the edge), relative to the chord.
  const Vec3 p0 = positions_m[fiber.node(0)], p1 = positions_m[fiber.node(fiber.segments)];
  const Vec3 before =
      before_node >= 0 ? positions_m[std::size_t(before_node)] : Vec3(2.0 * p0 - p1);
  const Vec3 after = after_node >= 0 ? positions_m[std::size_t(after_node)] : Vec3(2.0 * p1 - p0);
  Vec3 bow = 0.125 * ((p1 - after) + (p0 - before));  // Catmull-Rom at t = 1/2, minus the midpoint
  const double norm2 = normal.squaredNorm();
  if (norm2 > 0.0) {
    // Out of the cloth's plane only: an edge bowed within the plane would pull
    // the opposite edge's rows longer than they are.
    const Vec3 n = normal / std::sqrt(norm2);
    // The side it bowed to before, so that the edge does not jump across
    // its chord between frames; the coarse line's bend when it was straight.
    const Vec3& was_mid = previous_m[fiber.node(fiber.segments / 2)];
    double side =
        (was_mid - 0.5 * (previous_m[fiber.node(0)] + previous_m[fiber.node(fiber.segments)]))
            .dot(n);
    if (std::abs(side) < 1e-6 * fiber.rest_length_m()) side = bow.dot(n);
    bow = side < 0.0 ? Vec3(-n) : n;
  }
  lay_arc(fiber, positions_m, bow);
}

bool lay_arc(const Fiber& fiber, std::span<Vec3> positions_m, const Vec3& bow) {
  const int n = fiber.segments;
  const Vec3 p0 = positions_m[fiber.node(0)], p1 = positions_m[fiber.node(n)];
  const Vec3 chord = p1 - p0;
  const double c = chord.norm(), s = fiber.rest_spacing_m;
  if (c >= n * s || c == 0.0) {  // taut (or a point): evenly on the chord
    for (int i = 1; i < n; ++i) positions_m[fiber.node(i)] = p0 + (double(i) / n) * chord;
    return false;
  }
  const Vec3 u = chord / c;
  Vec3 w = bow - bow.dot(u) * u;
  if (w.squaredNorm() < 1e-24) {  // no preferred side: any fixed perpendicular
    w = std::abs(u.z()) < 0.9 ? Vec3::UnitZ() : Vec3::UnitY();
    w -= w.dot(u) * u;
  }
  w.normalize();
  // The arc angle phi with n chords S spanning c: c / S = sin(phi/2) / sin(phi/(2n)),
  // decreasing from n at phi = 0 to 0 at phi = 2 pi; bisection.
  const double ratio = c / s;
  double lo = 0.0, hi = 2.0 * std::numbers::pi;
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (std::sin(0.5 * mid) / std::sin(0.5 * mid / n) > ratio ? lo : hi) = mid;
  }
  const double phi = 0.5 * (lo + hi);
  const double radius = 0.5 * s / std::sin(0.5 * phi / n);
  const Vec3 centre = 0.5 * (p0 + p1) - radius * std::cos(0.5 * phi) * w;
  for (int i = 1; i < n; ++i) {
    const double angle = -0.5 * phi + phi * double(i) / n;
    positions_m[fiber.node(i)] = centre + radius * (std::sin(angle) * u + std::cos(angle) * w);
  }
  return true;
}

}  // namespace flagsim::infill
