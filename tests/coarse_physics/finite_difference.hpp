#pragma once
// Finite-difference check of a force term against its energy: f = -dE/dx.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "flagsim/coarse_physics/force_term.hpp"
#include "flagsim/core/lattice.hpp"
#include "tolerances.hpp"

namespace flagsim::test {

/// Rest positions displaced by seeded noise of `amplitude_m` in every direction,
/// so that every link is stretched or compressed and bent.
inline std::vector<Vec3> jiggled(const Lattice& lattice, double amplitude_m, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::vector<Vec3> x = lattice.rest_positions();
  for (Vec3& p : x)
    for (int c = 0; c < 3; ++c) p[c] += amplitude_m * (double(rng() >> 11) * 0x1.0p-53 - 0.5);
  return x;
}

/// Compares every force component with the central difference of the energy.
inline void expect_force_is_minus_energy_gradient(const physics::ForceTerm& term,
                                                  std::vector<Vec3> x) {
  std::vector<Vec3> v(x.size(), Vec3::Zero()), f(x.size(), Vec3::Zero());
  term.add_forces(x, v, f);
  double scale = 0.0;
  for (const Vec3& fi : f) scale = std::max(scale, fi.norm());
  ASSERT_GT(scale, 0.0) << "the configuration must load the term";
  const double h = kFiniteDifferenceStep;
  for (std::size_t i = 0; i < x.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const double saved = x[i][c];
      x[i][c] = saved + h;
      const double e_plus = term.energy(x);
      x[i][c] = saved - h;
      const double e_minus = term.energy(x);
      x[i][c] = saved;
      const double numeric = -(e_plus - e_minus) / (2.0 * h);
      EXPECT_NEAR(f[i][c], numeric, kFiniteDifferenceRelTol * scale + 1e-9)
          << "node " << i << " component " << c;
    }
  }
}

}  // namespace flagsim::test
