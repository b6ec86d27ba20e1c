#pragma once
// The air around the flag as an unsteady vortex lattice with a shed wake
// (wind.model = "vortex"; Katz & Plotkin, Low-Speed Aerodynamics, 2nd ed.,
// sections 12.3 and 13.12), linearised about the flag's rest plane z = 0.
//
// EXPERIMENTAL: checked against lifting-surface theory (tests), but on a
// flapping flag it does not converge with the lattice and makes the waves
// shorter (docs/flag_physics.md, measured 2026-12-05); the linearisation is
// the suspected cause. The default air is the panel wind (aero_force.hpp).
//
// Why: the quasi-steady lift (aero_force.hpp) is local and has no inertia. A
// real flag's pressure comes from the air around it: it is non-local (a wave
// of wavenumber k carries about 2 rho / k of air per area, the flag as a whole
// rho pi H / 4), it lags the motion through the wake the flag sheds, and the
// air's inertia, about five times the fabric's, is what carries a real flag's
// waves at about the wind speed (docs/flag_physics.md).
//
// The lattice: the panels of AirPanels (wind.panel, 8 x 12 on the default
// flag), one vortex ring per panel, its leading segment a quarter panel
// behind the panel's leading edge, its collocation point at three quarters
// of the chord, mid-span (K&P eq. 12.2 ff.). The geometry stays in the rest
// plane (the linear theory), so the influence matrix A (P x P, P panels) and
// the wake's (P x S Nw) are computed once and A inverted once.
//
// Per substep, with the panels' actual normals n_p (from their diagonals) and
// the velocities v_p and air velocities u_p at the collocation points:
//
//   A Gamma = (v_p - u_p) . n_p - w_wake                 (no flow through the panel)
//   f_p = -rho A_p [ U_p (Gamma_p - Gamma_p-) / dx + dGamma_p / dt ] e_z     (K&P 13.37)
//
// Gamma_p- the circulation of the panel ahead in the same strip (0 at the
// leading edge), U_p the air's speed along the chord, A_p the panel's rest
// area; f_p is spread a quarter to each panel corner and from there to the
// cloth with the panels' weights (air_panels.hpp). The signs: a ring of
// positive Gamma turns counter-clockwise about +z and induces +z flow inside.
//
// The wake: at every aero step dt_a = dx / U (the time the air takes to cross
// a panel), the trailing panels' circulations are shed into the first wake
// row and every row moves one panel down the wind (a frozen, planar wake:
// the linear theory), Nw rows (wake_lengths flag lengths), the last row
// reaching far downstream. Its induced normal flow at the collocation points
// is taken as linear in time between the last two aero steps (so that
// dGamma/dt stays finite: the wake acts one aero step late).
//
// The air's inertia (dGamma/dt's part in the acceleration, the added mass)
// is implicit: dGamma/dt = A^-1 (a_p . e_z + (v_p - u_p) . dn_p/dt - dw_wake/dt),
// and its a_p part is moved to the left of M a = f. With the spread U, the
// sampling V (cloth nodes -> collocation points) and C = rho diag(A_p) A^-1,
// (M + U C V^T) a = f is solved by Woodbury's identity,
//
//   a = y - M^-1 U K^-1 V^T y,   y = M^-1 f,   K = C^-1 + V^T M^-1 U    (P x P, constant)
//
// for the out-of-plane components, which keeps every step explicit and
// stable: an added mass five times the cloth's taken explicitly is the
// classic added-mass instability of partitioned fluid-structure coupling.
//
// What it leaves out: the wake's roll-up and its motion with the flag (the
// wake stays in the rest plane, moving at the mean wind along x), the
// spanwise flow, and separation (the quasi-steady drag and skin friction of
// aero_force.hpp stay on; its quasi-steady lift is turned off). Only the
// mass-spring integrator (and so the hybrid) solves with the added mass.
#include <Eigen/Dense>
#include <cstdint>
#include <span>
#include <vector>

#include "flagsim/coarse_physics/air_panels.hpp"
#include "flagsim/coarse_physics/cloth_model.hpp"
#include "flagsim/coarse_physics/wind_field.hpp"
#include "flagsim/scene/scene.hpp"

