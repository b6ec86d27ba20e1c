#pragma once
// The seeded initial perturbation (flag.initial_perturbation).
#include <cstdint>
#include <vector>

#include "flagsim/core/lattice.hpp"

namespace flagsim::physics {

/// Out-of-plane displacement z [J*K] in m: a sum of three smooth modes with
/// seeded amplitudes and phases, a function of the normalised rest coordinates
/// (u = k/(K-1), v = j/(J-1)) only, so the same seed gives the same shape at any
/// resolution. It grows linearly from 0 at the pole edge, |z| <= amplitude_m.
std::vector<double> smooth_perturbation(const Lattice& lattice, std::uint64_t seed,
                                        double amplitude_m);

}  // namespace flagsim::physics
