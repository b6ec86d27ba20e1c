#pragma once
// Wind force on the cloth, per triangle, from the relative velocity of the air.
//
// Each lattice cell (j,k)-(j,k+1)-(j+1,k)-(j+1,k+1) is split into the triangles
// (00, 01, 10) and (01, 11, 10). For a triangle of area A and unit normal n,
// with u = wind - (mean velocity of its three nodes):
//
//   drag  F_D = 1/2 rho C_d A (u.n) |u.n| n                 (pressure of the normal flow)
//   lift  F_L = 1/2 rho C_l A (u.n) (|u| n - (u.n) u/|u|)
//
// F_L is perpendicular to u, in the plane of u and n, with magnitude
// 1/2 rho C_l A |u|^2 cos(phi) sin(phi) (phi the angle of u to n): zero for flow
// along the normal or along the plate, largest at 45 degrees. Both terms are
// unchanged when n flips, so both faces of the cloth catch the wind. A flat
// plate facing the flow gets 1/2 rho C_d A |u|^2, the textbook value. Each node
// of the triangle receives a third of the force.
//
// Skin friction along the plate, from the flow's tangential part u_t = u - (u.n) n:
//
//   friction F_f = 1/2 rho C_f A |u_t| u_t                   (both faces: C_f counts both)
//
// tensions the cloth from the pole like a real flag's boundary layer.
//
// The triangles are those of the panel lattice (air_panels.hpp), not the
// cloth's: the cloth is sampled onto panels of a fixed physical size
// (wind.panel), the force computed there and spread back with the same
// weights, so one shape and motion gets the same force field at every lattice
// and no wave shorter than about two panels is driven. A cloth no finer than
// the panels (the hybrid's coarse lattice) is its own panel lattice.
//
// The air's velocity comes from the WindField (mean, gusts, turbulence),
// sampled at the nodes once per output frame (begin_frame) and averaged over
// each triangle: gusts last seconds and turbulent eddies pass a node in about
// length_scale / |U|, both far longer than a substep.
//
// Speed: add_forces runs every substep of every backend (the wind was the
// largest stage of the explicit and XPBD references and half of the hybrid's
// coarse physics). The nodes are copied into one array per coordinate, each
// lattice row's triangles are computed four at a time side by side (vector
// lanes, two per cell), and each node then adds the thirds of its six
// triangles in the order the triangle loop would: every operation is the one
// triangle_aero_force makes, in the same order, so the forces are the same
// bits as one triangle at a time (the default scene's frames are identical).
#include <cstdint>
#include <vector>

#include "flagsim/coarse_physics/air_panels.hpp"
#include "flagsim/coarse_physics/cloth_model.hpp"
#include "flagsim/coarse_physics/force_term.hpp"
#include "flagsim/coarse_physics/wind_field.hpp"
#include "flagsim/scene/scene.hpp"

