#pragma once
// Small scenes for the physics tests.
#include <gtest/gtest.h>

#include <algorithm>

#include "flagsim/coarse_physics/cloth_integrator.hpp"
#include "flagsim/scene/scene.hpp"

namespace flagsim::test {

/// A 1.0 x 0.8 m cloth on a J x K lattice with no effects but its own springs.
inline Scene small_cloth(int rows = 5, int cols = 7) {
  Scene scene;
  scene.name = "test";
  scene.flag.width_m = 1.0;
  scene.flag.height_m = 0.8;
  scene.flag.fine_rows = rows;
  scene.flag.fine_cols = cols;
  scene.flag.areal_density_kg_m2 = 0.2;
  scene.flag.stretch_modulus_n_m = 1.0e3;
  scene.flag.shear_modulus_n_m = 1.0e2;
  scene.flag.damping_per_s = 0.0;
  return scene;
}

// A soft cloth hanging under its own weight: ~1 cm of elastic stretch, 2.6% at
// the top edge. (Bullet's link projection softens by about strain/2: at 8% top
// strain its sag is 8% short of the spring's.)
inline Scene hanging_cloth(Backend backend, PinSet pin) {
  Scene scene = test::small_cloth(7, 9);
  scene.flag.pin = pin;
  scene.flag.stretch_modulus_n_m = 60.0;
  scene.flag.shear_modulus_n_m = 6.0;
  scene.flag.damping_per_s = 3.0;
  scene.gravity = Gravity{};
  scene.fps = 10.0;
  scene.solver.backend = backend;
  return scene;
}

// Largest drop of a node below its rest height once the cloth is at rest
// (after `frames` frames, 15 s at the scene's 10 fps), m.
inline double settled_sag(const Scene& scene, int frames = 150) {
  auto physics = physics::make_integrator(scene);
  for (int frame = 0; frame < frames; ++frame) physics->advance_frame(nullptr);  // 15 s
  double fastest = 0.0;
  for (const Vec3& v : physics->state().v_m_s) fastest = std::max(fastest, v.norm());
  EXPECT_LT(fastest, 1e-2) << to_string(scene.solver.backend) << ": not at rest";
  const auto rest = physics->model().lattice.rest_positions();
  double sag = 0.0;
  for (std::size_t i = 0; i < rest.size(); ++i)
    sag = std::max(sag, rest[i].y() - physics->state().x_m[i].y());
  return sag;
}

}  // namespace flagsim::test
