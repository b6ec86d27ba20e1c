#pragma once
// The discrete cloth: node masses and spring constants derived from the
// continuum parameters of the scene, so that the same scene is the same cloth
// at any lattice resolution.
//
// With rest spacings dx (along rows) and dy (along columns):
//  - mass of a node = areal density * the area it stands for: dx*dy inside,
//    half on an edge, a quarter at a corner (total = density * w * h);
//  - a row link stands for a strip of cloth dy wide: k = Y * dy / dx (Y the
//    2D stretch modulus, N/m), half that on the top and bottom edges, so the
//    strip stretches by Y * strain per unit width whatever dx and dy are;
//    column links likewise with k = Y * dx / dy;
//  - the two diagonals of each cell give the in-plane shear modulus G (N/m):
//    a shear gamma stretches each by gamma*dx*dy/d, and 2 * 1/2 k_d (gamma dx dy/d)^2
//    over the cell area dx*dy equals 1/2 G gamma^2 for k_d = G d^2 / (2 dx dy);
//  - bending (optional, rigidity D in N m) acts on every three consecutive nodes
//    of a row or column, see bending_springs.hpp.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "flagsim/coarse_physics/pin_motion.hpp"
#include "flagsim/core/lattice.hpp"
#include "flagsim/scene/material.hpp"
#include "flagsim/scene/scene.hpp"

namespace flagsim::physics {

/// All links (a, b) with b = a + offset, for one neighbour direction.
struct LinkFamily {
  int row_step = 0;          ///< dj of b relative to a
  int col_step = 0;          ///< dk of b relative to a
  double rest_length_m = 0;  ///< S of every link of the family
  double stiffness_n_m = 0;  ///< k of an interior link
  double edge_factor = 1.0;  ///< k multiplier for links along the lattice border
};

/// The cloth of one lattice, compiled from its material: immutable once
/// built, shared by whatever steps it (backends hold it by shared_ptr).
struct ClothModel {
  Lattice lattice;
  Material material;                   ///< what the numbers below are made from
  std::vector<double> mass_kg;         ///< [J*K]
  std::vector<std::uint8_t> pinned;    ///< [J*K], 1 = position prescribed
  PinMotion pin_motion{std::nullopt};  ///< how the pinned nodes move ([pole] motion)
  std::array<LinkFamily, 4> links;     ///< row, column, two diagonals

  /// Damping over a substep dt, implicit in time: v <- v / (1 + c dt). Every
  /// backend applies it: the explicit ones and XPBD as this factor, Bullet as
  /// its kDP = 1 - factor, implicit Euler as the mass scale 1 + c dt.
  double damping_mass_scale(double dt_s) const { return 1.0 + material.damping_per_s * dt_s; }
  double velocity_damping(double dt_s) const { return 1.0 / damping_mass_scale(dt_s); }
};

/// 1/2 sum m |v|^2, J: of a lattice's nodes, masses [n] kg and velocities [n] m/s.
double kinetic_energy_j(std::span<const double> mass_kg, std::span<const Vec3> v_m_s);

/// The cloth of `material` on `lattice` with the nodes of `pin` held, moving as `pole` says
/// (nullopt: at rest).
ClothModel make_cloth_model(const Material& material, const Lattice& lattice, PinSet pin,
                            const std::optional<PoleMotion>& pole);
/// The cloth of `scene` on its fine lattice (material_of(scene)).
ClothModel make_cloth_model(const Scene& scene);

/// Node indices held by `pin` (contract: flag.pin).
std::vector<std::uint8_t> pinned_nodes(const Lattice& lattice, PinSet pin);

/// Calls visit(a, b, k, rest) for every link of `family`; links on the border of
/// the lattice (half a strip of cloth) get k * edge_factor.
template <typename Visit>
void for_each_link(const ClothModel& model, const LinkFamily& family, Visit&& visit) {
  const Lattice& lattice = model.lattice;
  const int k_begin = family.col_step < 0 ? 1 : 0;
  const int k_end = lattice.cols - (family.col_step > 0 ? 1 : 0);
  const int j_end = lattice.rows - family.row_step;
  const long offset = long(family.row_step) * lattice.cols + family.col_step;
  const double edge_k = family.stiffness_n_m * family.edge_factor;
  for (int j = 0; j < j_end; ++j) {
    const bool border_row = family.row_step == 0 && (j == 0 || j == lattice.rows - 1);
    for (int k = k_begin; k < k_end; ++k) {
      const bool border = border_row || (family.col_step == 0 && (k == 0 || k == lattice.cols - 1));
      const std::size_t a = lattice.index(j, k);
      visit(a, std::size_t(long(a) + offset), border ? edge_k : family.stiffness_n_m,
            family.rest_length_m);
    }
  }
}

}  // namespace flagsim::physics
