#pragma once
// Backward Euler on the spring-damper cloth (scene.mode = "implicit" on the
// full lattice, solver.backend = "implicit" for the hybrid's coarse nodes):
// Baraff and Witkin 1998, "Large steps in cloth simulation".
//
// One substep of h seconds finds the velocities v1 with
//   M (v1 - v0) = h f(x0 + h v1, v1) - c h M v1,     x1 = x0 + h v1,
// (c = flag.damping, the same mass-proportional damping the explicit
// integrator applies implicitly) by Newton's method from v1 = v0: each of
// solver.iterations (default 1) iterations solves
//   A dv = r,  A = (1 + c h) M + h C + h^2 K,  r = h f(x0 + h v1, v1) - M ((1 + c h) v1 - v0)
// with K = -df/dx (stretch and bending Hessians) and C = -df/dv (the wind's
// velocity derivative), both in their positive semidefinite projection
// (Definiteness::kProjected), so A is symmetric positive definite. One
// iteration is Baraff and Witkin's linearised step. The solve is a conjugate
// gradient with a 3x3 block-Jacobi preconditioner, matrix-free (each term
// gives A's products and diagonal blocks), with the pinned nodes filtered out
// (their rows and columns removed: their v1 puts them where the pole is at
// t + h). It stops when |r - A dv| <= kCgTolerance |r|.
//
// solver.linear = "cholesky" solves the same system directly instead: A is
// assembled by probing its products (every node couples only with nodes at
// most 2 rows and 2 columns away, so 25 node colours x 3 components = 75
// products give every entry), its pattern analysed once (AMD ordering) and
// factorised by Eigen's SimplicialLDLT in every Newton iteration.
//
// Stability: unconditional for the linear part (a stiffer cloth or a longer
// step only damps more); solver.substeps sets the steps per frame (default 1:
// one step per output frame). Two things a long step gets wrong are not
// linear: one Newton iteration moves a fast-turning link along its tangent
// (lengthening it by about L theta^2 / 2 for a turn of theta), and the wind's
// change with the cloth's orientation is explicit (only its velocity
// derivative is in A; Newton iterations on the wind oscillate instead of
// converging). Measured on the default flag at one step a frame, single links
// of the free bottom edge jump by 7-30% of strain in one step. So every step
// is checked, as Baraff and Witkin check theirs: a step that changes any row
// or column link's strain by more than solver.max_step_strain_change (default
// 5%) is undone and taken again as two steps of half the length, down to
// 1 / 2^kMaxHalvings of the step solver.substeps sets; a shortest step is
// accepted whatever it does (the run's strain limit still applies). What a
// long step costs is accuracy (numerical damping of the flapping grows with h)
// and CG iterations, which grow with h^2 k / m (the system's condition
// number): a step whose CG does not reach its tolerance in kMaxCgIterations is
// undone and halved the same way; only a shortest step's failure ends the run
// as diverged, with what to change.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "flagsim/coarse_physics/cloth_integrator.hpp"
#include "flagsim/coarse_physics/force_term.hpp"
#include "flagsim/coarse_physics/obstacles.hpp"
#include "flagsim/coarse_physics/pin_motion.hpp"

