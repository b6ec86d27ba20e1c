#pragma once
// XPBD with small steps on the spring-damper cloth (scene.mode = "xpbd" on the
// full lattice, solver.backend = "xpbd" for the hybrid's coarse nodes):
// Macklin, Mueller and Chentanez 2016, "XPBD: position-based simulation of
// compliant constrained dynamics", with the small steps of Macklin et al. 2019
// ("Small steps in physics simulation": many substeps, one iteration each).
//
// The cloth's elastic energies become compliant constraints, each with
// compliance alpha = 1/k (the same k as the spring-damper's):
//  - every link (stretch, shear): C = |x_b - x_a| - S, scalar;
//  - every bending triple: C = x_a - 2 x_b + x_c, a 3-vector (E = 1/2 k_b |C|^2,
//    bending_springs.hpp).
// One substep of h: the other forces (gravity, wind) and the damping move the
// velocities explicitly, v <- (v + h f / m) / (1 + c h); p = x + h v (pinned
// nodes where the pole is at t + h); the multipliers start at 0; then
// solver.iterations (default 1) Gauss-Seidel passes over the constraints,
// each
//   dlambda = (-C - alpha~ lambda) / (sum_i w_i |grad_i C|^2 + alpha~),
//   alpha~ = alpha / h^2,   p_i += w_i grad_i C dlambda,
// in colour groups whose constraints share no node (4 link families x 2,
// 2 bending directions x 3), so the order is fixed and each group could run in
// parallel; finally v = (p - x) / h, x = p.
//
// Substeps: the projection is unconditionally stable; what grows with h is
// the error of one pass (the cloth is softer than its k and the strain larger,
// by about alpha~'s share of the denominator). A Gauss-Seidel pass carries a
// correction about one link, so a load reaches the pole through L / dx links
// in as many passes, while the cloth's own stretch wave crosses a link in
// dx / c, c = sqrt(Y / rho_A) (316 m/s for the default fabric). A substep
// longer than `iterations` such crossings lets the load outrun the
// projection: the links stretch with the lattice (the default scene at 13
// substeps a frame reached 37% strain in frame 2 at 129 x 193). So the substep
// is at most iterations dx / c (xpbd_propagation_substep_s): 337 a frame at
// 33 x 49, 1350 at 129 x 193, where the p99 link strain measured 1% at 320 and
// 1280. solver.substeps is a floor. The explicit wind needs h * rate < 1 too
// (as in the spring-damper backend). A blow-up is caught by the run's
// divergence checks.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "flagsim/coarse_physics/cloth_integrator.hpp"
#include "flagsim/coarse_physics/force_term.hpp"
#include "flagsim/coarse_physics/obstacles.hpp"
#include "flagsim/coarse_physics/pin_motion.hpp"

namespace flagsim::physics {

/// The longest XPBD substep whose `iterations` passes keep up with the
/// cloth's stretch wave: iterations * dx / sqrt(Y / rho_A), dx the shorter
/// rest spacing, Y the stretch modulus, rho_A the areal density; s.
double xpbd_propagation_substep_s(const ClothModel& model, double stretch_modulus_n_m,
                                  double areal_density_kg_m2, int iterations);

class Xpbd final : public ClothIntegrator {
 public:
  /// A link constraint.
  struct Link {
    std::uint32_t a = 0, b = 0;
    double rest = 0.0, compliance = 0.0;  ///< S, m; 1/k, m/N
  };
  /// A bending constraint.
  struct Triple {
    std::uint32_t a = 0, b = 0, c = 0;
    double compliance = 0.0;  ///< 1/k_b, m/N
  };
  /// Steps `model` (the cloth, compiled once: sim::Model) under the rest of `scene`
  /// (its effects, pole, solver settings and start).
  Xpbd(const Scene& scene, std::shared_ptr<const ClothModel> model);
  /// The cloth of the scene's fine lattice (make_cloth_model(scene)).
  explicit Xpbd(const Scene& scene)
      : Xpbd(scene, std::make_shared<const ClothModel>(make_cloth_model(scene))) {}
  const ClothModel& model() const override { return *model_; }
  const std::vector<std::string>& effects() const override { return effects_; }
  const ClothState& state() const override { return state_; }
  void set_state(const ClothState& state) override { state_ = state; }
  std::span<const std::unique_ptr<ForceTerm>> force_terms() const override { return terms_; }
  /// The explicit terms' limit (the wind's), s; infinity if none bounds it.
  double stable_substep_s() const override { return stable_substep_s_; }
  int substeps_per_frame() const override { return substeps_; }
  double substep_s() const override { return frame_s_ / substeps_; }
  void register_stages(StageTimes& times) override;
  void advance_frame(StageTimes* times) override;
  std::string solver_summary() const override;
  std::optional<SolverNote> divergence_advice() const override;

  /// The constraints in colour groups, in the order they are projected.
  const std::vector<std::vector<Link>>& link_groups() const { return link_groups_; }
  const std::vector<std::vector<Triple>>& bending_groups() const { return bending_groups_; }

 private:
  void step(double dt_s, StageTimes* times);
  void project(double dt_s);
  /// One pass over the links of colour group `g` on the x, y, z arrays
  /// positions_ (they share no node, so kLanes of them are projected side by
  /// side with the same bits as one at a time); alpha = compliance * inverse_h2.
  void project_links(std::size_t g, double inverse_h2);

  std::shared_ptr<const ClothModel> model_;  ///< never null
  std::optional<Obstacles> obstacles_;       ///< [pole] radius, [ground]: projected after each step
  std::vector<Vec3> step_start_m_;           ///< [contact]: the positions a substep began from
  std::vector<Vec3> rest_m_;
  std::vector<double> inverse_mass_;               ///< [J*K] 0 on pinned nodes, 1/kg
  std::vector<std::unique_ptr<ForceTerm>> terms_;  ///< gravity, wind: explicit
  std::vector<std::string> effects_;
  ClothState state_;
  std::vector<std::vector<Link>> link_groups_;
  std::vector<std::vector<Triple>> bending_groups_;
  std::vector<std::vector<double>> link_lambda_;
  /// Per group, each link's S (m) and 1/k (m/N), in the group's order.
  std::vector<std::vector<double>> link_rest_, link_compliance_;
  /// The predicted positions as x, y, z arrays [J*K] while links are projected:
  /// a group's links are consecutive nodes of a lattice row (every second node
  /// for row links), so kLanes of them load and store side by side.
  std::vector<double> positions_[3];
  std::vector<std::vector<Vec3>> bending_lambda_;
  std::vector<Vec3> forces_, predicted_;
  int iterations_ = 1;
  int substeps_ = 1;
  double frame_s_ = 0.0;
  double stable_substep_s_ = 0.0;
  std::vector<int> term_stage_;
  int project_stage_ = -1, update_stage_ = -1;
};

}  // namespace flagsim::physics
