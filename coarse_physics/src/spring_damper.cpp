#include "flagsim/coarse_physics/spring_damper.hpp"

#include <algorithm>
#include <cmath>

#include "flagsim/coarse_physics/force_terms.hpp"
#include "flagsim/core/stop_request.hpp"

namespace flagsim::physics {

SpringDamperSolver::SpringDamperSolver(const Scene& scene, std::shared_ptr<const ClothModel> model)
    : model_(std::move(model)),
      obstacles_(Obstacles::of(scene, model_->lattice)),
      initial_(physics::initial_state(scene, *model_)) {
  rest_m_ = model_->lattice.rest_positions();
  inverse_mass_.resize(model_->mass_kg.size());
  for (std::size_t i = 0; i < inverse_mass_.size(); ++i)
    inverse_mass_[i] = model_->pinned[i] ? 0.0 : 1.0 / model_->mass_kg[i];
  forces_n_.assign(model_->lattice.node_count(), Vec3::Zero());

  // The pipeline of force terms: only what the scene calls for is constructed.
  terms_ = make_force_terms(scene, *model_);
  effects_ = physics_effects(scene, *model_);

  if (scene.wind && scene.wind->model == AirModel::kVortex) {
    vortex_ = std::make_unique<VortexWake>(*model_, *scene.wind, scene.seed, inverse_mass_);
    effects_.insert(std::find(effects_.begin(), effects_.end(), "wind") + 1, "vortex");
  }

  frame_s_ = 1.0 / scene.fps;
  stable_substep_s_ = explicit_stability_limit(*model_, terms_);
  if (vortex_)
    stable_substep_s_ = std::min(stable_substep_s_, 1.0 / vortex_->velocity_rate_bound());
  substeps_per_frame_ =
      physics::substeps_per_frame(frame_s_, stable_substep_s_, scene.solver.substeps);

  // Held forces (held_forces.hpp). Not with obstacles: a projection changes
  // velocities within a substep, which a held force would not follow
  // (banner_ground crossed itself on 4 seeds of 6 with holds, 1 without); nor
  // with the vortex lattice, whose air inertia is solved with every substep's
  // forces.
  held_.emplace(terms_, scene.solver.wind_hold, substep_s(), substeps_per_frame_,
                !vortex_ && !obstacles_, model_->lattice.node_count());
}

void SpringDamperSolver::register_stages(StageTimes& times) {
  term_stage_ = register_term_stages(terms_, times);
  if (vortex_) vortex_stage_ = times.add("vortex");
  update_stage_ = times.add("integrate");
}

void SpringDamperSolver::advance_frame(ClothState& state, StageTimes* times) {
  if (vortex_) vortex_->begin_frame(state.time_s, state.x_m);
  held_->begin_frame();
  advance_substeps(terms_, state, substeps_per_frame_, substep_s(), [&](double dt) {
    step(state, dt, times);
    return true;
  });
}

void SpringDamperSolver::step(ClothState& state, double dt_s, StageTimes* times) {
  // The stages run back to back: one clock read between two.
  StageLaps laps(times);
  const auto stage_of = [&](std::size_t t) { return term_stage_.empty() ? -1 : term_stage_[t]; };
  held_->add(terms_, state.x_m, state.v_m_s, forces_n_,
             [&](std::size_t t, auto&& work) { laps.run(stage_of(t), work); });
  if (vortex_) {
    laps.run(vortex_stage_, [&] {
      vortex_->advance_to(state.time_s);
      vortex_->add_forces(state.time_s, state.x_m, state.v_m_s, forces_n_);
      // The accelerations f / m, then with the air's inertia (Woodbury).
      for (std::size_t i = 0; i < forces_n_.size(); ++i) forces_n_[i] *= inverse_mass_[i];
      vortex_->add_air_inertia(forces_n_);
      for (std::size_t i = 0; i < forces_n_.size(); ++i)
        if (!model_->pinned[i]) forces_n_[i] *= model_->mass_kg[i];
    });
  }
  auto update = [&] {
    const double next_time = state.time_s + dt_s;
    const Vec3 pin_offset = model_->pin_motion.offset_m(next_time);
    const Vec3 pin_velocity = model_->pin_motion.velocity_m_s(next_time);
    const double damping = model_->velocity_damping(dt_s);
    const std::size_t n = state.x_m.size();
    if (obstacles_ && obstacles_->self_contact())
      step_start_m_.assign(state.x_m.begin(), state.x_m.end());
    for (std::size_t i = 0; i < n; ++i) {
      if (model_->pinned[i]) {
        state.x_m[i] = rest_m_[i] + pin_offset;
        state.v_m_s[i] = pin_velocity;
      } else {
        state.v_m_s[i] = (state.v_m_s[i] + (dt_s * inverse_mass_[i]) * forces_n_[i]) * damping;
        state.x_m[i] += dt_s * state.v_m_s[i];
      }
    }
    for (std::size_t i = 0; i < driven_.size(); ++i) {
      const std::size_t node = driven_[i];
      const Vec3 before = state.x_m[node] - dt_s * state.v_m_s[node];
      state.x_m[node] = where_(i, next_time);
      state.v_m_s[node] = (state.x_m[node] - before) / dt_s;
    }
    if (obstacles_)
      obstacles_->project(next_time, state.x_m, state.v_m_s, model_->pinned, {}, step_start_m_);
    state.time_s = next_time;
  };
  laps.run(update_stage_, update);
}

void SpringDamperSolver::drive(std::vector<std::size_t> nodes, Driver where) {
  driven_ = std::move(nodes);
  where_ = std::move(where);
}

double SpringDamperSolver::kinetic_energy(const ClothState& state) const {
  return kinetic_energy_j(model_->mass_kg, state.v_m_s);
}

double SpringDamperSolver::potential_energy(const ClothState& state) const {
  double total = 0.0;
  for (const auto& term : terms_) total += term->energy(state.x_m);
  return total;
}

}  // namespace flagsim::physics
