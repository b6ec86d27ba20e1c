#pragma once
// Small scenes for the physics tests.
#include "flagsim/core/scene.hpp"

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

}  // namespace flagsim::test
