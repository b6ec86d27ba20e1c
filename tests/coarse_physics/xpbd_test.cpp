// XPBD: the same cloth as the spring-damper one in the limit of small steps,
// constraints in colour groups that share no node, the same bits for the same seed.
#include "flagsim/coarse_physics/xpbd.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <set>

#include "flagsim/scene/scene_parser.hpp"
#include "scene_fixtures.hpp"
#include "tolerances.hpp"

namespace flagsim::physics {
namespace {

TEST(Xpbd, StaticSagConvergesToTheExplicitOneAsSubstepsGrow) {
  const Scene spring_damper = test::hanging_cloth(Backend::kSpringDamper, PinSet::kTop);
  const double spring = test::settled_sag(spring_damper);
  double previous_error = INFINITY;
  // From 16: fewer are raised to 14, the substeps its links need
  // (xpbd_propagation_substep_s: 0.125 m links, c = sqrt(60 / 0.2) m/s).
  for (int substeps : {16, 32, 64, 128}) {
    Scene scene = test::hanging_cloth(Backend::kXpbd, PinSet::kTop);
    scene.solver.substeps = substeps;
    const double sag = test::settled_sag(scene);
    const double error = std::abs(sag - spring) / spring;
    std::printf("xpbd %3d substeps/frame: sag %.5f m (explicit %.5f), error %.3f%%\n", substeps,
                sag, spring, 100.0 * error);
    EXPECT_LT(error, previous_error) << substeps << " substeps";
    previous_error = error;
  }
  EXPECT_LT(previous_error, test::kSagRelTol);
}

TEST(Xpbd, ChoosesEnoughSubstepsForItsLinksToKeepUpWithTheLoad) {
  // One pass a substep carries a correction one link: the substep is at most
  // iterations x dx / c, c = sqrt(Y / rho_A) = sqrt(2e4 / 0.2) = 316 m/s for the
  // default fabric. At 13 substeps a frame (the scene's floor) the default
  // flag diverged in frame 2 at 129 x 193.
  const auto substeps = [](std::vector<std::string> overrides) {
    overrides.emplace_back("scene.mode=\"xpbd\"");
    return Xpbd(parse_scene(default_scene_toml(), kDefaultSceneName, overrides))
        .substeps_per_frame();
  };
  const double c = std::sqrt(2.0e4 / 0.2), frame = 1.0 / 30.0;
  EXPECT_EQ(substeps({}), int(std::ceil(frame / ((1.0 / 128.0) / c))));                    // 1350
  EXPECT_EQ(substeps({"flag.fine=[33,49]"}), int(std::ceil(frame / ((1.0 / 32.0) / c))));  // 338
  EXPECT_EQ(substeps({"flag.fine=[33,49]", "solver.iterations=2"}),
            int(std::ceil(frame / ((2.0 / 32.0) / c))));
  EXPECT_EQ(substeps({"flag.fine=[33,49]", "solver.substeps=2000"}), 2000);  // a floor
}

TEST(Xpbd, ColourGroupsShareNoNode) {
  Scene scene = test::small_cloth(6, 7);
  scene.flag.pin = PinSet::kNone;  // a link between two pins is no constraint
  scene.bending = Bending{};
  scene.bending->rigidity_j = 1e-3;
  const Xpbd physics(scene);
  EXPECT_EQ(physics.link_groups().size(), 8u);     // 4 link families x 2
  EXPECT_EQ(physics.bending_groups().size(), 6u);  // 2 directions x 3
  std::size_t links = 0, triples = 0;
  for (const auto& group : physics.link_groups()) {
    std::set<std::uint32_t> nodes;
    for (const Xpbd::Link& link : group) {
      EXPECT_TRUE(nodes.insert(link.a).second && nodes.insert(link.b).second);
      ++links;
    }
  }
  for (const auto& group : physics.bending_groups()) {
    std::set<std::uint32_t> nodes;
    for (const Xpbd::Triple& t : group) {
      EXPECT_TRUE(nodes.insert(t.a).second && nodes.insert(t.b).second && nodes.insert(t.c).second);
      ++triples;
    }
  }
  // Every constraint is in a group: 6x7 nodes, no pins.
  EXPECT_EQ(links, std::size_t(6 * 6 + 5 * 7 + 2 * 5 * 6));
  EXPECT_EQ(triples, std::size_t(6 * 5 + 4 * 7));
}

}  // namespace
}  // namespace flagsim::physics
