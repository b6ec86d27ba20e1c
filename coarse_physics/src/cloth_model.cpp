#include "flagsim/coarse_physics/cloth_model.hpp"

#include <cmath>

namespace flagsim::physics {

std::vector<std::uint8_t> pinned_nodes(const Lattice& lattice, PinSet pin) {
  std::vector<std::uint8_t> pinned(lattice.node_count(), 0);
  for (int j = 0; j < lattice.rows; ++j) {
    for (int k = 0; k < lattice.cols; ++k) {
      bool held = false;
      switch (pin) {
        case PinSet::kLeft:
          held = k == 0;
          break;
        case PinSet::kRight:
          held = k == lattice.cols - 1;
          break;
        case PinSet::kTop:
          held = j == 0;
          break;
        case PinSet::kCorners:
          held = (j == 0 || j == lattice.rows - 1) && (k == 0 || k == lattice.cols - 1);
          break;
        case PinSet::kNone:
          break;
      }
      pinned[lattice.index(j, k)] = held ? 1 : 0;
    }
  }
  return pinned;
}

double kinetic_energy_j(std::span<const double> mass_kg, std::span<const Vec3> v_m_s) {
  double total = 0.0;
  for (std::size_t i = 0; i < v_m_s.size(); ++i) total += 0.5 * mass_kg[i] * v_m_s[i].squaredNorm();
  return total;
}

ClothModel make_cloth_model(const Material& material, const Lattice& lattice, PinSet pin,
                            const std::optional<PoleMotion>& pole) {
  ClothModel model;
  model.pin_motion = PinMotion(pole);
  model.lattice = lattice;
  model.material = material;
  const double dx = lattice.spacing_x_m, dy = lattice.spacing_y_m;
  const double density = material.areal_density_kg_m2;

  model.mass_kg.resize(lattice.node_count());
  for (int j = 0; j < lattice.rows; ++j) {
    const double row_share = (j == 0 || j == lattice.rows - 1) ? 0.5 : 1.0;
    for (int k = 0; k < lattice.cols; ++k) {
      const double col_share = (k == 0 || k == lattice.cols - 1) ? 0.5 : 1.0;
      model.mass_kg[lattice.index(j, k)] = density * dx * dy * row_share * col_share;
    }
  }
  model.pinned = pinned_nodes(lattice, pin);

  const double stretch = material.stretch_modulus_n_m;
  const double shear = material.shear_modulus_n_m;
  const double diagonal = std::hypot(dx, dy);
  const double k_diagonal = shear * diagonal * diagonal / (2.0 * dx * dy);
  model.links[0] = {0, 1, dx, stretch * dy / dx, 0.5};
  model.links[1] = {1, 0, dy, stretch * dx / dy, 0.5};
  model.links[2] = {1, 1, diagonal, k_diagonal, 1.0};
  model.links[3] = {1, -1, diagonal, k_diagonal, 1.0};
  return model;
}

ClothModel make_cloth_model(const Scene& scene) {
  return make_cloth_model(material_of(scene), scene.fine_lattice(), scene.flag.pin, scene.pole);
}

}  // namespace flagsim::physics
