#include "flagsim/sim/divergence.hpp"

#include <fmt/format.h>

#include <cmath>

namespace flagsim {

std::optional<std::string> divergence_reason(std::span<const Vec3> positions_m,
                                             std::span<const Vec3> velocities_m_s,
                                             const StrainStats& strain, const Limits& limits) {
  double max_speed2 = 0.0;
  for (const Vec3& x : positions_m)
    if (!x.allFinite()) return std::string("a node position became NaN or infinite");
  for (const Vec3& v : velocities_m_s) {
    if (!v.allFinite()) return std::string("a node velocity became NaN or infinite");
    max_speed2 = std::max(max_speed2, v.squaredNorm());
  }
  if (!(strain.max <= limits.max_strain))
    return fmt::format(
        "max link strain {:.3g} exceeds limits.max_strain = {:.3g}; raise flag.stretch_modulus, "
        "lower the loads, or raise the limit if this much stretch is intended",
        strain.max, limits.max_strain);
  const double max_speed = std::sqrt(max_speed2);
  if (max_speed > limits.max_speed_m_s)
    return fmt::format(
        "a node moves at {:.3g} m/s, above limits.max_speed = {:.3g} m/s (energy blow-up); "
        "raise solver.substeps or flag.damping",
        max_speed, limits.max_speed_m_s);
  return std::nullopt;
}

}  // namespace flagsim
