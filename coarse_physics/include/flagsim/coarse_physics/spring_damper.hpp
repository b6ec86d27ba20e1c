#pragma once
// Our own spring-damper integrator (Terzopoulos-style cloth): the coarse physics
// of the hybrid mode, and on the full lattice the mass-spring baseline.
//
// Time stepping: symplectic (semi-implicit) Euler, with the velocity damping
// applied implicitly so that any damping rate is stable:
//   v <- (v + dt f(x, v) / m) / (1 + c dt),   x <- x + dt v.
// For the elastic part this is stable while dt * omega_max < 2. omega_max^2 is
// bounded by the block Gershgorin bound max_i sum_j ||K_ij|| / m_i over the
// free nodes (each term adds its share), and the explicit velocity-dependent
// wind force needs dt * rate < 1. The substep is kStabilitySafety of that limit;
// solver.substeps is only a minimum. Past the limit (which the solver never
// picks itself), the run is caught by the divergence checks of the run loop.
//
// Held forces (held_forces.hpp): the substep is set by the springs (0.13 ms
// on the default 9 x 13 coarse lattice, 8 us at 129 x 193), while the wind on
// its 0.25 m panels changes on the flap's time scale, so the wind and gravity
// are evaluated once every hold_substeps() substeps and extrapolated between;
// the springs and bending every substep. Not in scenes with obstacles ([pole]
// radius, [ground], [contact]), nor with the vortex lattice. On the default
// scene (rate bound 186/s) the hold is 0.54 ms, 4 substeps; at 129 x 193, 64.
// Measured 2026-12-07 (docs/flag_physics.md, "The wind held over substeps"):
// 0.2 s of the default coarse flag 0.6 um from every substep's run (11.5 um
// held constant, without the extrapolation); the default hybrid's flap over 27
// seeds within its seed scatter; the wind's stage 0.53 -> 0.13 ms a frame.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "flagsim/coarse_physics/cloth_model.hpp"
#include "flagsim/coarse_physics/cloth_state.hpp"
#include "flagsim/coarse_physics/force_term.hpp"
#include "flagsim/coarse_physics/held_forces.hpp"
#include "flagsim/coarse_physics/obstacles.hpp"
#include "flagsim/coarse_physics/pin_motion.hpp"
#include "flagsim/coarse_physics/stability.hpp"
#include "flagsim/coarse_physics/vortex_wake.hpp"
#include "flagsim/core/stage_times.hpp"
#include "flagsim/scene/scene.hpp"

namespace flagsim::physics {

class SpringDamperSolver {
 public:
  /// Steps `model` (the cloth, compiled once: sim::Model) under the rest of `scene`
  /// (the force terms its effects call for, pole, solver settings and start).
  SpringDamperSolver(const Scene& scene, std::shared_ptr<const ClothModel> model);
  /// The cloth of the scene's fine lattice (make_cloth_model(scene)).
  explicit SpringDamperSolver(const Scene& scene)
      : SpringDamperSolver(scene, std::make_shared<const ClothModel>(make_cloth_model(scene))) {}
  SpringDamperSolver(const SpringDamperSolver&) = delete;
  SpringDamperSolver& operator=(const SpringDamperSolver&) = delete;

  const ClothModel& model() const { return *model_; }
  /// Effects in pipeline order ("stretch,gravity,wind,damping,pole").
  const std::vector<std::string>& effects() const { return effects_; }

  /// The scene's start (physics::initial_state).
  const ClothState& initial_state() const { return initial_; }

  /// Largest stable substep (the bound above, before the safety factor), s.
  double stable_substep_s() const { return stable_substep_s_; }
  /// Substeps per output frame: max(solver.substeps, frame time / safe substep).
  int substeps_per_frame() const { return substeps_per_frame_; }
  double substep_s() const { return frame_s_ / substeps_per_frame_; }
  /// Substeps over which the slow and constant terms' forces are held (1: none held).
  int hold_substeps() const { return held_->hold_substeps(); }

  /// Registers one timing column per force term and one for the update.
  void register_stages(StageTimes& times);
  /// Advances `state` by one output frame; adds stage times if registered.
  void advance_frame(ClothState& state, StageTimes* times);
  /// One substep of dt seconds. The held forces are evaluated on the first
  /// call after construction or a frame's start and every hold_substeps()
  /// calls after.
  void step(ClothState& state, double dt_s, StageTimes* times);

  /// Prescribed motion for some nodes (the tracking run of `flag-sim compare`:
  /// the coarse nodes follow the hybrid's trajectory): after every substep,
  /// node nodes[i] is put at where(i, t) and given the velocity of that move.
  /// The stability limit is kept as computed with them free (conservative).
  using Driver = std::function<Vec3(std::size_t which, double time_s)>;
  void drive(std::vector<std::size_t> nodes, Driver where);

  /// Kinetic energy, J.
  double kinetic_energy(const ClothState& state) const;
  /// Sum of the conservative terms' potential energies, J.
  double potential_energy(const ClothState& state) const;
  /// The force terms, in pipeline order (for tests and benchmarks).
  const std::vector<std::unique_ptr<ForceTerm>>& terms() const { return terms_; }
  /// wind.model = "vortex": the air is the vortex lattice's (its wake fixed to the scene's wind).
  bool has_vortex() const { return vortex_ != nullptr; }

 private:
  std::shared_ptr<const ClothModel> model_;  ///< never null
  std::optional<Obstacles> obstacles_;       ///< [pole] radius, [ground]: projected after each step
  std::vector<Vec3> step_start_m_;           ///< [contact]: the positions a substep began from
  ClothState initial_;
  std::vector<Vec3> rest_m_;
  std::vector<double> inverse_mass_;
  std::vector<std::unique_ptr<ForceTerm>> terms_;
  std::vector<std::string> effects_;
  std::vector<Vec3> forces_n_;
  std::optional<HeldForces> held_;  ///< the wind and gravity, held over substeps
  /// wind.model = "vortex": the lift and the air's inertia (solved with the masses)
  std::unique_ptr<VortexWake> vortex_;
  int vortex_stage_ = -1;
  std::vector<std::size_t> driven_;
  Driver where_;
  std::vector<int> term_stage_;
  int update_stage_ = -1;
  double frame_s_ = 0.0;
  double stable_substep_s_ = 0.0;
  int substeps_per_frame_ = 1;
};

}  // namespace flagsim::physics
