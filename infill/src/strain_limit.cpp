#include "flagsim/infill/strain_limit.hpp"

#include <cmath>

namespace flagsim::infill {
namespace {

// Shortens a-b to `longest` if it is longer; returns whether it moved anything.
bool shorten(Vec3& a, Vec3& b, bool a_fixed, bool b_fixed, double longest) {
  const Vec3 d = b - a;
  const double length = d.norm();
  // (A link just shortened may come out an ulp long: that is not "too long".)
  if (length <= longest * (1.0 + 1e-12) || (a_fixed && b_fixed)) return false;
  const double shrink = 1.0 - longest / length;
  if (a_fixed) {
    b -= shrink * d;
  } else if (b_fixed) {
    a += shrink * d;
  } else {
    a += (0.5 * shrink) * d;
    b -= (0.5 * shrink) * d;
  }
  return true;
}

}  // namespace

int limit_stretch(const Lattice& lattice, std::span<const std::uint8_t> fixed,
                  std::span<Vec3> positions_m, double max_strain, int max_passes) {
  const double longest = 1.0 + max_strain;  // times each link's rest length
  for (int pass = 1; pass <= max_passes; ++pass) {
    bool moved = false;
    for_each_link(lattice, [&](const Link& link) {
      moved |= shorten(positions_m[link.a], positions_m[link.b], fixed[link.a], fixed[link.b],
                       longest * link.rest_m);
    });
    if (!moved) return pass;
  }
  return max_passes;
}

}  // namespace flagsim::infill
