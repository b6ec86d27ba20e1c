#include "flagsim/infill/paper/length_search.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "flagsim/infill/paper/initial_move.hpp"

namespace flagsim::infill {

double length_search(const Fiber& fiber, std::span<Vec3> positions_m,
                     std::span<const Vec3> previous_m, double tolerance) {
  LengthSearchScratch scratch;
  return length_search(fiber, positions_m, previous_m, tolerance, scratch);
}

double length_search(const Fiber& fiber, std::span<Vec3> positions_m,
                     std::span<const Vec3> previous_m, double tolerance,
                     LengthSearchScratch& scratch) {
  const double rest = fiber.rest_length_m();
  double error = std::abs(fiber.length_m(positions_m) - rest);
  if (error <= tolerance * rest || fiber.segments < 2) return 0.0;
  // Node i walks start_i + t (target_i - start_i); segment i is then A_i + t B_i
  // and the fiber's length sum_i sqrt(A.A + 2t A.B + t^2 B.B): each trial t
  // costs one square root per segment and moves nothing.
  constexpr int kSteps = 10;
  std::vector<Vec3>& step = scratch.step;
  std::vector<double>&aa = scratch.aa, &ab = scratch.ab, &bb = scratch.bb;
  const std::size_t n = std::size_t(fiber.segments);
  step.assign(n + 1, Vec3::Zero());  // ends stay: their step is zero
  aa.resize(n);
  ab.resize(n);
  bb.resize(n);
  for (int i = 1; i < fiber.segments; ++i) {
    const std::size_t node = fiber.node(i);
    const Vec3 target = previous_m[node] + interpolated_motion(fiber, double(i) / fiber.segments,
                                                               positions_m, previous_m);
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
    for (std::size_t i = 0; i < n; ++i)
      total += std::sqrt(std::max(0.0, aa[i] + t * (2.0 * ab[i] + t * bb[i])));
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

}  // namespace flagsim::infill
