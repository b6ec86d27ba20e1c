#pragma once
// The Bullet soft-body backend (solver.backend = "bullet", and mode "bullet" on
// the full lattice), built to mean the same cloth as the spring-damper one.
//
// Bullet (3.24, double precision build) solves links as position constraints:
// each of solver.iterations passes moves a link's two nodes by the fraction
// kLST of its length error, split by inverse mass. A spring of k N/m between
// nodes of inverse masses w_a, w_b closes, over one substep dt, the fraction
//   f = k dt^2 (w_a + w_b)
// of its error (symplectic Euler). Each link gets kLST = f / n for n passes:
// in a cloth at rest under a load the error hardly changes between passes, so
// the n passes close n * kLST = f of it, and the statics are the spring's.
// (1 - (1 - f)^(1/n), right for a lone link's free decay, made a hanging cloth
// 7% stiffer than the spring-damper one.) f = 1 is the stiffest link Bullet
// can represent at that substep; the substep is kStabilitySafety of the substep where the
// stiffest link has f = 1 (so f <= 0.25), and no more than the explicit terms
// (bending, wind) allow, as in the spring-damper backend.
//
// Bullet's traps, each handled here:
//  - generateBendingConstraints allocates memory quadratic in the node count;
//    bending is our own BendingSprings force instead (a link two nodes apart
//    resists bending only to second order, so it could not mean the scene's D).
//  - masses are given with the nodes, pinned nodes with mass 0 (setMass or
//    setTotalMass after pinning would unpin them).
//  - the first step recomputes rest lengths from the current positions: the
//    body is built at rest, its constants are computed there once, and only
//    then are the nodes moved to the perturbed start; nothing resets them later.
//  - Bullet's own aerodynamic models are off (kDG = kLF = 0): the wind must act
//    the same in both backends, so it is our per-triangle AeroForce, added with
//    bending in a pre-tick callback.
//  - one fixed substep per stepSimulation call (maxSubSteps = 0).
//  - gravity for soft bodies is the world info's m_gravity.
// Velocity damping c: Bullet sets v = (x - x_old) / dt * (1 - kDP); kDP =
// 1 - 1 / (1 + c dt) matches the spring-damper's implicit damping.
#include <memory>
#include <string>
#include <vector>

#include "flagsim/coarse_physics/cloth_integrator.hpp"
#include "flagsim/coarse_physics/obstacles.hpp"

namespace flagsim::physics {

/// The Bullet library this program runs with ("3.24"), for --version.
std::string bullet_version();

/// kLST of a link that must close the fraction `fraction` of its error per
/// substep in `iterations` passes: f / n, at most 1.
double bullet_link_stiffness(double fraction, int iterations);

class BulletCloth final : public ClothIntegrator {
 public:
  /// Steps `model` (the cloth, compiled once: sim::Model) under the rest of `scene`
  /// (its effects, pole, solver settings and start).
  BulletCloth(const Scene& scene, std::shared_ptr<const ClothModel> model);
  /// The cloth of the scene's fine lattice (make_cloth_model(scene)).
  explicit BulletCloth(const Scene& scene)
      : BulletCloth(scene, std::make_shared<const ClothModel>(make_cloth_model(scene))) {}
  ~BulletCloth() override;
  BulletCloth(const BulletCloth&) = delete;
  BulletCloth& operator=(const BulletCloth&) = delete;

  const ClothModel& model() const override { return *model_; }
  const std::vector<std::string>& effects() const override { return effects_; }
  const ClothState& state() const override { return state_; }
  /// Bullet's nodes are put where `state` says (positions, the previous
  /// positions and velocities), and its clock to the state's time.
  void set_state(const ClothState& state) override;
  double stable_substep_s() const override { return stable_substep_s_; }
  int substeps_per_frame() const override { return substeps_per_frame_; }
  double substep_s() const override { return frame_s_ / substeps_per_frame_; }
  void register_stages(StageTimes& times) override;
  void advance_frame(StageTimes* times) override;
  std::span<const std::unique_ptr<ForceTerm>> force_terms() const override { return terms_; }

  /// Called by Bullet before each substep: pins and our force terms.
  void before_substep(double dt_s);

 private:
  struct World;  // Bullet's objects, kept out of this header
  void read_back();
  /// [pole] radius, [ground]: Bullet's nodes out of the solids after a substep.
  void project_contacts(double time_s);
  std::vector<Vec3> contact_x_, contact_v_;  ///< scratch of project_contacts
  std::vector<Vec3> contact_start_;          ///< [contact]: the substep's start (Bullet's m_q)

  std::shared_ptr<const ClothModel> model_;  ///< never null
  std::optional<Obstacles> obstacles_;       ///< [pole] radius, [ground]: projected after each step
  std::vector<Vec3> rest_m_;
  std::vector<std::unique_ptr<ForceTerm>> terms_;  // bending, wind: what Bullet does not model
  std::vector<std::string> effects_;
  ClothState state_;
  std::vector<Vec3> forces_n_;
  std::unique_ptr<World> world_;
  std::vector<int> term_stage_;
  int step_stage_ = -1;
  StageTimes* times_ = nullptr;
  double frame_s_ = 0.0;
  double stable_substep_s_ = 0.0;
  int substeps_per_frame_ = 1;
};

}  // namespace flagsim::physics
