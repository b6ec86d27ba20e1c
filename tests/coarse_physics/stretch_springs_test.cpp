#include "flagsim/coarse_physics/stretch_springs.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "finite_difference.hpp"
#include "scene_fixtures.hpp"

namespace flagsim::physics {
namespace {

TEST(StretchSprings, ForceIsMinusEnergyGradient) {
  const ClothModel model = make_cloth_model(test::small_cloth(4, 5));
  const StretchSprings springs(model);
  test::expect_force_is_minus_energy_gradient(springs, test::jiggled(model.lattice, 0.05, 1));
}

TEST(StretchSprings, NoForceAtRestAndBalancedTotal) {
  const ClothModel model = make_cloth_model(test::small_cloth(4, 5));
  const StretchSprings springs(model);
  std::vector<Vec3> x = model.lattice.rest_positions(), v(x.size(), Vec3::Zero()),
                    f(x.size(), Vec3::Zero());
  springs.add_forces(x, v, f);
  for (const Vec3& fi : f) EXPECT_LT(fi.norm(), 1e-9);
  x = test::jiggled(model.lattice, 0.05, 2);
  std::fill(f.begin(), f.end(), Vec3::Zero());  // add_forces adds: start from zero again
  springs.add_forces(x, v, f);
  double largest = 0.0;
  for (const Vec3& fi : f) largest = std::max(largest, fi.norm());
  EXPECT_GT(largest, 1.0);  // jiggled by 5 cm the springs pull: the total below is a real sum
  Vec3 total = Vec3::Zero();
  for (const Vec3& fi : f) total += fi;
  EXPECT_LT(total.norm(), 1e-9);  // internal forces: Newton's third law
}

TEST(StretchSprings, TheForceIsEveryLinksAddedInTheLinkLoopsOrderToTheBit) {
  // add_forces computes four links side by side and each node sums its links'
  // forces; rows of 11 nodes exercise full and partial lane groups, the border
  // links their edge factor, a zero-length link the no-direction case.
  // Reference: one link at a time in for_each_link's order.
  const Scene scene = test::small_cloth(6, 11);
  const ClothModel model = make_cloth_model(scene);
  const StretchSprings springs(model);
  const Lattice& lattice = model.lattice;
  std::vector<Vec3> x = lattice.rest_positions(), f(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double s = double(i);
    x[i] += 0.03 * Vec3(std::sin(1.1 * s), std::cos(0.6 * s), std::sin(1.9 * s + 0.2));
    f[i] = Vec3(0.01 * s, -0.3, 2e-3 * s);  // what the terms before it left there
  }
  x[lattice.index(3, 5)] = x[lattice.index(3, 4)];  // a row link of zero length
  std::vector<Vec3> expected = f;
  for (const LinkFamily& family : model.links)
    for_each_link(model, family, [&](std::size_t a, std::size_t b, double k, double rest) {
      const Vec3 d = x[b] - x[a];
      const double length = d.norm();
      const Vec3 force = (length > 0.0 ? k * (length - rest) / length : 0.0) * d;
      expected[a] += force;
      expected[b] -= force;
    });
  springs.add_forces(x, {}, f);
  for (std::size_t i = 0; i < f.size(); ++i) EXPECT_EQ(f[i], expected[i]) << i;
}

TEST(StretchSprings, HessianIsMinusForceJacobian) {
  const ClothModel model = make_cloth_model(test::small_cloth(4, 5));
  StretchSprings springs(model);
  // Jiggled by 5 cm on 20-25 cm links: some links stretched, some compressed.
  const std::vector<Vec3> x = test::jiggled(model.lattice, 0.05, 3);
  test::expect_derivative_is_minus_force_jacobian(springs, x, std::vector<Vec3>(x.size()),
                                                  test::Wrt::kPosition);
}

TEST(StretchSprings, ProjectedHessianIsPositiveSemidefiniteAndExactUnderTension) {
  const ClothModel model = make_cloth_model(test::small_cloth(4, 5));
  StretchSprings springs(model);
  std::vector<Vec3> x = test::jiggled(model.lattice, 0.05, 3);
  const std::vector<Vec3> v(x.size(), Vec3::Zero());
  auto energy_of = [&](const std::vector<Vec3>& dx) {
    std::vector<Vec3> out(x.size(), Vec3::Zero());
    springs.add_stiffness_product(dx, out);
    double total = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) total += dx[i].dot(out[i]);
    return total;
  };
  // Compressed links make the exact Hessian indefinite: some direction has
  // dx^T K dx < 0; the projection has none.
  std::mt19937_64 rng(11);
  double exact_lowest = 0.0, projected_lowest = 0.0;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<Vec3> dx(x.size(), Vec3::Zero());
    const std::size_t node = rng() % x.size();
    dx[node] = Vec3(double(rng() % 7) - 3.0, double(rng() % 7) - 3.0, double(rng() % 7) - 3.0);
    springs.linearize(x, v, Definiteness::kExact);
    exact_lowest = std::min(exact_lowest, energy_of(dx));
    springs.linearize(x, v, Definiteness::kProjected);
    projected_lowest = std::min(projected_lowest, energy_of(dx));
  }
  EXPECT_LT(exact_lowest, 0.0);
  EXPECT_GE(projected_lowest, 0.0);
  // Stretched uniformly by 1%, every link is in tension: both agree exactly.
  x = model.lattice.rest_positions();
  for (Vec3& p : x) p *= 1.01;
  const std::vector<Vec3> dx = test::jiggled(model.lattice, 0.05, 4);
  springs.linearize(x, v, Definiteness::kExact);
  const double exact = energy_of(dx);
  springs.linearize(x, v, Definiteness::kProjected);
  EXPECT_EQ(energy_of(dx), exact);
}

}  // namespace
}  // namespace flagsim::physics
