#include "flagsim/coarse_physics/xpbd.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "flagsim/coarse_physics/bending_springs.hpp"
#include "flagsim/coarse_physics/cloth_state.hpp"
#include "flagsim/coarse_physics/creased_bending.hpp"
#include "flagsim/coarse_physics/force_terms.hpp"
#include "flagsim/core/lanes.hpp"
#include "flagsim/core/stop_request.hpp"

// Lanes are passed by value only between inlined helpers (core/lanes.hpp).
#pragma GCC diagnostic ignored "-Wpsabi"

namespace flagsim::physics {

double xpbd_propagation_substep_s(const ClothModel& model, double stretch_modulus_n_m,
                                  double areal_density_kg_m2, int iterations) {
  const double spacing = std::min(model.lattice.spacing_x_m, model.lattice.spacing_y_m);
  const double wave_speed = std::sqrt(stretch_modulus_n_m / areal_density_kg_m2);
  return double(iterations) * spacing / wave_speed;
}

Xpbd::Xpbd(const Scene& scene, std::shared_ptr<const ClothModel> model)
    : model_(std::move(model)),
      obstacles_(Obstacles::of(scene, model_->lattice)),
      rest_m_(model_->lattice.rest_positions()),
      // Stretch and bending are constraints below; the rest are forces.
      terms_(make_force_terms(scene, *model_, {.stretch = false, .bending = false})),
      effects_(physics_effects(scene, *model_)),
      state_(initial_state(scene, *model_)),
      iterations_(scene.solver.iterations.value_or(1)),
      frame_s_(1.0 / scene.fps),
      stable_substep_s_(0.0) {
  // With [creases], the bending stays a constraint and the creases' part of it
  // (creased_bending.hpp, plain = false) is a force with the others.
  if (std::unique_ptr<CreasedBending> creases = make_creased_bending(scene, *model_, false))
    terms_.insert(terms_.begin(), std::move(creases));
  stable_substep_s_ = explicit_stability_limit(*model_, terms_);
  substeps_ = physics::substeps_per_frame(frame_s_, stable_substep_s_, scene.solver.substeps);
  const double propagation =
      xpbd_propagation_substep_s(*model_, model_->material.stretch_modulus_n_m,
                                 model_->material.areal_density_kg_m2, iterations_);
  substeps_ = std::max(substeps_, int(std::ceil(frame_s_ / propagation - 1e-9)));
  const std::size_t n = model_->lattice.node_count();
  inverse_mass_.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    inverse_mass_[i] = model_->pinned[i] ? 0.0 : 1.0 / model_->mass_kg[i];
  forces_.assign(n, Vec3::Zero());

  // Links, two colours per family: row links alternate along the row (by k),
  // the others by row (j); no two links of one colour share a node.
  const int cols = model_->lattice.cols;
  for (const LinkFamily& family : model_->links) {
    std::vector<Link> groups[2];
    for_each_link(*model_, family, [&](std::size_t a, std::size_t b, double k, double rest) {
      if (inverse_mass_[a] + inverse_mass_[b] == 0.0 || k <= 0.0) return;  // two pins
      const int along = family.row_step == 0 ? int(a % cols) : int(a / cols);
      groups[along % 2].push_back({std::uint32_t(a), std::uint32_t(b), rest, 1.0 / k});
    });
    for (auto& group : groups)
      if (!group.empty()) link_groups_.push_back(std::move(group));
  }
  // Bending triples, three colours per direction, by the centre's place along the fiber.
  if (const std::optional<double> rigidity = model_->material.bending_rigidity_j) {
    std::vector<Triple> groups[2][3];
    for (const BendingTriple& t : bending_triples(model_->lattice, *rigidity)) {
      const bool row = t.c - t.b == 1;
      const int along = row ? int(t.b % cols) : int(t.b / cols);
      groups[row ? 0 : 1][along % 3].push_back({t.a, t.b, t.c, 1.0 / t.k_n_m});
    }
    for (auto& direction : groups)
      for (auto& group : direction)
        if (!group.empty()) bending_groups_.push_back(std::move(group));
  }
  link_lambda_.resize(link_groups_.size());
  link_rest_.resize(link_groups_.size());
  link_compliance_.resize(link_groups_.size());
  for (std::size_t g = 0; g < link_groups_.size(); ++g) {
    link_lambda_[g].resize(link_groups_[g].size());
    for (const Link& link : link_groups_[g]) {
      link_rest_[g].push_back(link.rest);
      link_compliance_[g].push_back(link.compliance);
    }
  }
  for (auto& axis : positions_) axis.resize(n);
  bending_lambda_.resize(bending_groups_.size());
  for (std::size_t g = 0; g < bending_groups_.size(); ++g)
    bending_lambda_[g].resize(bending_groups_[g].size());
}

void Xpbd::register_stages(StageTimes& times) {
  term_stage_ = register_term_stages(terms_, times);
  project_stage_ = times.add("constraints");
  update_stage_ = times.add("integrate");
}

void Xpbd::advance_frame(StageTimes* times) {
  advance_substeps(terms_, state_, substeps_, substep_s(), [&](double dt) {
    step(dt, times);
    return true;
  });
}

void Xpbd::step(double dt_s, StageTimes* times) {
  const double h = dt_s;
  const double next_time = state_.time_s + h;
  const std::size_t n = state_.x_m.size();
  std::fill(forces_.begin(), forces_.end(), Vec3::Zero());
  for (std::size_t t = 0; t < terms_.size(); ++t) {
    const int stage = term_stage_.empty() ? -1 : term_stage_[t];
    run_timed(times, stage, [&] { terms_[t]->add_forces(state_.x_m, state_.v_m_s, forces_); });
  }
  const Vec3 pin_offset = model_->pin_motion.offset_m(next_time);
  run_timed(times, update_stage_, [&] {
    const double damping = model_->velocity_damping(h);
    predicted_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      if (model_->pinned[i]) {
        predicted_[i] = rest_m_[i] + pin_offset;
      } else {
        state_.v_m_s[i] = (state_.v_m_s[i] + (h * inverse_mass_[i]) * forces_[i]) * damping;
        predicted_[i] = state_.x_m[i] + h * state_.v_m_s[i];
      }
    }
  });
  run_timed(times, project_stage_, [&] { project(h); });
  run_timed(times, update_stage_, [&] {
    const Vec3 pin_velocity = model_->pin_motion.velocity_m_s(next_time);
    const double inverse_h = 1.0 / h;
    if (obstacles_ && obstacles_->self_contact())
      step_start_m_.assign(state_.x_m.begin(), state_.x_m.end());
    for (std::size_t i = 0; i < n; ++i) {
      state_.v_m_s[i] =
          model_->pinned[i] ? pin_velocity : Vec3((predicted_[i] - state_.x_m[i]) * inverse_h);
      state_.x_m[i] = predicted_[i];
    }
    if (obstacles_)
      obstacles_->project(next_time, state_.x_m, state_.v_m_s, model_->pinned, {}, step_start_m_);
  });
  state_.time_s = next_time;
}

