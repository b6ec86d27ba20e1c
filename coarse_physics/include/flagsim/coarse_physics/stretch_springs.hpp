#pragma once
// Structural (row, column) and shear (diagonal) springs of the cloth model.
// Energy per link: 1/2 k (|x_b - x_a| - S)^2; force on b: -k (|d| - S) d/|d|.
//
// Hessian of one link, with d = x_b - x_a, l = |d|, n = d/l:
//   H = k [ n n^T + (1 - S/l) (I - n n^T) ],   d^2E/dx_a^2 = d^2E/dx_b^2 = H,
//   d^2E/dx_a dx_b = -H.
// A compressed link (l < S) has a negative transverse part (it buckles);
// Definiteness::kProjected drops it.
//
// Speed: add_forces runs every substep (the largest stage of the explicit
// reference). Each family's link forces are computed four links at a time
// along the lattice rows (core/lanes.hpp) into an array by the link's first
// node, and each node then adds its links' forces family by family, the link
// that ends at it before the one that starts at it: the order of the link
// loop, so the forces are the same bits as one link at a time (a test checks).
#include <array>
#include <cstdint>
#include <vector>

#include "flagsim/coarse_physics/cloth_model.hpp"
#include "flagsim/coarse_physics/force_term.hpp"

namespace flagsim::physics {

class StretchSprings final : public ForceTerm {
 public:
  explicit StretchSprings(const ClothModel& model);
  std::string_view name() const override { return "stretch"; }
  void add_forces(std::span<const Vec3> x_m, std::span<const Vec3> v_m_s,
                  std::span<Vec3> forces_n) const override;
  double energy(std::span<const Vec3> x_m) const override;
  void add_stiffness_bound(std::span<double> row_sum_n_m) const override;
  void linearize(std::span<const Vec3> x_m, std::span<const Vec3> v_m_s, Definiteness how) override;
  void add_stiffness_product(std::span<const Vec3> dx_m, std::span<Vec3> out_n) const override;
  void add_stiffness_diagonal(std::span<Mat3> diagonal_n_m) const override;

 private:
  const ClothModel& model_;
  struct Link {
    std::uint32_t a = 0, b = 0;
  };
  std::vector<Link> links_;    ///< every link of every family, in for_each_link order
  std::vector<Mat3> hessian_;  ///< [links] H at the last linearization, N/m

  /// The positions split into x, y, z arrays and the forces being summed,
  /// [J*K] each, padded past the end (a lane may read a node beyond the
  /// last, and discards it); each family's link forces on its first node a,
  /// [pad + J*K] per coordinate, link (a, a + offset) at pad + a, 0 where no
  /// link starts (so that a node adds 0 for a link it does not have).
  struct Workspace {
    std::size_t pad = 0;
    std::vector<double> x[3], f[3];
    std::array<std::vector<double>, 3> link[4];
  };
  /// One family's link forces, on their first nodes.
  void family_forces(int family) const;
  /// Every node's link forces added to work_.f, in the link loop's order.
  void sum_links() const;
  mutable Workspace work_;
};

}  // namespace flagsim::physics
