#pragma once
// One force acting on the cloth: a stage of the physics pipeline. A term is
// constructed only when the scene calls for its effect.
//
// Shapes: positions x [J*K] in m, velocities v [J*K] in m/s, forces [J*K] in N,
// all row-major over the lattice.
#include <span>
#include <string_view>

#include "flagsim/core/vec3.hpp"

namespace flagsim::physics {

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
};

}  // namespace flagsim::physics
