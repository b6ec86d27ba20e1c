// XPBD: the same cloth as the spring-damper one in the limit of small steps,
// constraints in colour groups that share no node, the same bits for the same seed.
#include "flagsim/coarse_physics/xpbd.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <set>

#include "scene_fixtures.hpp"
#include "tolerances.hpp"

namespace flagsim::physics {
namespace {

TEST(Xpbd, StaticSagConvergesToTheExplicitOneAsSubstepsGrow) {
  const Scene spring_damper = test::hanging_cloth(Backend::kSpringDamper, PinSet::kTop);
  const double spring = test::settled_sag(spring_damper);
  double previous_error = INFINITY;
  for (int substeps : {2, 8, 32, 128}) {
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
