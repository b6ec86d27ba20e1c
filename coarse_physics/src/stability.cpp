#include "flagsim/coarse_physics/stability.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "flagsim/core/errors.hpp"
#include "flagsim/core/limits.hpp"

namespace flagsim::physics {

double explicit_stability_limit(const ClothModel& model,
                                const std::vector<std::unique_ptr<ForceTerm>>& terms) {
  std::vector<double> row_sum(model.lattice.node_count(), 0.0);
  double rate = 0.0;
  for (const auto& term : terms) {
    term->add_stiffness_bound(row_sum);
    rate = std::max(rate, term->velocity_rate_bound());
  }
  double omega2 = 0.0;
  for (std::size_t i = 0; i < row_sum.size(); ++i)
    if (!model.pinned[i]) omega2 = std::max(omega2, row_sum[i] * (1.0 / model.mass_kg[i]));
  double limit = std::numeric_limits<double>::infinity();
  if (omega2 > 0.0) limit = 2.0 / std::sqrt(omega2);
  if (rate > 0.0) limit = std::min(limit, 1.0 / rate);
  return limit;
}

int substeps_per_frame(double frame_s, double stable_substep_s, int minimum) {
  const double needed = std::ceil(frame_s / (kStabilitySafety * stable_substep_s) - 1e-9);
  if (!(needed <= double(limits::kSubstepsPerFrame)))
    throw UserError(fmt::format(
        "the scene's stability limit is a substep of {:.3g} s: {:.3g} substeps a frame of {:.3g} "
        "s, more than {} (make the lattice coarser (flag.fine, flag.coarse), the flag larger "
        "(flag.size) or heavier (flag.areal_density), or the cloth softer (flag.stretch_modulus))",
        stable_substep_s, needed, frame_s, limits::kSubstepsPerFrame));
  return std::max(minimum, int(needed));
}

}  // namespace flagsim::physics
