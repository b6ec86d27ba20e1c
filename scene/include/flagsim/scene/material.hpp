#pragma once
// The cloth's material, stated once in a scene and read by everything that
// simulates or fills the cloth: every physics backend (a force form for the
// integrators, a constraint form for XPBD and Bullet) and the infill (its
// wrinkles from the yarn). SI units, per unit area or width of the sheet.
//
// Bending is stated either as the sheet's rigidity D (`[bending] stiffness`,
// N m) or as the paper's yarn, radius r and modulus E (eqs. (1)-(10)). A
// sheet woven of round yarns side by side (2 r apart), each a rod of bending
// stiffness E I = E pi r^4 / 4, has per unit width
//
//   D = E pi r^4 / 4 / (2 r) = pi E r^3 / 8,
//
// and the paper's k r^4 of one yarn (eq. (10): k = 1/2 E pi / 4,
// infill::bending_constant_k_r4) is pi E r^4 / 8 = D r. So the yarn gives D; D and r give E = 8 D /
// (pi r^3). The paper's own example (r = 1 mm, E = 1 GPa) is a stiff sheet (D = 0.39 N m, a plastic
// film's); flag fabric has D ~ 1e-5 to 1e-4 N m (r ~ 0.1 mm yarns of E ~ 1-10 GPa).
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "flagsim/scene/scene.hpp"

namespace flagsim {

/// The paper's yarn: a round fiber of radius r and Young's modulus E.
struct Yarn {
  double radius_m = 1.0e-3;
  double modulus_pa = 1.0e9;
  /// D of a sheet of these yarns side by side: pi E r^3 / 8, N m.
  double sheet_rigidity_j() const;
};

/// The yarn [wrinkles] takes when the scene states none (the paper's example).
inline constexpr Yarn kDefaultYarn{};

struct Material {
  double areal_density_kg_m2 = 0.0;  ///< flag.areal_density
  double stretch_modulus_n_m = 0.0;  ///< Y, flag.stretch_modulus
  double shear_modulus_n_m = 0.0;    ///< G, flag.shear_modulus
  double damping_per_s = 0.0;        ///< c, flag.damping
  /// D, N m: the physics' bending ([bending]); nullopt: none (Terzopoulos 1987).
  std::optional<double> bending_rigidity_j;
  /// The yarn step 3.5 bends (k r^4 = pi E r^4 / 8). With [bending], the one
  /// whose sheet has its D: r as stated in [bending] or [wrinkles] (else
  /// kDefaultYarn's), E as stated or 8 D / (pi r^3). Without, [wrinkles]' own
  /// keys, each kDefaultYarn's where absent (the physics has no bending then).
  Yarn yarn;
  /// [creases]: the bending's rest angles set and relax; nullopt: no creases.
  std::optional<Creases> creases;
  /// Whether the physics' bending is creased: [creases] and a bending D to crease.
  bool creased() const { return creases.has_value() && bending_rigidity_j.has_value(); }
};

/// Called with a key ("wrinkles.fiber_modulus") and what is wrong with it
/// where a scene states two materials; must throw.
using MaterialFail = std::function<void(std::string_view key, const std::string& message)>;

/// The material `scene` states; `fail` where it states two: [bending] and
/// [wrinkles] giving different yarns, a modulus whose sheet is not as stiff
/// as bending.stiffness, a modulus without a radius.
Material material_of(const Scene& scene, const MaterialFail& fail);
/// The same, throwing UserError("scene: KEY: ...").
Material material_of(const Scene& scene);

}  // namespace flagsim