namespace {

using lanes::Lanes;

// Nodes a, a + 2, a + 4, a + 6 and a + 1, a + 3, a + 5, a + 7 of one
// coordinate (the row links (a, a + 1) of one colour), and back.
[[gnu::always_inline]] inline void deinterleave(const double* from, Lanes& even, Lanes& odd) {
  const Lanes low = lanes::load(from), high = lanes::load(from + lanes::kWidth);
  even = __builtin_shufflevector(low, high, 0, 2, 4, 6);
  odd = __builtin_shufflevector(low, high, 1, 3, 5, 7);
}
[[gnu::always_inline]] inline void interleave(double* to, Lanes even, Lanes odd) {
  lanes::store(to, __builtin_shufflevector(even, odd, 0, 4, 1, 5));
  lanes::store(to + lanes::kWidth, __builtin_shufflevector(even, odd, 2, 6, 3, 7));
}

}  // namespace

FLAGSIM_LANES_CLONES void Xpbd::project_links(std::size_t g, double inverse_h2) {
  using lanes::load;
  using lanes::splat;
  using lanes::store;
  constexpr int kLanes = lanes::kWidth;
  double* const px = positions_[0].data();
  double* const py = positions_[1].data();
  double* const pz = positions_[2].data();
  const double* const w = inverse_mass_.data();
  const std::vector<Link>& group = link_groups_[g];
  double* const lambda = link_lambda_[g].data();
  const double* const rest_of = link_rest_[g].data();
  const double* const compliance_of = link_compliance_[g].data();
  // C = |x_b - x_a| - S, dlambda = (-C - alpha lambda) / (w_a + w_b + alpha),
  // x_a -= w_a dlambda n, x_b += w_b dlambda n (XPBD, Macklin et al. 2016, eq. 18).
  const auto project_one = [&](std::size_t l) {
    const std::size_t a = group[l].a, b = group[l].b;
    const Vec3 d(px[b] - px[a], py[b] - py[a], pz[b] - pz[a]);
    const double length = d.norm();
    if (length == 0.0) return;  // no direction to correct along
    const double alpha = compliance_of[l] * inverse_h2;
    const double w_a = w[a], w_b = w[b];
    const double dlambda = (-(length - rest_of[l]) - alpha * lambda[l]) / (w_a + w_b + alpha);
    lambda[l] += dlambda;
    const Vec3 step = (dlambda / length) * d;
    px[a] -= w_a * step.x(), py[a] -= w_a * step.y(), pz[a] -= w_a * step.z();
    px[b] += w_b * step.x(), py[b] += w_b * step.y(), pz[b] += w_b * step.z();
  };
  std::size_t l = 0;
  for (; l + kLanes <= group.size(); l += kLanes) {
    // The batch's layout: links of consecutive nodes (column links and
    // diagonals, within a row), of every second node with b = a + 1 (row
    // links), or anything else (a row's end, a link left out between pins).
    const std::size_t a0 = group[l].a, b0 = group[l].b;
    const std::size_t stride = group[l + 1].a - a0;
    bool regular = stride == 1 || (stride == 2 && b0 == a0 + 1);
    for (std::size_t i = 1; i < std::size_t(kLanes) && regular; ++i)
      regular = group[l + i].a == a0 + i * stride && group[l + i].b == b0 + i * stride;
    Lanes ax, ay, az, bx, by, bz, w_a, w_b;
    if (regular && stride == 1) {
      ax = load(px + a0), ay = load(py + a0), az = load(pz + a0);
      bx = load(px + b0), by = load(py + b0), bz = load(pz + b0);
      w_a = load(w + a0), w_b = load(w + b0);
    } else if (regular) {
      deinterleave(px + a0, ax, bx);
      deinterleave(py + a0, ay, by);
      deinterleave(pz + a0, az, bz);
      deinterleave(w + a0, w_a, w_b);
    } else {
      for (int i = 0; i < kLanes; ++i) {
        const std::size_t a = group[l + std::size_t(i)].a, b = group[l + std::size_t(i)].b;
        ax[i] = px[a], ay[i] = py[a], az[i] = pz[a];
        bx[i] = px[b], by[i] = py[b], bz[i] = pz[b];
        w_a[i] = w[a], w_b[i] = w[b];
      }
    }
    const Lanes old_lambda = load(lambda + l);
    const Lanes dx = bx - ax, dy = by - ay, dz = bz - az;
    const Lanes length2 = (dx * dx + dy * dy) + dz * dz;
    Lanes length;
    for (int i = 0; i < kLanes; ++i) length[i] = std::sqrt(length2[i]);
    const auto moves = length != splat(0.0);
    const Lanes safe_length = moves ? length : splat(1.0);
    const Lanes alpha = load(compliance_of + l) * splat(inverse_h2);
    const Lanes dlambda =
        (-(length - load(rest_of + l)) - alpha * old_lambda) / ((w_a + w_b) + alpha);
    const Lanes scale = dlambda / safe_length;
    const Lanes sx = scale * dx, sy = scale * dy, sz = scale * dz;
    // A link of zero length keeps its nodes and multiplier (as project_one).
    store(lambda + l, moves ? old_lambda + dlambda : old_lambda);
    ax = moves ? ax - w_a * sx : ax, ay = moves ? ay - w_a * sy : ay;
    az = moves ? az - w_a * sz : az;
    bx = moves ? bx + w_b * sx : bx, by = moves ? by + w_b * sy : by;
    bz = moves ? bz + w_b * sz : bz;
    if (regular && stride == 1) {
      store(px + a0, ax), store(py + a0, ay), store(pz + a0, az);
      store(px + b0, bx), store(py + b0, by), store(pz + b0, bz);
    } else if (regular) {
      interleave(px + a0, ax, bx);
      interleave(py + a0, ay, by);
      interleave(pz + a0, az, bz);
    } else {
      for (int i = 0; i < kLanes; ++i) {
        const std::size_t a = group[l + std::size_t(i)].a, b = group[l + std::size_t(i)].b;
        px[a] = ax[i], py[a] = ay[i], pz[a] = az[i];
        px[b] = bx[i], py[b] = by[i], pz[b] = bz[i];
      }
    }
  }
  for (; l < group.size(); ++l) project_one(l);
}