namespace flagsim::physics {

/// Force on one triangle (x0, x1, x2) in air moving at `relative_velocity` (m/s)
/// relative to the triangle, N. A degenerate triangle gets none.
Vec3 triangle_aero_force(const Vec3& x0, const Vec3& x1, const Vec3& x2,
                         const Vec3& relative_velocity, const Wind& wind);

/// dF/du of triangle_aero_force for the same arguments, N s/m: the wind's
/// velocity derivative (the air's velocity relative to the triangle is u, so a
/// node's velocity enters with -1/3). Drag's part, rho/4 C_d 2 |u.c| / |c|^2 c c^T, is
/// positive semidefinite; lift's part is not symmetric.
Mat3 triangle_aero_velocity_jacobian(const Vec3& x0, const Vec3& x1, const Vec3& x2,
                                     const Vec3& relative_velocity, const Wind& wind);

class AeroForce final : public ForceTerm {
 public:
  /// @param cloth_speed_bound_m_s  an estimate of the largest node speed (pole
  ///        motion, flapping), used only for the stability bound
  AeroForce(const ClothModel& model, const Wind& wind, std::uint64_t seed,
            double areal_density_kg_m2, double cloth_speed_bound_m_s);
  AeroForce(const AeroForce&) = delete;  // lattice_ refers to panels_' own lattice
  AeroForce& operator=(const AeroForce&) = delete;
  std::string_view name() const override { return "wind"; }
  void begin_frame(double time_s, std::span<const Vec3> x_m) override;
  void add_forces(std::span<const Vec3> x_m, std::span<const Vec3> v_m_s,
                  std::span<Vec3> forces_n) const override;
  double velocity_rate_bound() const override;
  /// The force on the panels changes as they move, on the flap's time scale
  /// (tenths of a second), not the springs' (tenths of a millisecond).
  ForceTiming timing() const override { return ForceTiming::kSlow; }
  const WindField* wind_field() const override { return &field_; }
  bool set_wind_drift(const WindField::Drift& drift, double time_s,
                      std::span<const Vec3> x_m) override;
  /// Keeps C_t = -d f_node / d v_node' = J_t / 9 of every triangle t (J_t its
  /// triangle_aero_velocity_jacobian; the same block for each of its 3 x 3 node
  /// pairs). kProjected keeps the symmetric part with negative eigenvalues
  /// clamped to 0. The position derivative is not kept: the wind is not
  /// conservative and the implicit stepper treats its change with x explicitly.
  void linearize(std::span<const Vec3> x_m, std::span<const Vec3> v_m_s, Definiteness how) override;
  void add_damping_product(std::span<const Vec3> dv_m_s, std::span<Vec3> out_n) const override;
  void add_damping_diagonal(std::span<Mat3> diagonal_n_s_m) const override;
  /// The panels the air sees the cloth on.
  const AirPanels& panels() const { return panels_; }

 private:
  /// Calls visit(a, b, c) for every triangle, in the order of damping_.
  template <typename Visit>
  void for_each_triangle(Visit&& visit) const;

  /// Positions, node velocities, air velocities and the forces being summed
  /// at the panel nodes, split into x, y, z arrays ([panel nodes] each); each triangle's third of
  /// its force, [(J-1)(K-1)] per coordinate, for the upper (00, 01, 10) and lower (01, 11, 10)
  /// triangle of a cell.
  struct Workspace {
    std::vector<double> x[3], v[3], air[3], f[3], upper[3], lower[3];
  };
  /// The cloth's `values` at the panel nodes ([panel nodes]); `values` itself
  /// when the panels are the cloth's nodes.
  std::span<const Vec3> on_panels(std::span<const Vec3> values, std::vector<Vec3>& out) const;
  /// One lattice row of cells (j, k) .. (j, K-2): their triangles' thirds.
  void row_thirds(int j) const;
  /// Every node's triangles' thirds added to work_.f, in the triangle loop's order.
  void gather_thirds() const;

  AirPanels panels_;
  const Lattice& lattice_;  ///< the panels' lattice: every loop below runs on it
  std::size_t cloth_nodes_;
  Wind wind_;
  WindField field_;
  std::vector<Vec3> air_m_s_;  ///< [panel nodes] air velocity at the panel nodes this frame
  mutable std::vector<Vec3> panel_x_, panel_v_,
      panel_out_;           ///< [panel nodes] linearize's, products'
  mutable Workspace work_;  ///< add_forces' arrays (no allocation per substep)
  /// [(Jp-1)(Kp-1)] per panel cell: its rest area over that of its sampled
  /// rest corners. A panel node on an edge samples the cloth under half a hat,
  /// so it sits about a third of a panel inside the edge; the cell's force is
  /// scaled back to the area it stands for (1 inside, and when the panels are
  /// the cloth's nodes), so a uniform pressure gives the same force per area
  /// on every cloth node and the whole flag its whole force.
  std::vector<double> cell_scale_;
  /// Each panel cell's lift coefficient: wind.lift, or 0 at the held edge
  /// (wind.lift_at_pole false).
  std::vector<double> cell_lift_;
  std::vector<Mat3> damping_;  ///< [2 (J-1)(K-1)] C_t at the last linearization, N s/m
  double areal_density_kg_m2_;
  double cloth_speed_bound_m_s_;
};

}  // namespace flagsim::physics
