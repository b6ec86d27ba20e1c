#pragma once
// Strain statistics of a lattice state (contract: /stats/max_strain, /stats/mean_strain).
#include <cmath>
#include <span>

#include "flagsim/core/lattice.hpp"

namespace flagsim {

struct StrainStats {
  double max = 0.0;   ///< max over all row and column neighbour links of |d - S| / S
  double mean = 0.0;  ///< mean of the same over all links
};

/// |d - S| / S of one link at positions_m (d its length, S its rest length).
inline double strain_of(std::span<const Vec3> positions_m, const Link& link) {
  return std::abs((positions_m[link.b] - positions_m[link.a]).norm() - link.rest_m) / link.rest_m;
}

/// Strain of every row link ((j,k)-(j,k+1), rest S = spacing_x) and column link
/// ((j,k)-(j+1,k), rest S = spacing_y). positions_m: [J*K] row-major, m.
/// A non-finite position gives a non-finite max (NaN propagates), never a silent 0.
/// @param node_strain  [J*K] or empty: when given, each node's largest strain of
///   its (up to four) row and column links (contract: /frames/strain), float32 as
///   stored; not meaningful in a frame whose statistics are NaN
StrainStats link_strain(const Lattice& lattice, std::span<const Vec3> positions_m,
                        std::span<float> node_strain = {});

}  // namespace flagsim
