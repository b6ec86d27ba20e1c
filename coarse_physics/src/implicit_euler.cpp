#include "flagsim/coarse_physics/implicit_euler.hpp"

#include <fmt/format.h>

#include <Eigen/LU>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
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

struct ImplicitEuler::Direct {
  Eigen::SparseMatrix<double> matrix;  ///< [3N x 3N], pinned nodes' rows and columns identity
  std::vector<int> slot;               ///< value index of each probed entry, in probing order
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt;
  Eigen::VectorXd rhs, solution;
  bool analysed = false;
};

ImplicitEuler::~ImplicitEuler() = default;

ImplicitEuler::ImplicitEuler(const Scene& scene, std::shared_ptr<const ClothModel> model)
    : model_(std::move(model)),
      obstacles_(Obstacles::of(scene, model_->lattice)),
      rest_m_(model_->lattice.rest_positions()),
      terms_(make_force_terms(scene, *model_)),
      effects_(physics_effects(scene, *model_)),
      state_(initial_state(scene, *model_)),
      newton_iterations_(scene.solver.iterations.value_or(1)),
      max_step_strain_change_(scene.solver.max_step_strain_change),
      substeps_(scene.solver.substeps),
      frame_s_(1.0 / scene.fps),
      explicit_limit_s_(explicit_stability_limit(*model_, terms_)) {
  const std::size_t n = model_->lattice.node_count();
  for (auto* v : {&x0_, &v0_, &forces_, &residual_, &delta_, &r_, &z_, &p_, &ap_, &scratch_})
    v->assign(n, Vec3::Zero());
  block_inverse_.assign(n, Mat3::Zero());
  direct_ = scene.solver.linear == LinearSolver::kCholesky;
  if (direct_) direct_state_ = std::make_unique<Direct>();
  stiffness_diagonal_.assign(n, Mat3::Zero());
  damping_diagonal_.assign(n, Mat3::Zero());
}

void ImplicitEuler::register_stages(StageTimes& times) {
  term_stage_ = register_term_stages(terms_, times);
  matrix_stage_ = times.add("newton_matrix");
  solve_stage_ = times.add("linear_solve");
}

void ImplicitEuler::advance_frame(StageTimes* times) {
  cg_max_ = cg_total_ = 0;
  if (failure_) return;
  advance_substeps(terms_, state_, substeps_, substep_s(), [&](double dt) {
    advance(dt, 0, times);
    return !failure_;
  });
}

void ImplicitEuler::advance(double dt_s, int halvings, StageTimes* times) {
  ++steps_taken_;
  if (halvings == kMaxHalvings) {
    step(dt_s, times);
    return;
  }
  const double start_s = state_.time_s;
  step(dt_s, times);
  // A solve that did not converge is retried too: shorter steps solve in
  // fewer iterations. Only the shortest step's failure ends the run.
  if (!failure_ && largest_strain_change() <= max_step_strain_change_) return;
  ++steps_undone_;
  failure_.reset();
  // Undone: step() kept the state it started from in x0_ and v0_.
  state_.x_m = x0_;
  state_.v_m_s = v0_;
  state_.time_s = start_s;
  advance(0.5 * dt_s, halvings + 1, times);
  if (!failure_) advance(0.5 * dt_s, halvings + 1, times);
}

double ImplicitEuler::largest_strain_change() const {
  // The row and column links: the strain the run reports (/stats/max_strain).
  double largest = 0.0;
  for (const LinkFamily& family : {model_->links[0], model_->links[1]}) {
    const double inverse_rest = 1.0 / family.rest_length_m;
    for_each_link(*model_, family, [&](std::size_t a, std::size_t b, double, double) {
      const double before = (x0_[b] - x0_[a]).norm();
      const double after = (state_.x_m[b] - state_.x_m[a]).norm();
      largest = std::max(largest, std::abs(after - before) * inverse_rest);
    });
  }
  return largest;
}

