#include "flagsim/coarse_physics/stretch_springs.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

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
