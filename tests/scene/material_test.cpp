#include "flagsim/scene/material.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "flagsim/core/errors.hpp"
#include "flagsim/scene/scene_parser.hpp"

namespace flagsim {
namespace {

constexpr const char* kHybrid = R"(
[scene]
mode = "hybrid"
[flag]
size = [1.5, 1.0]
fine = [17, 25]
coarse = [5, 7]
areal_density = 0.3
stretch_modulus = 1.5e4
shear_modulus = 1.0e3
damping = 0.2
)";

Scene parse(const std::string& tables) {
  return parse_scene(std::string(kHybrid) + tables, "m.toml");
}

std::string error_of(const std::string& tables) {
  try {
    parse(tables);
  } catch (const UserError& e) {
    return e.what();
  }
  return "";
}

TEST(Material, IsTheFlagsConstantsWithoutBendingAndThePapersYarn) {
  const Material m = material_of(parse(""));
  EXPECT_EQ(m.areal_density_kg_m2, 0.3);
  EXPECT_EQ(m.stretch_modulus_n_m, 1.5e4);
  EXPECT_EQ(m.shear_modulus_n_m, 1.0e3);
  EXPECT_EQ(m.damping_per_s, 0.2);
  EXPECT_FALSE(m.bending_rigidity_j.has_value());  // no [bending]: none (Terzopoulos 1987)
  EXPECT_EQ(m.yarn.radius_m, kDefaultYarn.radius_m);
  EXPECT_EQ(m.yarn.modulus_pa, kDefaultYarn.modulus_pa);
}

TEST(Material, AYarnSideBySideHasRigidityPiEr3Over8) {
  // r = 0.1 mm, E = 2 GPa: D = pi 2e9 1e-12 / 8 = 7.85e-4 N m, by hand.
  const Yarn yarn{1.0e-4, 2.0e9};
  EXPECT_NEAR(yarn.sheet_rigidity_j(), std::numbers::pi * 2.0e9 * 1.0e-12 / 8.0, 1e-18);
  const Scene scene = parse("[bending]\nfiber_radius = 1.0e-4\nfiber_modulus = 2.0e9\n");
  const Material m = material_of(scene);
  ASSERT_TRUE(m.bending_rigidity_j.has_value());
  EXPECT_EQ(*m.bending_rigidity_j, yarn.sheet_rigidity_j());
  EXPECT_EQ(m.yarn.radius_m, 1.0e-4);
  EXPECT_EQ(m.yarn.modulus_pa, 2.0e9);
}

TEST(Material, StiffnessAndARadiusGiveTheYarnsModulus) {
  // D = 1e-4 N m from yarns of r = 0.2 mm: E = 8 D / (pi r^3) = 3.18 GPa,
  // and a sheet of those yarns has D again.
  const Material m = material_of(parse("[bending]\nstiffness = 1.0e-4\nfiber_radius = 2.0e-4\n"));
  EXPECT_EQ(*m.bending_rigidity_j, 1.0e-4);
  EXPECT_NEAR(m.yarn.modulus_pa, 8.0e-4 / (std::numbers::pi * 8.0e-12), 1e-3);
  EXPECT_NEAR(m.yarn.sheet_rigidity_j(), 1.0e-4, 1e-18);
}

TEST(Material, WrinklesTakeTheYarnOfBendingOrTheirOwn) {
  const Material from_bending = material_of(parse(
      "[bending]\nfiber_radius = 1.0e-4\nfiber_modulus = 2.0e9\n[wrinkles]\nk_prime = 2.0\n"));
  EXPECT_EQ(from_bending.yarn.radius_m, 1.0e-4);
  EXPECT_EQ(from_bending.yarn.modulus_pa, 2.0e9);
  // Restating the same yarn is the same material.
  EXPECT_NO_THROW(
      parse("[bending]\nfiber_radius = 1.0e-4\nfiber_modulus = 2.0e9\n[wrinkles]\nfiber_radius = "
            "1.0e-4\n"));
  // Without [bending], [wrinkles] states the yarn (and the physics has no bending).
  const Material own =
      material_of(parse("[wrinkles]\nfiber_radius = 5.0e-4\nfiber_modulus = 3.0e9\n"));
  EXPECT_FALSE(own.bending_rigidity_j.has_value());
  EXPECT_EQ(own.yarn.radius_m, 5.0e-4);
  EXPECT_EQ(own.yarn.modulus_pa, 3.0e9);
}

TEST(Material, TwoStatementsOfTheBendingAreRefusedWithTheKeyAndLine) {
  EXPECT_EQ(error_of("[bending]\nfiber_modulus = 2.0e9\n"),
            "m.toml:13:17: bending.fiber_modulus: a yarn needs its radius too "
            "(bending.fiber_radius, m)");
  EXPECT_EQ(error_of("[bending]\nstiffness = 1e-4\nfiber_radius = 1e-4\nfiber_modulus = 2e9\n"),
            "m.toml:15:17: bending.fiber_modulus: the yarn's modulus and `stiffness` both state "
            "the bending (D = pi E r^3 / 8); state one of them");
  EXPECT_EQ(error_of("[bending]\nfiber_radius = 1e-4\n[wrinkles]\nfiber_radius = 2e-4\n"),
            "m.toml:15:16: wrinkles.fiber_radius: 0.0002 m, but [bending] states 0.0001 m: the "
            "cloth has one material; leave it out of [wrinkles]");
  // [bending]'s D (default 1e-4 N m) and [wrinkles]' yarn (r = 1 mm, E = 1 GPa: D = 0.39 N m).
  EXPECT_EQ(error_of("[bending]\n[wrinkles]\nfiber_modulus = 1e9\n"),
            "m.toml:14:17: wrinkles.fiber_modulus: 1e+09 Pa: a sheet of these yarns (r = 0.001 m) "
            "has D = pi E r^3 / 8 = 0.392699 N m, but bending.stiffness is 0.0001 N m; state the "
            "stiffness or the yarn's modulus, not both (with the radius alone, E = 8 D / (pi r^3) "
            "= 254648 Pa)");
  // r = 1 cm, E = 1 TPa: D = 3.9e5 N m, past the stiffness key's bound of 1 N m.
  EXPECT_NE(error_of("[bending]\nfiber_radius = 0.01\nfiber_modulus = 1e12\n")
                .find("bending.fiber_modulus: a sheet of these yarns has D = pi E r^3 / 8 = "
                      "392699 N m: expected at most 1 N m"),
            std::string::npos);
}

TEST(Material, ASceneBuiltInCodeIsCheckedForOneMaterialToo) {
  Scene scene = parse("[bending]\nfiber_radius = 1.0e-4\nfiber_modulus = 2.0e9\n");
  EXPECT_NO_THROW(check_scene(scene));
  scene.bending->rigidity_j = 1e-3;  // no longer what the yarn gives
  try {
    check_scene(scene);
    ADD_FAILURE() << "an inconsistent material was accepted";
  } catch (const UserError& e) {
    EXPECT_EQ(std::string(e.what()),
              "scene: bending.fiber_modulus: 2e+09 Pa: a sheet of these yarns (r = 0.0001 m) has "
              "D = pi E r^3 / 8 = 0.000785398 N m, but bending.stiffness is 0.001 N m; state the "
              "stiffness or the yarn's modulus, not both (with the radius alone, E = 8 D / (pi "
              "r^3) = 2.54648e+09 Pa)");
  }
  scene = parse("[bending]\nfiber_radius = 1.0e-4\n");
  scene.wrinkles = Wrinkles{};
  scene.wrinkles->fiber_modulus_pa = 1e9;
  EXPECT_THROW(check_scene(scene), UserError);  // [wrinkles] restates the yarn differently
  scene.wrinkles->fiber_modulus_pa.reset();
  scene.bending->fiber_radius_m = -1.0;
  EXPECT_THROW(check_scene(scene), UserError);
}

}  // namespace
}  // namespace flagsim