namespace flagsim::physics {

/// Relative residual at which the conjugate gradient stops.
inline constexpr double kCgTolerance = 1e-4;
/// Iterations after which a solve that has not reached kCgTolerance fails.
inline constexpr int kMaxCgIterations = 4000;
/// Halvings of a step at most: no step is shorter than 1/32 of solver.substeps'.
inline constexpr int kMaxHalvings = 5;

class ImplicitEuler final : public ClothIntegrator {
 public:
  /// Steps `model` (the cloth, compiled once: sim::Model) under the rest of `scene`
  /// (its effects, pole, solver settings and start).
  ImplicitEuler(const Scene& scene, std::shared_ptr<const ClothModel> model);
  /// The cloth of the scene's fine lattice (make_cloth_model(scene)).
  explicit ImplicitEuler(const Scene& scene)
      : ImplicitEuler(scene, std::make_shared<const ClothModel>(make_cloth_model(scene))) {}
  ~ImplicitEuler() override;
  const ClothModel& model() const override { return *model_; }
  const std::vector<std::string>& effects() const override { return effects_; }
  const ClothState& state() const override { return state_; }
  void set_state(const ClothState& state) override { state_ = state; }
  std::span<const std::unique_ptr<ForceTerm>> force_terms() const override { return terms_; }
  /// The explicit integrator's limit for the same cloth, s (for comparison:
  /// this stepper does not need it).
  double stable_substep_s() const override { return explicit_limit_s_; }
  int substeps_per_frame() const override { return substeps_; }
  double substep_s() const override { return frame_s_ / substeps_; }
  void register_stages(StageTimes& times) override;
  void advance_frame(StageTimes* times) override;
  std::optional<SolverNote> failure() const override { return failure_; }
  std::string solver_summary() const override;
  std::optional<SolverNote> divergence_advice() const override;

  /// CG iterations of the last frame: the most of any one solve, and in all.
  int cg_iterations_max() const { return cg_max_; }
  int cg_iterations_total() const { return cg_total_; }
  /// Steps taken, and steps undone for changing a strain by more than
  /// solver.max_step_strain_change (each taken again as two halves), since
  /// the start of the run.
  long steps_taken() const { return steps_taken_; }
  long steps_undone() const { return steps_undone_; }

 private:
  /// One step of dt_s, undone and taken as two halves while it changes a
  /// strain by more than max_step_strain_change_ (`halvings` so far).
  void advance(double dt_s, int halvings, StageTimes* times);
  void step(double dt_s, StageTimes* times);
  /// The largest change of any row or column link's strain from x0_ to the state.
  double largest_strain_change() const;
  /// out = A dv on the free nodes (0 on the pinned ones).
  void apply(double dt_s, const std::vector<Vec3>& dv, std::vector<Vec3>& out);
  /// dv with A dv = rhs by preconditioned CG; false if it did not converge.
  bool solve(double dt_s, const std::vector<Vec3>& rhs, std::vector<Vec3>& dv);
  /// The same by sparse Cholesky (LDL^T) of A assembled by probing; false if
  /// the factorisation failed.
  bool solve_direct(double dt_s, const std::vector<Vec3>& rhs, std::vector<Vec3>& dv);
  /// A's entries into the direct solver's matrix (pattern and ordering the first time).
  void assemble(double dt_s);

  std::shared_ptr<const ClothModel> model_;  ///< never null
  std::optional<Obstacles> obstacles_;       ///< [pole] radius, [ground]: projected after each step
  std::vector<Vec3> rest_m_;
  std::vector<std::unique_ptr<ForceTerm>> terms_;
  std::vector<std::string> effects_;
  ClothState state_;
  int newton_iterations_ = 1;
  double max_step_strain_change_ = 0.0;
  int substeps_ = 1;
  double frame_s_ = 0.0;
  double explicit_limit_s_ = 0.0;
  // Work arrays [J*K], kept between steps; x0_ and v0_ hold the state a step
  // started from (an undone step goes back to it).
  std::vector<Vec3> x0_, v0_, forces_, residual_, delta_, r_, z_, p_, ap_, scratch_;
  std::vector<Mat3> block_inverse_;  ///< inverse diagonal blocks of A
  std::vector<Mat3> stiffness_diagonal_, damping_diagonal_;
  std::vector<int> term_stage_;
  int matrix_stage_ = -1, solve_stage_ = -1;
  int cg_max_ = 0, cg_total_ = 0;
  long steps_taken_ = 0, steps_undone_ = 0;
  std::optional<SolverNote> failure_;
  bool direct_ = false;  ///< solver.linear = "cholesky"
  struct Direct;         ///< the assembled matrix and its factorisation
  std::unique_ptr<Direct> direct_state_;
};

}  // namespace flagsim::physics