void Xpbd::project(double dt_s) {
  const double inverse_h2 = 1.0 / (dt_s * dt_s);
  std::vector<Vec3>& p = predicted_;
  const std::vector<double>& w = inverse_mass_;
  for (auto& lambda : link_lambda_) std::fill(lambda.begin(), lambda.end(), 0.0);
  for (auto& lambda : bending_lambda_) std::fill(lambda.begin(), lambda.end(), Vec3::Zero());
  for (int iteration = 0; iteration < iterations_; ++iteration) {
    lanes::split(p, positions_);
    for (std::size_t g = 0; g < link_groups_.size(); ++g) project_links(g, inverse_h2);
    lanes::join(positions_, p);
    for (std::size_t g = 0; g < bending_groups_.size(); ++g) {
      const std::vector<Triple>& group = bending_groups_[g];
      std::vector<Vec3>& lambda = bending_lambda_[g];
      for (std::size_t t = 0; t < group.size(); ++t) {
        const Triple& triple = group[t];
        const double w_a = w[triple.a], w_b = w[triple.b], w_c = w[triple.c];
        const double weight = w_a + 4.0 * w_b + w_c;
        if (weight == 0.0) continue;  // three pins
        const double alpha = triple.compliance * inverse_h2;
        const Vec3 q = p[triple.a] - 2.0 * p[triple.b] + p[triple.c];
        const Vec3 dlambda = (-q - alpha * lambda[t]) / (weight + alpha);
        lambda[t] += dlambda;
        p[triple.a] += w_a * dlambda;
        p[triple.b] -= 2.0 * w_b * dlambda;
        p[triple.c] += w_c * dlambda;
      }
    }
  }
}

std::optional<SolverNote> Xpbd::divergence_advice() const {
  return SolverNote{
      .kind = SolverNote::Kind::kXpbdSubstep, .substeps = substeps_, .iterations = iterations_};
}

std::string Xpbd::solver_summary() const {
  return fmt::format("{} constraint pass{} a substep over {} + {} colour groups", iterations_,
                     iterations_ == 1 ? "" : "es", link_groups_.size(), bending_groups_.size());
}

}  // namespace flagsim::physics
