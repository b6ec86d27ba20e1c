// What every backend behind ClothIntegrator promises alike.
#include <gtest/gtest.h>

#include <cstring>

#include "flagsim/coarse_physics/cloth_integrator.hpp"
#include "flagsim/coarse_physics/cloth_state.hpp"
#include "scene_fixtures.hpp"

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

}  // namespace
}  // namespace flagsim::physics