void ImplicitEuler::apply(double dt_s, const std::vector<Vec3>& dv, std::vector<Vec3>& out) {
  const double mass_scale = model_->damping_mass_scale(dt_s);
  const std::size_t n = dv.size();
  for (std::size_t i = 0; i < n; ++i) out[i] = (mass_scale * model_->mass_kg[i]) * dv[i];
  // h C dv + h^2 K dv, accumulated as h (C dv + h K dv).
  std::vector<Vec3>& scratch = scratch_;
  std::fill(scratch.begin(), scratch.end(), Vec3::Zero());
  for (const auto& term : terms_) term->add_stiffness_product(dv, scratch);
  for (std::size_t i = 0; i < n; ++i) scratch[i] *= dt_s;
  for (const auto& term : terms_) term->add_damping_product(dv, scratch);
  for (std::size_t i = 0; i < n; ++i)
    out[i] = model_->pinned[i] ? Vec3::Zero() : Vec3(out[i] + dt_s * scratch[i]);
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
    failure_ = SolverNote{.kind = SolverNote::Kind::kCgNotConverged,
                          .substeps = substeps_,
                          .iterations = newton_iterations_,
                          .cg_iterations = iteration,
                          .time_s = state_.time_s,
                          .step_s = dt_s,
                          .residual = relative,
                          .tolerance = kCgTolerance};
  return converged;
}

void ImplicitEuler::assemble(double dt_s) {
  // Probing: with unit vectors on every node of one colour (j mod 5, k mod 5)
  // and one component, A e holds, in the rows of each node r, the column of
  // the one node of that colour within 2 rows and 2 columns of r: the reach of
  // every term (bending triples span 2 links, links and triangles 1).
  Direct& d = *direct_state_;
  const Lattice& lattice = model_->lattice;
  const int rows = lattice.rows, cols = lattice.cols;
  const std::size_t n = lattice.node_count();
  std::vector<Eigen::Triplet<double>> triplets;
  std::size_t entry = 0;
  if (d.analysed) d.matrix.coeffs().setZero();
  for (int cj = 0; cj < 5; ++cj) {
    for (int ck = 0; ck < 5; ++ck) {
      for (int c = 0; c < 3; ++c) {
        std::fill(p_.begin(), p_.end(), Vec3::Zero());
        for (int j = cj; j < rows; j += 5)
          for (int k = ck; k < cols; k += 5)
            if (!model_->pinned[lattice.index(j, k)]) p_[lattice.index(j, k)][c] = 1.0;
        apply(dt_s, p_, ap_);
        for (int jr = 0; jr < rows; ++jr) {
          const int j = jr - ((jr - cj) % 5 + 5) % 5 + (((jr - cj) % 5 + 5) % 5 > 2 ? 5 : 0);
          if (j < 0 || j >= rows) continue;
          for (int kr = 0; kr < cols; ++kr) {
            const int k = kr - ((kr - ck) % 5 + 5) % 5 + (((kr - ck) % 5 + 5) % 5 > 2 ? 5 : 0);
            if (k < 0 || k >= cols) continue;
            const std::size_t row = lattice.index(jr, kr), col = lattice.index(j, k);
            if (model_->pinned[row] || model_->pinned[col]) continue;
            for (int r = 0; r < 3; ++r) {
              const int at_row = int(3 * row) + r, at_col = int(3 * col) + c;
              if (at_row < at_col) continue;  // the lower triangle: LDL^T reads only it
              if (!d.analysed)
                triplets.emplace_back(at_row, at_col, ap_[row][r]);
              else
                d.matrix.valuePtr()[d.slot[entry]] = ap_[row][r];
              ++entry;
            }
          }
        }
      }
    }
  }
  if (!d.analysed) {
    for (std::size_t i = 0; i < n; ++i)
      if (model_->pinned[i])
        for (int r = 0; r < 3; ++r) triplets.emplace_back(int(3 * i) + r, int(3 * i) + r, 1.0);
    d.matrix.resize(int(3 * n), int(3 * n));
    d.matrix.setFromTriplets(triplets.begin(), triplets.end());
    d.matrix.makeCompressed();
    // Where each probed entry landed, to fill values in place from now on.
    d.slot.resize(entry);
    std::size_t e = 0;
    for (const auto& t : triplets) {
      if (e == entry) break;
      d.slot[e++] = int(&d.matrix.coeffRef(t.row(), t.col()) - d.matrix.valuePtr());
    }
    d.ldlt.analyzePattern(d.matrix);
    d.analysed = true;
    d.rhs.resize(int(3 * n));
  } else {
    for (std::size_t i = 0; i < n; ++i)
      if (model_->pinned[i])
        for (int r = 0; r < 3; ++r) d.matrix.coeffRef(int(3 * i) + r, int(3 * i) + r) = 1.0;
  }
}

