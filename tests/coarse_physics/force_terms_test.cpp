// force_terms.cpp: a term is built only when the scene calls for its effect,
// in the one pipeline order, and a backend can leave out what it models itself.
#include "flagsim/coarse_physics/force_terms.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "flagsim/core/stage_times.hpp"
#include "scene_fixtures.hpp"

namespace flagsim::physics {
namespace {

std::vector<std::string> names(const std::vector<std::unique_ptr<ForceTerm>>& terms) {
  std::vector<std::string> out;
  out.reserve(terms.size());
  for (const auto& term : terms) out.emplace_back(term->name());
  return out;
}

Scene everything() {
  Scene scene = test::small_cloth();
  scene.gravity = Gravity{};
  scene.bending = Bending{};
  scene.wind = Wind{};
  scene.wind->gusts = Gusts{};
  scene.wind->turbulence = Turbulence{};
  scene.pole = PoleMotion{};
  scene.flag.damping_per_s = 0.1;
  return scene;
}

TEST(ForceTerms, OnlyTheEffectsTheSceneCallsForInPipelineOrder) {
  const Scene bare = test::small_cloth();
  const ClothModel bare_model = make_cloth_model(bare);
  EXPECT_EQ(names(make_force_terms(bare, bare_model)), std::vector<std::string>{"stretch"});
  const Scene full = everything();
  const ClothModel model = make_cloth_model(full);
  EXPECT_EQ(names(make_force_terms(full, model)),
            (std::vector<std::string>{"stretch", "bending", "gravity", "wind"}));
}

TEST(ForceTerms, ABackendLeavesOutWhatItModelsItself) {
  const Scene full = everything();
  const ClothModel model = make_cloth_model(full);
  // Bullet: its links stretch and its world pulls down; wind stays ours.
  EXPECT_EQ(names(make_force_terms(full, model, {false, true, false})),
            (std::vector<std::string>{"bending", "wind"}));
}

TEST(ForceTerms, EachTermGetsATimingColumnNamedAfterIt) {
  const Scene full = everything();
  const ClothModel model = make_cloth_model(full);
  const auto terms = make_force_terms(full, model);
  StageTimes times;
  const std::vector<int> stages = register_term_stages(terms, times);
  ASSERT_EQ(stages.size(), terms.size());
  for (std::size_t i = 0; i < terms.size(); ++i)
    EXPECT_EQ(times.names().at(std::size_t(stages[i])), terms[i]->name()) << i;
}

TEST(ForceTerms, TheEffectsListNamesEveryEffectInItsOrder) {
  const Scene full = everything();
  EXPECT_EQ(physics_effects(full, make_cloth_model(full)),
            (std::vector<std::string>{"stretch", "bending", "gravity", "wind", "gusts",
                                      "turbulence", "damping", "pole"}));
  Scene touching = full;  // self-contact: a projection, named last
  touching.contact = Contact{};
  EXPECT_EQ(physics_effects(touching, make_cloth_model(touching)).back(), "contact");
  const Scene bare = test::small_cloth();  // no damping either
  EXPECT_EQ(physics_effects(bare, make_cloth_model(bare)), std::vector<std::string>{"stretch"});
}

}  // namespace
}  // namespace flagsim::physics
