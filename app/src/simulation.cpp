#include "simulation.hpp"

#include <fmt/format.h>

#include "flagsim/coarse_physics/cloth_model.hpp"
#include "flagsim/coarse_physics/initial_shape.hpp"
#include "flagsim/coarse_physics/spring_damper.hpp"
#include "flagsim/infill/infill_solver.hpp"
#include "flagsim/infill/keyframes.hpp"

namespace flagsim::app {
namespace {

// mode "mass-spring": the spring-damper integrator on the full lattice.
class MassSpringSimulation final : public Simulation {
 public:
  explicit MassSpringSimulation(const Scene& scene)
      : solver_(scene), state_(solver_.initial_state(scene.seed)) {}
  const Lattice& lattice() const override { return solver_.model().lattice; }
  std::vector<std::string> effects() const override { return solver_.effects(); }
  std::vector<std::pair<std::string, double>> numbers() const override {
    return {{"substep_seconds", solver_.substep_s()},
            {"substeps_per_frame", double(solver_.substeps_per_frame())},
            {"stable_substep_seconds", solver_.stable_substep_s()}};
  }
  void register_stages(StageTimes& times) override { solver_.register_stages(times); }
  void advance_frame(StageTimes* times) override { solver_.advance_frame(state_, times); }
  std::span<const Vec3> positions() const override { return state_.x_m; }
  std::span<const Vec3> velocities() const override { return state_.v_m_s; }
  double kinetic_energy_j() const override { return solver_.kinetic_energy(state_); }
  std::string stepping_summary() const override {
    return fmt::format("{} substeps/frame of {:.3g} s", solver_.substeps_per_frame(),
                       solver_.substep_s());
  }

 private:
  physics::SpringDamperSolver solver_;
  physics::ClothState state_;
};

// Step 3.5's constants from [wrinkles], or nullopt when the scene has none.
std::optional<infill::WrinkleParams> wrinkle_params(const Scene& scene) {
  if (!scene.wrinkles) return std::nullopt;
  const Wrinkles& w = *scene.wrinkles;
  infill::WrinkleParams params;
  params.k_r4 = infill::bending_constant_k_r4(w.fiber_modulus_pa, w.fiber_radius_m);
  params.k_prime = w.k_prime.value_or(params.k_prime);
  params.tolerance = w.tolerance.value_or(params.tolerance);
  return params;
}

// mode "infill": no physics; the corners follow the keyframes and the whole
// lattice comes from the paper's infill (Figs. 9-10). Velocities are the
// frame-to-frame differences, for the divergence checks and kinetic energy.
class InfillSimulation final : public Simulation {
 public:
  explicit InfillSimulation(const Scene& scene)
      : scene_(scene),
        lattice_(scene.fine_lattice()),
        solver_(lattice_, infill::CellGrid::of(lattice_, 2, 2),
                scene.infill ? scene.infill->relax_iterations : kDefaultRelaxSweeps,
                wrinkle_params(scene), scene.wrinkles ? scene.wrinkles->rounds.value_or(2) : 0),
        mass_kg_(physics::make_cloth_model(scene).mass_kg) {
    positions_ = lattice_.rest_positions();
    if (scene.flag.initial_perturbation_m > 0.0) {
      const auto z =
          physics::smooth_perturbation(lattice_, scene.seed, scene.flag.initial_perturbation_m);
      for (std::size_t i = 0; i < z.size(); ++i) positions_[i].z() += z[i];
    }
    velocities_.assign(positions_.size(), Vec3::Zero());
    previous_ = positions_;
    fill(0.0, nullptr);  // frame 0: the corners of the first keyframe
    std::fill(velocities_.begin(), velocities_.end(), Vec3::Zero());
  }
  const Lattice& lattice() const override { return lattice_; }
  std::vector<std::string> effects() const override {
    if (scene_.wrinkles) return {"keyframes", "infill", "wrinkles"};
    return {"keyframes", "infill"};
  }
  std::vector<std::pair<std::string, double>> numbers() const override { return {}; }
  void register_stages(StageTimes& times) override { solver_.register_stages(times); }
  void advance_frame(StageTimes* times) override {
    ++frame_;
    fill(frame_ / scene_.fps, times);
  }
  std::span<const Vec3> positions() const override { return positions_; }
  std::span<const Vec3> velocities() const override { return velocities_; }
  double kinetic_energy_j() const override {
    double total = 0.0;
    for (std::size_t i = 0; i < velocities_.size(); ++i)
      total += 0.5 * mass_kg_[i] * velocities_[i].squaredNorm();
    return total;
  }
  std::string stepping_summary() const override {
    return fmt::format("{} relaxation sweeps in the last frame", solver_.last_relax_sweeps());
  }

 private:
  // One cell spans the whole flag, so 3.4 needs many passes; it stops early
  // once converged (twisted.toml at 33 x 49: 0.78% max strain with 1000, 1.7% with 200).
  static constexpr int kDefaultRelaxSweeps = 1000;

  void fill(double time_s, StageTimes* times) {
    const auto corners = infill::corners_at(scene_.keyframes, time_s);
    std::copy(positions_.begin(), positions_.end(), previous_.begin());
    solver_.fill(corners, positions_, times);
    for (std::size_t i = 0; i < positions_.size(); ++i)
      velocities_[i] = (positions_[i] - previous_[i]) * scene_.fps;
  }

  const Scene& scene_;
  Lattice lattice_;
  infill::InfillSolver solver_;
  std::vector<double> mass_kg_;
  std::vector<Vec3> positions_, previous_, velocities_;
  int frame_ = 0;
};

}  // namespace

std::unique_ptr<Simulation> make_simulation(const Scene& scene) {
  if (scene.mode == Mode::kInfill) return std::make_unique<InfillSimulation>(scene);
  return std::make_unique<MassSpringSimulation>(scene);
}

}  // namespace flagsim::app
