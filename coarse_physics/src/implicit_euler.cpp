#include "flagsim/coarse_physics/implicit_euler.hpp"

#include <fmt/format.h>

#include <Eigen/LU>
#include <cmath>

#include "flagsim/coarse_physics/cloth_state.hpp"
#include "flagsim/coarse_physics/force_terms.hpp"
#include "flagsim/core/stop_request.hpp"

namespace flagsim::physics {
namespace {

double dot(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double total = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) total += a[i].dot(b[i]);
  return total;
}

}  // namespace

ImplicitEuler::ImplicitEuler(const Scene& scene)
    : model_(make_cloth_model(scene)),
      pins_(scene.pole),
      rest_m_(model_.lattice.rest_positions()),
      terms_(make_force_terms(scene, model_, pins_)),
      effects_(physics_effects(scene, model_)),
      state_(initial_state(scene, model_)),
      newton_iterations_(scene.solver.iterations.value_or(1)),
      substeps_(scene.solver.substeps),
      frame_s_(1.0 / scene.fps),
      explicit_limit_s_(explicit_stability_limit(model_, terms_)) {
  const std::size_t n = model_.lattice.node_count();
  for (auto* v : {&x0_, &v0_, &forces_, &residual_, &delta_, &r_, &z_, &p_, &ap_, &scratch_})
    v->assign(n, Vec3::Zero());
  block_inverse_.assign(n, Mat3::Zero());
  stiffness_diagonal_.assign(n, Mat3::Zero());
  damping_diagonal_.assign(n, Mat3::Zero());
}

void ImplicitEuler::register_stages(StageTimes& times) {
  term_stage_.clear();
  for (const auto& term : terms_) term_stage_.push_back(times.add(std::string(term->name())));
  matrix_stage_ = times.add("newton_matrix");
  solve_stage_ = times.add("linear_solve");
}

void ImplicitEuler::advance_frame(StageTimes* times) {
  cg_max_ = cg_total_ = 0;
  if (failure_) return;
  advance_substeps(terms_, state_, substeps_, substep_s(), [&](double dt) {
    step(dt, times);
    return !failure_;
  });
}

void ImplicitEuler::apply(double dt_s, const std::vector<Vec3>& dv, std::vector<Vec3>& out) {
  const double mass_scale = 1.0 + model_.damping_per_s * dt_s;
  const std::size_t n = dv.size();
  for (std::size_t i = 0; i < n; ++i) out[i] = (mass_scale * model_.mass_kg[i]) * dv[i];
  // h C dv + h^2 K dv, accumulated as h (C dv + h K dv).
  std::vector<Vec3>& scratch = scratch_;
  std::fill(scratch.begin(), scratch.end(), Vec3::Zero());
  for (const auto& term : terms_) term->add_stiffness_product(dv, scratch);
  for (std::size_t i = 0; i < n; ++i) scratch[i] *= dt_s;
  for (const auto& term : terms_) term->add_damping_product(dv, scratch);
  for (std::size_t i = 0; i < n; ++i)
    out[i] = model_.pinned[i] ? Vec3::Zero() : Vec3(out[i] + dt_s * scratch[i]);
}

bool ImplicitEuler::solve(double dt_s, const std::vector<Vec3>& rhs, std::vector<Vec3>& dv) {
  const std::size_t n = rhs.size();
  std::fill(dv.begin(), dv.end(), Vec3::Zero());
  const double rhs_norm = std::sqrt(dot(rhs, rhs));
  if (rhs_norm == 0.0) return true;
  r_ = rhs;
  std::vector<Vec3>& z = z_;
  for (std::size_t i = 0; i < n; ++i) z[i] = block_inverse_[i] * r_[i];
  p_ = z;
  double rz = dot(r_, z);
  double relative = 1.0;
  int iteration = 0;
  bool converged = false;
  while (iteration < kMaxCgIterations) {
    ++iteration;
    apply(dt_s, p_, ap_);
    const double curvature = dot(p_, ap_);
    if (!(curvature > 0.0)) break;  // not positive definite (a NaN state): fail
    const double alpha = rz / curvature;
    for (std::size_t i = 0; i < n; ++i) {
      dv[i] += alpha * p_[i];
      r_[i] -= alpha * ap_[i];
    }
    relative = std::sqrt(dot(r_, r_)) / rhs_norm;
    if (relative <= kCgTolerance) {
      converged = true;
      break;
    }
    for (std::size_t i = 0; i < n; ++i) z[i] = block_inverse_[i] * r_[i];
    const double rz_next = dot(r_, z);
    const double beta = rz_next / rz;
    rz = rz_next;
    for (std::size_t i = 0; i < n; ++i) p_[i] = z[i] + beta * p_[i];
  }
  cg_max_ = std::max(cg_max_, iteration);
  cg_total_ += iteration;
  if (!converged)
    failure_ = fmt::format(
        "implicit Euler: the linear solve did not converge at t = {:.4g} s (relative residual "
        "{:.2g} after {} conjugate-gradient iterations, tolerance {:.0e}): raise solver.substeps "
        "(now {}) for shorter steps, which it solves in fewer iterations",
        state_.time_s, relative, iteration, kCgTolerance, substeps_);
  return converged;
}

