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
  // Node i walks start_i + t (target_i - start_i); segment i is then A_i + t B_i
  // and the fiber's length sum_i sqrt(A.A + 2t A.B + t^2 B.B): each trial t
  // costs one square root per segment and moves nothing.
  constexpr int kSteps = 10;
  thread_local std::vector<Vec3> step;
  thread_local std::vector<double> aa, ab, bb;
  const std::size_t n = std::size_t(fiber.segments);
  step.assign(n + 1, Vec3::Zero());  // ends stay: their step is zero
  aa.resize(n);
  ab.resize(n);
  bb.resize(n);
  for (int i = 1; i < fiber.segments; ++i) {
    const std::size_t node = fiber.node(i);
    const Vec3 target = previous_m[node] + interpolated_motion(fiber, double(i) / fiber.segments, positions_m, previous_m);
    step[std::size_t(i)] = target - positions_m[node];
  }
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 a = positions_m[fiber.node(int(i) + 1)] - positions_m[fiber.node(int(i))];
    const Vec3 b = step[i + 1] - step[i];
    aa[i] = a.squaredNorm();
    ab[i] = a.dot(b);
    bb[i] = b.squaredNorm();
  }
  auto length_at = [&](double t) {
    double total = 0.0;
    for (std::size_t i = 0; i < n; ++i) total += std::sqrt(std::max(0.0, aa[i] + t * (2.0 * ab[i] + t * bb[i])));
    return total;
  };
  int best = 0;
  for (int k = 1; k <= kSteps; ++k) {
    const double trial = std::abs(length_at(double(k) / kSteps) - rest);
    if (trial >= error) break;  // no longer approaching the rest length
    error = trial;
    best = k;
  }
  const double t = double(best) / kSteps;
  if (best > 0)
    for (int i = 1; i < fiber.segments; ++i) positions_m[fiber.node(i)] += t * step[std::size_t(i)];
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
