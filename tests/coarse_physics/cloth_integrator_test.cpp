// What every backend behind ClothIntegrator promises alike.
#include "flagsim/coarse_physics/cloth_integrator.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "flagsim/coarse_physics/cloth_state.hpp"
#include "scene_fixtures.hpp"
#include "tolerances.hpp"

namespace flagsim::physics {
namespace {

TEST(Integrators, EachBackendGivesIdenticalBitsForTheSameSeed) {
  for (const auto& [backend, name] : kBackendNames) {
    Scene scene = test::hanging_cloth(backend, PinSet::kLeft);
    scene.wind = Wind{};
    scene.wind->velocity_m_s = Vec3(8, 0, 1);
    scene.flag.initial_perturbation_m = 0.02;
    scene.solver.substeps = 20;
    auto run = [&](std::uint64_t seed) {
      scene.seed = seed;
      const auto physics = make_integrator(scene);
      for (int f = 0; f < 10; ++f) physics->advance_frame(nullptr);
      return physics->state().x_m;
    };
    const auto a = run(4), b = run(4), c = run(5);
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3))) << name;
    EXPECT_NE(0, std::memcmp(a.data(), c.data(), a.size() * sizeof(Vec3))) << name;
  }
}

TEST(Integrators, EveryBackendStartsFromTheSameState) {
  Scene scene = test::hanging_cloth(Backend::kSpringDamper, PinSet::kLeft);
  scene.flag.initial_perturbation_m = 0.02;
  scene.seed = 3;
  const ClothState start = initial_state(scene, make_cloth_model(scene));
  for (const auto& [backend, name] : kBackendNames) {
    scene.solver.backend = backend;
    const auto physics = make_integrator(scene);
    EXPECT_EQ(0, std::memcmp(physics->state().x_m.data(), start.x_m.data(),
                             start.x_m.size() * sizeof(Vec3)))
        << name;
  }
}

TEST(Integrators, TheFactoryBuildsTheBackendTheSceneNamesAndItsEnergyIsHalfMvSquared) {
  for (const auto& [backend, name] : kBackendNames) {
    Scene scene = test::hanging_cloth(backend, PinSet::kTop);
    scene.solver.substeps = 40;
    const auto physics = make_integrator(scene);
    EXPECT_EQ(physics->kinetic_energy(), 0.0) << name;  // it starts at rest
    physics->advance_frame(nullptr);                    // 0.1 s of falling
    const ClothState& state = physics->state();
    double energy = 0.0;
    for (std::size_t i = 0; i < state.v_m_s.size(); ++i)
      energy += 0.5 * physics->model().mass_kg[i] * state.v_m_s[i].squaredNorm();
    EXPECT_GT(energy, 0.0) << name;
    EXPECT_NEAR(physics->kinetic_energy(), energy, test::kRoundOff * energy) << name;
    // Each backend names its own solver in the summary (Bullet's iterations,
    // implicit Euler's linear solve, XPBD's passes) or nothing.
    const std::string summary = physics->solver_summary();
    if (backend == Backend::kSpringDamper) {
      EXPECT_TRUE(summary.empty()) << summary;
    }
  }
}

}  // namespace
}  // namespace flagsim::physics