void ImplicitEuler::step(double dt_s, StageTimes* times) {
  const double h = dt_s;
  const double next_time = state_.time_s + h;
  const Vec3 pin_offset = pins_.offset_m(next_time);
  const std::size_t n = state_.x_m.size();
  const double mass_scale = 1.0 + model_.damping_per_s * h;
  x0_ = state_.x_m;
  v0_ = state_.v_m_s;
  std::vector<Vec3>& v = state_.v_m_s;
  for (std::size_t i = 0; i < n; ++i)
    if (model_.pinned[i]) v[i] = (rest_m_[i] + pin_offset - x0_[i]) / h;
  for (int iteration = 0; iteration < newton_iterations_; ++iteration) {
    // The point the forces are linearized at: the start x0 in the first
    // iteration (Baraff and Witkin's step: x0 + h v0 can be far from any
    // state of the cloth, and one linearization there overshoots), then the
    // current iterate x0 + h v (Newton's method).
    if (iteration > 0)
      for (std::size_t i = 0; i < n; ++i) state_.x_m[i] = x0_[i] + h * v[i];
    std::fill(forces_.begin(), forces_.end(), Vec3::Zero());
    for (std::size_t t = 0; t < terms_.size(); ++t) {
      const int stage = term_stage_.empty() ? -1 : term_stage_[t];
      run_timed(times, stage, [&] { terms_[t]->add_forces(state_.x_m, v, forces_); });
    }
    run_timed(times, matrix_stage_, [&] {
      for (const auto& term : terms_) term->linearize(state_.x_m, v, Definiteness::kProjected);
      // r = h (f - K (x0 + h v - x_lin)) - M ((1 + c h) v - v0); the K part only
      // in the first iteration, where x_lin = x0.
      std::fill(scratch_.begin(), scratch_.end(), Vec3::Zero());
      if (iteration == 0) {
        for (std::size_t i = 0; i < n; ++i) ap_[i] = h * v[i];
        for (const auto& term : terms_) term->add_stiffness_product(ap_, scratch_);
      }
      for (std::size_t i = 0; i < n; ++i)
        residual_[i] = model_.pinned[i] ? Vec3::Zero()
                                        : Vec3(h * (forces_[i] - scratch_[i]) -
                                               model_.mass_kg[i] * (mass_scale * v[i] - v0_[i]));
      std::fill(stiffness_diagonal_.begin(), stiffness_diagonal_.end(), Mat3::Zero());
      std::fill(damping_diagonal_.begin(), damping_diagonal_.end(), Mat3::Zero());
      for (const auto& term : terms_) {
        term->add_stiffness_diagonal(stiffness_diagonal_);
        term->add_damping_diagonal(damping_diagonal_);
      }
      for (std::size_t i = 0; i < n; ++i) {
        const Mat3 block = mass_scale * model_.mass_kg[i] * Mat3::Identity() +
                           h * damping_diagonal_[i] + h * h * stiffness_diagonal_[i];
        block_inverse_[i] = model_.pinned[i] ? Mat3::Zero() : Mat3(block.inverse());
      }
    });
    bool converged = true;
    run_timed(times, solve_stage_, [&] { converged = solve(h, residual_, delta_); });
    if (!converged) break;
    for (std::size_t i = 0; i < n; ++i) v[i] += delta_[i];
  }
  const Vec3 pin_velocity = pins_.velocity_m_s(next_time);
  for (std::size_t i = 0; i < n; ++i) {
    if (model_.pinned[i]) {
      state_.x_m[i] = rest_m_[i] + pin_offset;
      v[i] = pin_velocity;
    } else {
      state_.x_m[i] = x0_[i] + h * v[i];
    }
  }
  state_.time_s = next_time;
}

std::string ImplicitEuler::divergence_advice() const {
  return fmt::format(
      "implicit Euler linearizes each step once per Newton iteration: raise solver.substeps "
      "(now {}) or solver.iterations (now {})",
      substeps_, newton_iterations_);
}

std::string ImplicitEuler::solver_summary() const {
  return fmt::format("{} Newton iteration{} a step, CG {} iterations at most in the last frame",
                     newton_iterations_, newton_iterations_ == 1 ? "" : "s", cg_max_);
}

}  // namespace flagsim::physics
