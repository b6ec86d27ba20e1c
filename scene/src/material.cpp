#include "flagsim/scene/material.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "flagsim/core/errors.hpp"

namespace flagsim {

double Yarn::sheet_rigidity_j() const {
  return std::numbers::pi * modulus_pa * radius_m * radius_m * radius_m / 8.0;
}

Material material_of(const Scene& scene, const MaterialFail& fail) {
  Material material;
  material.areal_density_kg_m2 = scene.flag.areal_density_kg_m2;
  material.stretch_modulus_n_m = scene.flag.stretch_modulus_n_m;
  material.shear_modulus_n_m = scene.flag.shear_modulus_n_m;
  material.damping_per_s = scene.flag.damping_per_s;
  material.yarn = kDefaultYarn;
  material.creases = scene.creases;
  const std::optional<Wrinkles>& wrinkles = scene.wrinkles;
  if (!scene.bending) {  // no bending in the physics: the yarn is [wrinkles]' alone
    if (wrinkles)
      material.yarn = Yarn{wrinkles->fiber_radius_m.value_or(kDefaultYarn.radius_m),
                           wrinkles->fiber_modulus_pa.value_or(kDefaultYarn.modulus_pa)};
    return material;
  }
  // The bending is stated: the yarn is the one that gives it (D = pi E r^3 / 8),
  // each of r and E stated in [bending] or [wrinkles], or neither.
  const Bending& bending = *scene.bending;
  const double rigidity = bending.rigidity_j;
  material.bending_rigidity_j = rigidity;
  const auto one_of = [&](const char* name, const std::optional<double>& in_bending,
                          const std::optional<double> Wrinkles::*member,
                          const char* unit) -> std::optional<double> {
    const std::optional<double> in_wrinkles =
        wrinkles ? (*wrinkles).*member : std::optional<double>{};
    if (in_bending && in_wrinkles && *in_bending != *in_wrinkles)
      fail(fmt::format("wrinkles.{}", name),
           fmt::format("{:g} {}, but [bending] states {:g} {}: the cloth has one material; "
                       "leave it out of [wrinkles]",
                       *in_wrinkles, unit, *in_bending, unit));
    return in_bending ? in_bending : in_wrinkles;
  };
  const std::optional<double> radius =
      one_of("fiber_radius", bending.fiber_radius_m, &Wrinkles::fiber_radius_m, "m");
  const std::optional<double> modulus =
      one_of("fiber_modulus", bending.fiber_modulus_pa, &Wrinkles::fiber_modulus_pa, "Pa");
  const char* modulus_key =
      bending.fiber_modulus_pa ? "bending.fiber_modulus" : "wrinkles.fiber_modulus";
  if (bending.fiber_modulus_pa && !bending.fiber_radius_m)
    fail("bending.fiber_modulus", "a yarn needs its radius too (bending.fiber_radius, m)");
  const double r = radius.value_or(kDefaultYarn.radius_m);
  const double from_rigidity = 8.0 * rigidity / (std::numbers::pi * r * r * r);
  material.yarn = Yarn{r, modulus.value_or(from_rigidity)};
  if (modulus) {
    const double sheet = material.yarn.sheet_rigidity_j();
    if (!(std::abs(sheet - rigidity) <= 1e-12 * sheet))
      fail(modulus_key,
           fmt::format("{:g} Pa: a sheet of these yarns (r = {:g} m) has D = pi E r^3 / 8 = {:g} "
                       "N m, but bending.stiffness is {:g} N m; state the stiffness or the "
                       "yarn's modulus, not both (with the radius alone, E = 8 D / (pi r^3) = "
                       "{:g} Pa)",
                       *modulus, r, sheet, rigidity, from_rigidity));
  }
  return material;
}

Material material_of(const Scene& scene) {
  return material_of(scene, [](std::string_view key, const std::string& message) {
    throw UserError(fmt::format("scene: {}: {}", key, message));
  });
}

}  // namespace flagsim
