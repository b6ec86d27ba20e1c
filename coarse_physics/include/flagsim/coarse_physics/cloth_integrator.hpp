#pragma once
// What advances a cloth in time, whichever backend does it (contract:
// solver.backend): our explicit spring-damper integrator, Bullet's soft body,
// backward Euler (implicit_euler.hpp) or XPBD (xpbd.hpp). All build the same
// cloth from a scene (ClothModel: masses from the area a node stands for, link
// stiffness from the stretch and shear moduli and the spacing) and own their
// state, which starts as physics::initial_state.
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "flagsim/coarse_physics/cloth_model.hpp"
#include "flagsim/coarse_physics/solver_note.hpp"
#include "flagsim/coarse_physics/spring_damper.hpp"
#include "flagsim/core/stage_times.hpp"
#include "flagsim/scene/scene.hpp"

namespace flagsim::physics {

class ClothIntegrator {
 public:
  virtual ~ClothIntegrator() = default;
  virtual const ClothModel& model() const = 0;
  /// Effects in pipeline order ("stretch,gravity,wind,damping,pole").
  virtual const std::vector<std::string>& effects() const = 0;
  /// Positions [J*K] m, velocities [J*K] m/s and time after the last frame.
  virtual const ClothState& state() const = 0;
  /// Continues from `state` (one that state() gave for this cloth: [J*K]
  /// positions and velocities, and its time); stepping on from it gives the
  /// same bytes as stepping on from where it was taken.
  virtual void set_state(const ClothState& state) = 0;
  /// Largest substep the backend treats as faithful (stability or stiffness limit), s.
  virtual double stable_substep_s() const = 0;
  virtual int substeps_per_frame() const = 0;
  virtual double substep_s() const = 0;
  /// Registers one timing column per stage.
  virtual void register_stages(StageTimes& times) = 0;
  /// Advances by one output frame (1/fps).
  virtual void advance_frame(StageTimes* times) = 0;
  /// Why the last frame's stepping cannot be trusted though its state may
  /// look sound (a linear solve that did not converge); nullopt when it can.
  /// The run ends such a frame as diverged.
  virtual std::optional<SolverNote> failure() const { return std::nullopt; }
  /// What a diverged run's reason adds for this backend (the setting that buys
  /// it stability or accuracy, with its value now); nullopt where the generic
  /// advice is the whole story.
  virtual std::optional<SolverNote> divergence_advice() const { return std::nullopt; }
  /// What the summary line adds about the solver ("1 Newton iteration, 84 CG
  /// iterations a substep at most"); empty for nothing.
  virtual std::string solver_summary() const { return {}; }
  /// Kinetic energy, J.
  double kinetic_energy() const;

  /// The force terms the backend applies as forces (the wind among them).
  virtual std::span<const std::unique_ptr<ForceTerm>> force_terms() const = 0;
  /// The wind's mean and the turbulence's drift (wind_field.hpp); nullopt
  /// without [wind]. Part of what a later frame depends on.
  std::optional<WindField::Drift> wind_drift() const;
  /// The wind takes `drift` from the next frame on (a new mean wind, or a
  /// saved one); false without [wind], or where the air cannot change (the
  /// vortex lattice's wake was shed in the old wind).
  virtual bool set_wind_drift(const WindField::Drift& drift);
};

/// The integrator of `scene.solver.backend` stepping `model` (the cloth of
/// any lattice: the hybrid's coarse one) under the rest of `scene`.
std::unique_ptr<ClothIntegrator> make_integrator(const Scene& scene,
                                                 std::shared_ptr<const ClothModel> model);
/// The same for the scene's fine lattice.
std::unique_ptr<ClothIntegrator> make_integrator(const Scene& scene);

/// The spring-damper backend behind the ClothIntegrator interface.
class SpringDamperIntegrator final : public ClothIntegrator {
 public:
  SpringDamperIntegrator(const Scene& scene, std::shared_ptr<const ClothModel> model)
      : solver_(scene, std::move(model)), state_(solver_.initial_state()) {}
  explicit SpringDamperIntegrator(const Scene& scene)
      : SpringDamperIntegrator(scene, std::make_shared<const ClothModel>(make_cloth_model(scene))) {
  }
  const ClothModel& model() const override { return solver_.model(); }
  const std::vector<std::string>& effects() const override { return solver_.effects(); }
  const ClothState& state() const override { return state_; }
  void set_state(const ClothState& state) override { state_ = state; }
  double stable_substep_s() const override { return solver_.stable_substep_s(); }
  int substeps_per_frame() const override { return solver_.substeps_per_frame(); }
  double substep_s() const override { return solver_.substep_s(); }
  void register_stages(StageTimes& times) override { solver_.register_stages(times); }
  void advance_frame(StageTimes* times) override { solver_.advance_frame(state_, times); }
  std::span<const std::unique_ptr<ForceTerm>> force_terms() const override {
    return solver_.terms();
  }
  bool set_wind_drift(const WindField::Drift& drift) override {
    return !solver_.has_vortex() && ClothIntegrator::set_wind_drift(drift);
  }

 private:
  SpringDamperSolver solver_;
  ClothState state_;
};

}  // namespace flagsim::physics
