#include "flagsim/sim/model.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <numeric>
#include <string>
#include <vector>

#include "flagsim/core/errors.hpp"
#include "flagsim/scene/scene_parser.hpp"
#include "flagsim/sim/simulation.hpp"

namespace flagsim::sim {
namespace {

Scene default_with(std::vector<std::string> overrides) {
  return parse_scene(default_scene_toml(), kDefaultSceneName, overrides);
}

double total_mass_kg(const physics::ClothModel& cloth) {
  return std::accumulate(cloth.mass_kg.begin(), cloth.mass_kg.end(), 0.0);
}

TEST(Model, CompilesTheClothOfEachLatticeOnceFromOneMaterial) {
  const auto hybrid = Model::compile(default_with({"flag.fine=[33,49]"}));
  ASSERT_TRUE(hybrid->physics_cloth());
  const physics::ClothModel& coarse = *hybrid->physics_cloth();
  const physics::ClothModel& dense = hybrid->dense_cloth();
  EXPECT_EQ(coarse.lattice.rows, 9);
  EXPECT_EQ(coarse.lattice.cols, 13);
  EXPECT_EQ(dense.lattice.rows, 33);
  EXPECT_EQ(dense.lattice.cols, 49);
  // Both lattices carry the whole flag: 0.2 kg/m^2 x 1.5 m x 1.0 m (to the
  // round-off of a sum of 1617 terms, n eps 0.3 kg = 5e-14 kg).
  EXPECT_NEAR(total_mass_kg(coarse), 0.3, 1e-13);
  EXPECT_NEAR(total_mass_kg(dense), 0.3, 1e-13);
  // A row link stands for a strip as wide as a row: k = Y dy / dx at any spacing.
  EXPECT_DOUBLE_EQ(coarse.links[0].stiffness_n_m,
                   2.0e4 * coarse.lattice.spacing_y_m / coarse.lattice.spacing_x_m);
  EXPECT_EQ(coarse.material.stretch_modulus_n_m, hybrid->material().stretch_modulus_n_m);

  const auto full = Model::compile(default_with({"flag.fine=[9,13]", "scene.mode=mass-spring"}));
  EXPECT_EQ(full->physics_cloth().get(), &full->dense_cloth());  // one cloth, shared
  Scene infill = default_with({"flag.fine=[9,13]"});
  infill.mode = Mode::kInfill;
  infill.flag.coarse.reset();
  infill.wind.reset();
  infill.gravity.reset();
  infill.keyframes = {
      Keyframe{0.0, {Vec3(0, 0, 0), Vec3(1.5, 0, 0), Vec3(0, -1, 0), Vec3(1.5, -1, 0)}}};
  EXPECT_FALSE(Model::compile(infill)->physics_cloth());  // no physics
}

TEST(Model, ASceneBuiltInCodeIsCheckedAsAFilesIs) {
  Scene scene = default_with({});
  scene.flag.coarse = std::array<int, 2>{8, 13};  // 7 coarse links do not divide 128
  try {
    Model::compile(scene);
    ADD_FAILURE() << "compiled";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("scene: flag.coarse: [8, 13] does not divide"),
              std::string::npos)
        << e.what();
  }
}

TEST(Model, SimulationsShareOneModelThatOutlivesItsScene) {
  std::shared_ptr<const Model> model;
  {
    const Scene scene = default_with({"flag.fine=[17,25]"});
    model = Model::compile(scene);
  }  // the scene is gone; the model holds its own
  const auto a = make_simulation(model);
  const auto b = make_simulation(model);
  for (int frame = 0; frame < 3; ++frame) {
    a->advance_frame(nullptr);
    b->advance_frame(nullptr);
  }
  ASSERT_EQ(a->positions().size(), b->positions().size());
  EXPECT_TRUE(std::equal(a->positions().begin(), a->positions().end(), b->positions().begin()));
  EXPECT_EQ(model.use_count(), 3);  // this test's and the two simulations'
}

TEST(Model, BendingStatedAsAYarnIsTheSameClothAsItsStiffness) {
  // r = 0.1 mm, E = 2 GPa: D = pi E r^3 / 8; the physics sees only D.
  const double rigidity = Yarn{1.0e-4, 2.0e9}.sheet_rigidity_j();
  const std::vector<std::string> full = {"scene.mode=mass-spring", "flag.fine=[9,13]"};
  std::vector<std::string> as_yarn = full, as_stiffness = full;
  as_yarn.insert(as_yarn.end(), {"bending.fiber_radius=1.0e-4", "bending.fiber_modulus=2.0e9"});
  as_stiffness.push_back("bending.stiffness=" + fmt::format("{:.17g}", rigidity));
  const auto yarn = make_simulation(default_with(as_yarn));
  const auto stiffness = make_simulation(default_with(as_stiffness));
  EXPECT_EQ(yarn->effects(), stiffness->effects());
  for (int frame = 0; frame < 3; ++frame) {
    yarn->advance_frame(nullptr);
    stiffness->advance_frame(nullptr);
  }
  EXPECT_TRUE(std::equal(yarn->positions().begin(), yarn->positions().end(),
                         stiffness->positions().begin()));
}

}  // namespace
}  // namespace flagsim::sim