bool ImplicitEuler::solve_direct(double dt_s, const std::vector<Vec3>& rhs, std::vector<Vec3>& dv) {
  Direct& d = *direct_state_;
  assemble(dt_s);
  d.ldlt.factorize(d.matrix);
  if (d.ldlt.info() != Eigen::Success) {
    failure_ = SolverNote{.kind = SolverNote::Kind::kCholeskyFailed,
                          .substeps = substeps_,
                          .iterations = newton_iterations_,
                          .time_s = state_.time_s,
                          .step_s = dt_s};
    return false;
  }
  for (std::size_t i = 0; i < rhs.size(); ++i) d.rhs.segment<3>(int(3 * i)) = rhs[i];
  d.solution = d.ldlt.solve(d.rhs);
  for (std::size_t i = 0; i < rhs.size(); ++i)
    dv[i] = model_->pinned[i] ? Vec3::Zero() : Vec3(d.solution.segment<3>(int(3 * i)));
  return true;
}

void ImplicitEuler::step(double dt_s, StageTimes* times) {
  const double h = dt_s;
  const double next_time = state_.time_s + h;
  const Vec3 pin_offset = model_->pin_motion.offset_m(next_time);
  const std::size_t n = state_.x_m.size();
  const double mass_scale = model_->damping_mass_scale(h);
  x0_ = state_.x_m;
  v0_ = state_.v_m_s;
  std::vector<Vec3>& v = state_.v_m_s;
  for (std::size_t i = 0; i < n; ++i)
    if (model_->pinned[i]) v[i] = (rest_m_[i] + pin_offset - x0_[i]) / h;
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
        residual_[i] = model_->pinned[i] ? Vec3::Zero()
                                         : Vec3(h * (forces_[i] - scratch_[i]) -
                                                model_->mass_kg[i] * (mass_scale * v[i] - v0_[i]));
      if (!direct_) {  // the CG's preconditioner: A's diagonal blocks, inverted
        std::fill(stiffness_diagonal_.begin(), stiffness_diagonal_.end(), Mat3::Zero());
        std::fill(damping_diagonal_.begin(), damping_diagonal_.end(), Mat3::Zero());
        for (const auto& term : terms_) {
          term->add_stiffness_diagonal(stiffness_diagonal_);
          term->add_damping_diagonal(damping_diagonal_);
        }
        for (std::size_t i = 0; i < n; ++i) {
          const Mat3 block = mass_scale * model_->mass_kg[i] * Mat3::Identity() +
                             h * damping_diagonal_[i] + h * h * stiffness_diagonal_[i];
          block_inverse_[i] = model_->pinned[i] ? Mat3::Zero() : Mat3(block.inverse());
        }
      }
    });
    bool converged = true;
    run_timed(times, solve_stage_, [&] {
      converged = direct_ ? solve_direct(h, residual_, delta_) : solve(h, residual_, delta_);
    });
    if (!converged) break;
    for (std::size_t i = 0; i < n; ++i) v[i] += delta_[i];
  }
  const Vec3 pin_velocity = model_->pin_motion.velocity_m_s(next_time);
  for (std::size_t i = 0; i < n; ++i) {
    if (model_->pinned[i]) {
      state_.x_m[i] = rest_m_[i] + pin_offset;
      v[i] = pin_velocity;
    } else {
      state_.x_m[i] = x0_[i] + h * v[i];
    }
  }
  if (obstacles_) obstacles_->project(next_time, state_.x_m, v, model_->pinned, {}, x0_);
  state_.time_s = next_time;
}

std::optional<SolverNote> ImplicitEuler::divergence_advice() const {
  return SolverNote{.kind = SolverNote::Kind::kImplicitLinearization,
                    .substeps = substeps_,
                    .iterations = newton_iterations_};
}

std::string ImplicitEuler::solver_summary() const {
  const std::string halved =
      steps_undone_ == 0
          ? std::string()
          : fmt::format(
                "; {} of {} steps undone and halved (a strain changed by over {:g}% or the "
                "solve did not converge)",
                steps_undone_, steps_taken_, 100.0 * max_step_strain_change_);
  if (direct_)
    return fmt::format("{} Newton iteration{} a step, sparse LDL^T{}", newton_iterations_,
                       newton_iterations_ == 1 ? "" : "s", halved);
  return fmt::format("{} Newton iteration{} a step, CG {} iterations at most in the last frame{}",
                     newton_iterations_, newton_iterations_ == 1 ? "" : "s", cg_max_, halved);
}

}  // namespace flagsim::physics
