#include "flagsim/infill/steps.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace flagsim::infill {

double end_weight(double s) { return std::abs(1.0 - 2.0 * s); }

Vec3 interpolated_motion(const Fiber& fiber, double s, std::span<const Vec3> positions_m,
                         std::span<const Vec3> previous_m) {
  const std::size_t a = fiber.node(0), b = fiber.node(fiber.segments);
  return (1.0 - s) * (positions_m[a] - previous_m[a]) + s * (positions_m[b] - previous_m[b]);
}

void weighted_initial_move(const Fiber& fiber, std::span<Vec3> positions_m,
                           std::span<const Vec3> previous_m) {
  for (int i = 1; i < fiber.segments; ++i) {
    const double s = double(i) / fiber.segments;
    const std::size_t n = fiber.node(i);
    positions_m[n] = previous_m[n] + end_weight(s) * interpolated_motion(fiber, s, positions_m, previous_m);
  }
}

double length_search(const Fiber& fiber, std::span<Vec3> positions_m,
                     std::span<const Vec3> previous_m, double tolerance) {
  const double rest = fiber.rest_length_m();
  double error = std::abs(fiber.length_m(positions_m) - rest);
  if (error <= tolerance * rest || fiber.segments < 2) return 0.0;
  // Straight lines from the current nodes to the targets, walked a tenth at a time.
  constexpr int kSteps = 10;
  thread_local std::vector<Vec3> start, target;
  start.resize(std::size_t(fiber.segments + 1));
  target.resize(start.size());
  for (int i = 1; i < fiber.segments; ++i) {
    const std::size_t n = fiber.node(i);
    start[i] = positions_m[n];
    target[i] = previous_m[n] + interpolated_motion(fiber, double(i) / fiber.segments, positions_m, previous_m);
  }
  int best = 0;
  for (int step = 1; step <= kSteps; ++step) {
    const double t = double(step) / kSteps;
    for (int i = 1; i < fiber.segments; ++i) positions_m[fiber.node(i)] = start[i] + t * (target[i] - start[i]);
    const double trial = std::abs(fiber.length_m(positions_m) - rest);
    if (trial >= error) break;  // no longer approaching the rest length
    error = trial;
    best = step;
  }
  const double t = double(best) / kSteps;
  for (int i = 1; i < fiber.segments; ++i) positions_m[fiber.node(i)] = start[i] + t * (target[i] - start[i]);
  return t;
}

int relax_fiber(const Fiber& fiber, std::span<Vec3> positions_m, int max_sweeps, double tolerance) {
  for (int sweep = 1; sweep <= max_sweeps; ++sweep) {
    double worst = 0.0;
    for (int i = 0; i < fiber.segments; ++i) {
      const double w_a = i == 0 ? 0.0 : 1.0;
      const double w_b = i + 1 == fiber.segments ? 0.0 : 1.0;
      worst = std::max(worst, project_distance(positions_m[fiber.node(i)], positions_m[fiber.node(i + 1)],
                                               w_a, w_b, fiber.rest_spacing_m));
    }
    if (worst <= tolerance) return sweep;
  }
  return max_sweeps;
}

}  // namespace flagsim::infill