namespace flagsim::physics {

/// Normal velocity (along +z) induced at `point` by a vortex segment a -> b
/// of unit circulation (K&P's VORTXL, eq. 10.115), m/s per m^2/s. Zero within
/// `core_m` of the segment's line.
Vec3 segment_induced_velocity(const Vec3& point, const Vec3& a, const Vec3& b, double core_m);

class VortexWake {
 public:
  /// @param inverse_mass_1_kg  [cloth nodes] 1/m_i, 0 for a pinned node
  VortexWake(const ClothModel& model, const Wind& wind, std::uint64_t seed,
             std::span<const double> inverse_mass_1_kg, double wake_lengths = 3.0);

  /// Once per output frame: the air's velocity at the panel nodes (gusts, turbulence).
  void begin_frame(double time_s, std::span<const Vec3> x_m);
  /// Sheds the wake rows whose aero steps fall at or before `time_s`.
  void advance_to(double time_s);
  /// Adds every part of the force but the added mass's (see above) at time_s.
  void add_forces(double time_s, std::span<const Vec3> x_m, std::span<const Vec3> v_m_s,
                  std::span<Vec3> forces_n);
  /// Replaces the accelerations `a` = f / m (0 for pinned nodes) by the solution of
  /// (M + U C V^T) a = f: only their z components change.
  void add_air_inertia(std::span<Vec3> a_m_s2) const;
  /// For tests: adds the added-mass force -U C V^T a of the accelerations `a`
  /// (the part of the force add_air_inertia moves to the left side).
  void add_added_mass_force(std::span<const Vec3> a_m_s2, std::span<Vec3> forces_n) const;
  /// |d f / d v| / m bound of the circulatory force, 1/s (the stability limit).
  double velocity_rate_bound() const;

  /// For tests: the panels' circulations at the last add_forces, m^2/s, and the
  /// influence matrix (P x P), the aero step.
  const Eigen::VectorXd& circulation() const { return gamma_; }
  const Eigen::MatrixXd& influence() const { return influence_; }
  double aero_step_s() const { return aero_step_s_; }
  int panel_rows() const { return rows_; }
  int panel_cols() const { return cols_; }
  /// The added-mass matrix C = rho diag(A_p) A^-1 (P x P), kg per panel.
  Eigen::MatrixXd added_mass() const;

 private:
  /// Cloth values -> panel nodes (x, y, z arrays).
  void to_panels(std::span<const Vec3> cloth, std::vector<double> (&out)[3]) const;
  /// The panels' values at their collocation points from panel-node values.
  double at_collocation(const std::vector<double>& nodes, int p) const;
  /// The z components of cloth vectors at the collocation points (V^T).
  Eigen::VectorXd sample_collocation_z(std::span<const Vec3> cloth) const;
  /// Adds per-panel z forces, a quarter to each corner, to the cloth (U).
  void spread_panel_z(const Eigen::VectorXd& per_panel, std::span<Vec3> out) const;

  AirPanels panels_;
  Wind wind_;
  WindField field_;
  int rows_ = 0, cols_ = 0;  ///< panel strips (span) and panels per strip (chord)
  int wake_rows_ = 0;
  double dx_m_ = 0.0, dy_m_ = 0.0, area_m2_ = 0.0;
  double speed_m_s_ = 0.0;  ///< the mean wind's speed along the chord
  double aero_step_s_ = 0.0;
  double areal_density_kg_m2_ = 0.0;
  double next_shed_s_ = 0.0, last_shed_s_ = 0.0;
  Eigen::MatrixXd influence_;               ///< A, [P x P]
  Eigen::MatrixXd inverse_;                 ///< A^-1
  Eigen::MatrixXd wake_influence_;          ///< [P x rows_ Nw]
  Eigen::MatrixXd woodbury_;                ///< K^-1
  Eigen::VectorXd wake_gamma_;              ///< [rows_ Nw], row-major by wake row
  Eigen::VectorXd wake_w_, wake_w_before_;  ///< the wake's normal flow at the last two sheds
  Eigen::VectorXd gamma_, rhs_, rate_rhs_, rate_;
  std::vector<Vec3> air_m_s_;  ///< [panel nodes]
  std::vector<double> inverse_mass_;
  mutable std::vector<double> px_[3], pv_[3], pair_[3], scratch_[3];
  mutable std::vector<Vec3> cloth_scratch_;
};

}  // namespace flagsim::physics
