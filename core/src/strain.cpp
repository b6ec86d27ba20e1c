#include "flagsim/core/strain.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace flagsim {

StrainStats link_strain(const Lattice& lattice, std::span<const Vec3> positions_m,
                        std::span<float> node_strain) {
  assert(positions_m.size() == lattice.node_count());
  assert(node_strain.empty() || node_strain.size() == lattice.node_count());
  // A node's strain is the largest of its (up to four) links': each link
  // raises both of its nodes' (float conversion is monotonic, so the max of
  // the converted strains is the converted max).
  std::fill(node_strain.begin(), node_strain.end(), 0.0f);
  double max_strain = 0.0, sum = 0.0;
  std::size_t links = 0;
  for_each_link(lattice, [&](const Link& link) {
    const double s = strain_of(positions_m, link);
    max_strain = std::max(max_strain, s);
    sum += s;
    ++links;
    if (!node_strain.empty()) {
      node_strain[link.a] = std::max(node_strain[link.a], float(s));
      node_strain[link.b] = std::max(node_strain[link.b], float(s));
    }
  });
  // A non-finite strain makes the sum non-finite (std::max may have dropped a
  // NaN): the statistics say so, never a silent 0. The node field of such a
  // frame is not meaningful; the run stops there as diverged, unwritten.
  if (!std::isfinite(sum))
    return {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  return {max_strain, links ? sum / double(links) : 0.0};
}

}  // namespace flagsim
