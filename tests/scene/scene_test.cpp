#include "flagsim/scene/scene.hpp"

#include <gtest/gtest.h>

#include "flagsim/scene/scene_parser.hpp"

namespace flagsim {
namespace {

// The default scene as shipped: hybrid, 129 x 193 filled from 9 x 13, 10 s at 30 fps.
Scene default_scene() {
  return parse_scene(default_scene_toml(), kDefaultSceneName);
}

TEST(Scene, FramesIncludeTheStartAndTheLatticeIsTheFineOne) {
  const Scene scene = default_scene();
  EXPECT_EQ(scene.simulated_frames(), 301);  // t = 0, 1/30, ..., 10 s
  const Lattice lattice = scene.fine_lattice();
  EXPECT_EQ(lattice.rows, 129);
  EXPECT_EQ(lattice.cols, 193);
  EXPECT_DOUBLE_EQ(lattice.spacing_x_m, 1.5 / 192);
}

TEST(Scene, EachModeRunsItsBackend) {
  const Scene hybrid = default_scene();
  EXPECT_EQ(backend_of(hybrid), Backend::kSpringDamper);  // solver.backend, its default
  EXPECT_EQ(backend_of(in_mode(hybrid, Mode::kMassSpring)), Backend::kSpringDamper);
  EXPECT_EQ(backend_of(in_mode(hybrid, Mode::kBullet)), Backend::kBullet);
  EXPECT_EQ(backend_of(in_mode(hybrid, Mode::kImplicit)), Backend::kImplicit);
  EXPECT_EQ(backend_of(in_mode(hybrid, Mode::kXpbd)), Backend::kXpbd);
  EXPECT_EQ(backend_of(in_mode(hybrid, Mode::kInfill)), std::nullopt);
  EXPECT_EQ(backend_name_of(in_mode(hybrid, Mode::kInfill)), "");
  EXPECT_EQ(backend_name_of(in_mode(hybrid, Mode::kMassSpring)), "spring-damper");
  // A full-lattice mode names its own integrator whatever solver.backend says.
  EXPECT_EQ(with_resolved_backend(in_mode(hybrid, Mode::kXpbd)).solver.backend, Backend::kXpbd);
}

TEST(Scene, VariantsChangeOnlyWhatTheyNameAndLeaveTheSceneAsItWas) {
  const Scene scene = default_scene();
  const Scene tracking = in_mode(scene, Mode::kMassSpring);
  EXPECT_EQ(tracking.mode, Mode::kMassSpring);
  EXPECT_EQ(scene.mode, Mode::kHybrid);
  EXPECT_EQ(tracking.toml_text, scene.toml_text);
  const Scene doubled = with_substeps(scene, 2 * scene.solver.substeps + 7);
  EXPECT_EQ(doubled.solver.substeps, 2 * scene.solver.substeps + 7);
  EXPECT_EQ(doubled.mode, scene.mode);
  EXPECT_EQ(doubled.flag.fine_rows, scene.flag.fine_rows);
}

TEST(Scene, TheCoarseLatticeSceneIsTheSameClothOnFewerNodes) {
  const Scene scene = default_scene();
  const Scene coarse = on_coarse_lattice(scene);
  EXPECT_EQ(coarse.flag.fine_rows, 9);
  EXPECT_EQ(coarse.flag.fine_cols, 13);
  EXPECT_FALSE(coarse.flag.coarse.has_value());
  // Same continuum: size, density, moduli, damping, pin, wind.
  EXPECT_EQ(coarse.flag.width_m, scene.flag.width_m);
  EXPECT_EQ(coarse.flag.height_m, scene.flag.height_m);
  EXPECT_EQ(coarse.flag.areal_density_kg_m2, scene.flag.areal_density_kg_m2);
  EXPECT_EQ(coarse.flag.stretch_modulus_n_m, scene.flag.stretch_modulus_n_m);
  EXPECT_EQ(coarse.flag.damping_per_s, scene.flag.damping_per_s);
  EXPECT_EQ(coarse.flag.pin, scene.flag.pin);
  ASSERT_TRUE(coarse.wind.has_value());
  EXPECT_EQ(coarse.wind->velocity_m_s, scene.wind->velocity_m_s);
  EXPECT_EQ(coarse.fine_lattice().spacing_x_m, 1.5 / 12);
}

}  // namespace
}  // namespace flagsim
