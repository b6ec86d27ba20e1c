#include "flagsim/coarse_physics/held_forces.hpp"

#include <algorithm>
#include <cmath>

namespace flagsim::physics {

HeldForces::HeldForces(const std::vector<std::unique_ptr<ForceTerm>>& terms, double wind_hold,
                       double substep_s, int substeps_per_frame, bool may_hold, std::size_t nodes) {
  double slow_rate = 0.0;
  for (std::size_t t = 0; t < terms.size(); ++t) {
    const ForceTiming timing = terms[t]->timing();
    if (timing == ForceTiming::kEverySubstep) continue;
    held_terms_.push_back(t);
    if (timing == ForceTiming::kSlow && terms[t]->velocity_rate_bound() >= slow_rate) {
      slow_rate = terms[t]->velocity_rate_bound();
      slow_term_ = t;
    }
  }
  if (slow_rate > 0.0 && may_hold) {
    const double hold_s = wind_hold / slow_rate;
    hold_substeps_ =
        int(std::clamp(std::floor(hold_s / substep_s + 1e-9), 1.0, double(substeps_per_frame)));
  }
  if (hold_substeps_ > 1) {
    held_.assign(nodes, Vec3::Zero());
    held_before_ = held_;
  }
}

}  // namespace flagsim::physics
