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

/// Which derivative of the force a check is about.
enum class Wrt { kPosition, kVelocity };

/// Compares the term's products K dx (or C dv) and its diagonal blocks,
/// linearized exactly at (x, v), with central differences of its force along
/// seeded directions: K = -df/dx, C = -df/dv.
inline void expect_derivative_is_minus_force_jacobian(physics::ForceTerm& term,
                                                      const std::vector<Vec3>& x,
                                                      const std::vector<Vec3>& v, Wrt wrt) {
  const std::size_t n = x.size();
  term.linearize(x, v, physics::Definiteness::kExact);
  auto force_at = [&](const std::vector<Vec3>& dir, double eps) {
    std::vector<Vec3> xs = x, vs = v, f(n, Vec3::Zero());
    std::vector<Vec3>& moved = wrt == Wrt::kPosition ? xs : vs;
    for (std::size_t i = 0; i < n; ++i) moved[i] += eps * dir[i];
    term.add_forces(xs, vs, f);
    return f;
  };
  auto product = [&](const std::vector<Vec3>& dir) {
    std::vector<Vec3> out(n, Vec3::Zero());
    if (wrt == Wrt::kPosition)
      term.add_stiffness_product(dir, out);
    else
      term.add_damping_product(dir, out);
    return out;
  };
  // The step is scaled to the state (velocities of ~10 m/s, positions of ~1 m).
  const double h = kFiniteDifferenceStep * (wrt == Wrt::kPosition ? 1.0 : 10.0);
  std::mt19937_64 rng(7);
  double largest = 0.0;
  for (int trial = 0; trial < 3; ++trial) {
    std::vector<Vec3> dir(n);
    for (Vec3& d : dir)
      for (int c = 0; c < 3; ++c) d[c] = double(rng() >> 11) * 0x1.0p-53 - 0.5;
    const std::vector<Vec3> plus = force_at(dir, h), minus = force_at(dir, -h);
    const std::vector<Vec3> analytic = product(dir);
    double scale = 0.0;
    for (const Vec3& a : analytic) scale = std::max(scale, a.norm());
    largest = std::max(largest, scale);
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3 numeric = -(plus[i] - minus[i]) / (2.0 * h);
      EXPECT_LT((analytic[i] - numeric).norm(), kFiniteDifferenceRelTol * scale + 1e-9)
          << "trial " << trial << " node " << i << ": " << analytic[i].transpose() << " vs "
          << numeric.transpose();
    }
  }
  ASSERT_GT(largest, 0.0) << "the configuration must load the derivative";
  // Diagonal blocks: column c of block i is (K e_ic)_i.
  std::vector<physics::Mat3> diagonal(n, physics::Mat3::Zero());
  if (wrt == Wrt::kPosition)
    term.add_stiffness_diagonal(diagonal);
  else
    term.add_damping_diagonal(diagonal);
  for (std::size_t i = 0; i < n; i += std::max<std::size_t>(1, n / 7)) {
    for (int c = 0; c < 3; ++c) {
      std::vector<Vec3> unit(n, Vec3::Zero());
      unit[i][c] = 1.0;
      const Vec3 column = product(unit)[i];
      EXPECT_LT((diagonal[i].col(c) - column).norm(), kAnalyticRelTol * (column.norm() + 1.0))
          << "node " << i << " column " << c;
    }
  }
}

}  // namespace flagsim::test
