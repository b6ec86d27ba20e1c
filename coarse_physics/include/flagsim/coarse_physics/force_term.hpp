#pragma once
// One force acting on the cloth: a stage of the physics pipeline. A term is
// constructed only when the scene calls for its effect.
//
// Shapes: positions x [J*K] in m, velocities v [J*K] in m/s, forces [J*K] in N,
// all row-major over the lattice.
//
// Besides its force, a term gives what each stepper needs of it: its energy
// (conservative terms), a stiffness bound (the explicit steppers' stability
// limit) and its derivatives at a state (the implicit stepper's Newton matrix,
// as products and 3x3 diagonal blocks, never assembled).
#include <Eigen/Core>
#include <span>
#include <string_view>

#include "flagsim/coarse_physics/wind_field.hpp"
#include "flagsim/core/vec3.hpp"

namespace flagsim::physics {

using Mat3 = Eigen::Matrix3d;

/// How linearize() keeps a term's derivatives.
enum class Definiteness {
  kExact,      ///< -df/dx and -df/dv as they are (the finite-difference tests)
  kProjected,  ///< each element's block made positive semidefinite, so that the
               ///< implicit stepper's matrix M + h C + h^2 K is symmetric positive
               ///< definite; what is dropped (a compressed link's negative
               ///< transverse stiffness, the wind's non-dissipative lift
               ///< response) stays in the residual, so Newton's fixed point is
               ///< unchanged and only its convergence rate is
};

/// How often a stepper must evaluate a term's force (SpringDamperSolver
/// evaluates the last two once per hold of several substeps).
enum class ForceTiming {
  kEverySubstep,  ///< stiff in x or v (springs, bending): every substep
  kConstant,      ///< never changes (gravity): once per hold, exactly
  kSlow,          ///< changes on the flap's time scale (the wind on its panels): may be
                  ///< held while velocity_rate_bound() x the hold stays small
};

class ForceTerm {
 public:
  virtual ~ForceTerm() = default;
  /// Name of the effect ("stretch", "gravity", ...): a column of /stats/stage_seconds.
  virtual std::string_view name() const = 0;
  /// Called at the start of every output frame with its time and positions: a
  /// term whose inputs change slowly (the wind field) refreshes them here
  /// rather than in every substep.
  virtual void begin_frame(double /*time_s*/, std::span<const Vec3> /*x_m*/) {}
  /// Adds this term's force on every node to `forces_n`.
  virtual void add_forces(std::span<const Vec3> x_m, std::span<const Vec3> v_m_s,
                          std::span<Vec3> forces_n) const = 0;
  /// Potential energy, J, whose negative gradient is the force; 0 for a
  /// non-conservative term.
  virtual double energy(std::span<const Vec3> /*x_m*/) const { return 0.0; }
  /// Adds, per node i, an upper bound of sum_j ||d f_i / d x_j|| (N/m): the
  /// block Gershgorin row sum used for the stability limit.
  virtual void add_stiffness_bound(std::span<double> /*row_sum_n_m*/) const {}
  /// Upper bound of ||d f_i / d v_i|| / m_i over the nodes, 1/s.
  virtual double velocity_rate_bound() const { return 0.0; }
  /// Whether a stepper may hold this term's force over several substeps.
  virtual ForceTiming timing() const { return ForceTiming::kEverySubstep; }
  /// The wind's term: its mean wind and the turbulence's drift (wind_field.hpp);
  /// nullptr for every other term.
  virtual const WindField* wind_field() const { return nullptr; }
  /// The wind's term takes `drift` (a new mean wind, or a saved state) from the
  /// next frame on, at positions x_m and time time_s; false for other terms.
  virtual bool set_wind_drift(const WindField::Drift& /*drift*/, double /*time_s*/,
                              std::span<const Vec3> /*x_m*/) {
    return false;
  }

  /// What a later frame depends on besides the positions and velocities (a
  /// crease's rest angles, creased_bending.hpp): saved with the state
  /// (ClothState::memory) and restored into the term at every frame's start.
  /// Empty for a term without memory.
  virtual std::span<const double> memory() const { return {}; }
  virtual void set_memory(std::span<const double> /*memory*/) {}
  /// Evaluates and keeps the derivatives at (x, v) that the products below
  /// use (the implicit stepper calls it once per Newton iteration).
  virtual void linearize(std::span<const Vec3> /*x_m*/, std::span<const Vec3> /*v_m_s*/,
                         Definiteness /*how*/) {}
  /// out += K dx with K = -df/dx (N/m; the energy's Hessian for a conservative
  /// term) at the last linearization. A term that has no position derivative
  /// in the implicit matrix (the wind's: it is not conservative) adds nothing.
  virtual void add_stiffness_product(std::span<const Vec3> /*dx_m*/,
                                     std::span<Vec3> /*out_n*/) const {}
  /// diagonal[i] += K_ii, N/m.
  virtual void add_stiffness_diagonal(std::span<Mat3> /*diagonal_n_m*/) const {}
  /// out += C dv with C = -df/dv (N s/m) at the last linearization.
  virtual void add_damping_product(std::span<const Vec3> /*dv_m_s*/,
                                   std::span<Vec3> /*out_n*/) const {}
  /// diagonal[i] += C_ii, N s/m.
  virtual void add_damping_diagonal(std::span<Mat3> /*diagonal_n_s_m*/) const {}
};

}  // namespace flagsim::physics
