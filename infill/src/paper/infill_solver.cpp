#include "flagsim/infill/paper/infill_solver.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <optional>

#include "flagsim/core/stop_request.hpp"
#include "flagsim/core/strain.hpp"
#include "flagsim/infill/paper/boundary.hpp"
#include "flagsim/infill/paper/initial_move.hpp"
#include "flagsim/infill/paper/length_search.hpp"
#include "flagsim/infill/paper/relax.hpp"

namespace flagsim::infill {

InfillSolver::InfillSolver(const Lattice& fine, const CellGrid& grid, int relax_sweeps,
                           std::optional<WrinkleParams> wrinkles, int rounds,
                           std::optional<CreaseRidgeParams> creases)
    : lattice_(fine),
      grid_(grid),
      relax_sweeps_(relax_sweeps),
      wrinkles_(wrinkles),
      rounds_(rounds),
      crease_params_(creases) {
  if (crease_params_) unridged_.assign(fine.node_count(), Vec3::Zero());
  const int rs = grid.row_stride, cs = grid.col_stride, cols = fine.cols;
  held_.assign(fine.node_count(), 0);
  for (int jc = 0; jc < grid.coarse_rows; ++jc) {
    for (int kc = 0; kc < grid.coarse_cols; ++kc) {
      const std::size_t n = grid.dense_index(fine, jc, kc);
      coarse_dense_.push_back(n);
      held_[n] = 1;
      const auto coarse_at = [&](int j, int k) -> std::ptrdiff_t {
        if (j < 0 || k < 0 || j >= grid.coarse_rows || k >= grid.coarse_cols) return -1;
        return std::ptrdiff_t(grid.dense_index(fine, j, k));
      };
      // A cell is named by its top-left coarse node; it exists when that node
      // has coarse neighbours to the right and below.
      const auto cell_at = [&](int j, int k) -> std::ptrdiff_t {
        if (j < 0 || k < 0 || j + 1 >= grid.coarse_rows || k + 1 >= grid.coarse_cols) return -1;
        return coarse_at(j, k);
      };
      if (kc + 1 < grid.coarse_cols && cs > 1)
        edges_.push_back({{n, 1, cs, fine.spacing_x_m},
                          coarse_at(jc, kc - 1),
                          coarse_at(jc, kc + 2),
                          {cell_at(jc - 1, kc), cell_at(jc, kc)}});
      if (jc + 1 < grid.coarse_rows && rs > 1)
        edges_.push_back({{n, cols, rs, fine.spacing_y_m},
                          coarse_at(jc - 1, kc),
                          coarse_at(jc + 2, kc),
                          {cell_at(jc, kc - 1), cell_at(jc, kc)}});
    }
  }
  for (int jc = 0; jc + 1 < grid.coarse_rows; ++jc) {
    for (int kc = 0; kc + 1 < grid.coarse_cols; ++kc) {
      const int j0 = jc * rs, k0 = kc * cs;
      if (cs > 1)
        for (int j = j0 + 1; j < j0 + rs; ++j)
          cell_rows_.push_back({fine.index(j, k0), 1, cs, fine.spacing_x_m});
      if (rs > 1)
        for (int k = k0 + 1; k < k0 + cs; ++k)
          cell_cols_.push_back({fine.index(j0, k), cols, rs, fine.spacing_y_m});
    }
  }
  previous_.resize(fine.node_count());
  coarse_start_.resize(coarse_dense_.size());
  coarse_step_.resize(coarse_dense_.size());
}

void InfillSolver::hold(std::span<const std::uint8_t> nodes) {
  for (std::size_t i = 0; i < held_.size(); ++i) held_[i] = held_[i] || nodes[i];
}

void InfillSolver::register_stages(StageTimes& times) {
  stages_.boundary = times.add("infill_3.1", StageGroup::kInfill);
  stages_.initial_move = times.add("infill_3.2", StageGroup::kInfill);
  stages_.length = times.add("infill_3.3", StageGroup::kInfill);
  stages_.relax = times.add("infill_3.4", StageGroup::kInfill);
  if (wrinkles_) stages_.wrinkles = times.add("infill_3.5", StageGroup::kInfill);
  if (crease_params_) stages_.creases = times.add("infill_creases", StageGroup::kInfill);
}

void InfillSolver::set_dense_creases(std::span<const double> dense_rest_rad) {
  if (!crease_params_) return;  // made without [creases]: draws none
  if (!dense_creases_)
    dense_creases_.emplace(lattice_, CellGrid::of(lattice_, lattice_.rows, lattice_.cols),
                           *crease_params_);
  dense_creases_->set_rest(dense_rest_rad);
}

std::vector<double> InfillSolver::memory() const {
  if (!crease_params_) return {};
  std::vector<double> memory = {ridged_ ? 1.0 : 0.0};
  memory.reserve(1 + 3 * unridged_.size());
  for (const Vec3& p : unridged_) memory.insert(memory.end(), {p.x(), p.y(), p.z()});
  return memory;
}

void InfillSolver::set_memory(std::span<const double> memory) {
  if (!crease_params_) return;
  assert(memory.size() == 1 + 3 * unridged_.size());
  ridged_ = memory[0] != 0.0;
  for (std::size_t i = 0; i < unridged_.size(); ++i)
    unridged_[i] = Vec3(memory[1 + 3 * i], memory[2 + 3 * i], memory[3 + 3 * i]);
}

std::size_t InfillSolver::cell_corner_of(std::size_t node) const {
  const int j = int(node / std::size_t(lattice_.cols)), k = int(node % std::size_t(lattice_.cols));
  const CellGrid::Place at = grid_.place(j, k);
  return grid_.dense_index(lattice_, at.jc, at.kc);
}

Vec3 InfillSolver::cell_normal(std::size_t corner, std::span<const Vec3> positions_m) const {
  const std::size_t down = std::size_t(grid_.row_stride) * std::size_t(lattice_.cols);
  const std::size_t right = std::size_t(grid_.col_stride);
  const Vec3& p00 = positions_m[corner];
  const Vec3& p01 = positions_m[corner + right];
  const Vec3& p10 = positions_m[corner + down];
  const Vec3& p11 = positions_m[corner + down + right];
  return ((p01 - p00) + (p11 - p10)).cross((p10 - p00) + (p11 - p01));
}

void InfillSolver::rewrinkle(std::span<Vec3> positions_m) {
  // Each fiber's ends are on its cell's edges, which 3.5 leaves as 3.1 put them,
  // except lone edges (corners only), which get the same treatment first.
  for (const Edge& edge : edges_)
    if (edge.before < 0 && edge.after < 0)
      rewrinkle_fiber(edge.fiber, positions_m,
                      cell_normal(cell_corner_of(edge.fiber.first), positions_m), *wrinkles_);
  for (const Fiber& row : cell_rows_)
    rewrinkle_fiber(row, positions_m, cell_normal(cell_corner_of(row.first), positions_m),
                    *wrinkles_);
  for (const Fiber& col : cell_cols_)
    rewrinkle_fiber(col, positions_m, cell_normal(cell_corner_of(col.first), positions_m),
                    *wrinkles_);
}

void InfillSolver::fill(std::span<const Vec3> coarse_m, std::span<Vec3> positions_m,
                        StageTimes* times) {
  // The last fill's ridges off: the lattice it carries is the one before them.
  if (ridged_) std::copy(unridged_.begin(), unridged_.end(), positions_m.begin());
  double largest_motion = 0.0;
  for (std::size_t c = 0; c < coarse_dense_.size(); ++c) {
    coarse_start_[c] = positions_m[coarse_dense_[c]];
    largest_motion = std::max(largest_motion, (coarse_m[c] - coarse_start_[c]).norm());
  }
  const double cell_side =
      std::min(grid_.row_stride * lattice_.spacing_y_m, grid_.col_stride * lattice_.spacing_x_m);
  const double wanted = std::ceil(largest_motion / (kMaxStepFraction * cell_side));
  const int steps = int(std::clamp(wanted, 1.0, double(kMaxCutSteps)));
  last_steps_ = steps;
  last_sweeps_ = 0;
  capped_ = wanted > kMaxCutSteps;  // steps longer than a cell: not the paper's 3.1
  for (int s = 1; s <= steps && !stop_requested(); ++s) {
    const double t = double(s) / steps;
    for (std::size_t c = 0; c < coarse_dense_.size(); ++c)
      coarse_step_[c] =
          s == steps ? coarse_m[c] : Vec3(coarse_start_[c] + t * (coarse_m[c] - coarse_start_[c]));
    deform(coarse_step_, positions_m, times);
  }
  ridged_ = dense_creases_ && dense_creases_->any();
  if (ridged_) {
    std::copy(positions_m.begin(), positions_m.end(), unridged_.begin());
    run_timed(times, stages_.creases, [&] {
      add_dense_ridges(*dense_creases_, lattice_, positions_m, held_, dense_normals_, dense_copy_);
    });
    run_timed(times, stages_.relax, [&] {  // 3.4: the fibers keep their lengths
      const int sweeps =
          relax_lattice(lattice_, held_, positions_m, relax_sweeps_, kRelaxTolerance);
      last_sweeps_ += sweeps;
      capped_ = capped_ || sweeps >= relax_sweeps_;
    });
  }
  report_.converged = !capped_;
  report_.iterations = last_sweeps_;
  report_.residual =
      capped_ ? std::max(0.0, link_strain(lattice_, positions_m).max - kRelaxTolerance) : 0.0;
  report_.coarse_offset_m = 0.0;
  for (std::size_t c = 0; c < coarse_dense_.size(); ++c)
    report_.coarse_offset_m =
        std::max(report_.coarse_offset_m, (positions_m[coarse_dense_[c]] - coarse_m[c]).norm());
}

void InfillSolver::deform(std::span<const Vec3> coarse_target_m, std::span<Vec3> positions_m,
                          StageTimes* times) {
  auto timed = [&](int stage, auto&& work) { run_timed(times, stage, work); };
  auto relax = [&] {  // 3.4
    const int sweeps = relax_lattice(lattice_, held_, positions_m, relax_sweeps_, kRelaxTolerance);
    last_sweeps_ += sweeps;
    capped_ = capped_ || sweeps >= relax_sweeps_;
  };
  std::copy(positions_m.begin(), positions_m.end(), previous_.begin());
  timed(stages_.boundary,
        [&] {  // 3.1: coarse nodes to their targets, then every cell edge as a fiber
          for (std::size_t c = 0; c < coarse_dense_.size(); ++c)
            positions_m[coarse_dense_[c]] = coarse_target_m[c];
          for (const Edge& edge : edges_) {
            // The cloth's normal at the edge: its cells' normals, averaged.
            Vec3 normal = Vec3::Zero();
            for (std::ptrdiff_t cell : edge.cells)
              if (cell >= 0) normal += cell_normal(std::size_t(cell), positions_m).normalized();
            move_edge(edge.fiber, edge.before, edge.after, normal, positions_m, previous_,
                      kLengthTolerance);
            // A lone edge got the paper's fiber steps and needs 3.4; an arc is exact.
            if (edge.before < 0 && edge.after < 0)
              relax_fiber(edge.fiber, positions_m, relax_sweeps_, kRelaxTolerance);
          }
        });
  timed(stages_.initial_move,
        [&] { initial_move_cells(lattice_, grid_, positions_m, previous_); });  // 3.2
  timed(stages_.length, [&] {  // 3.3: rows, then columns
    for (const Fiber& row : cell_rows_)
      length_search(row, positions_m, previous_, kLengthTolerance, length_scratch_);
    for (const Fiber& col : cell_cols_)
      length_search(col, positions_m, previous_, kLengthTolerance, length_scratch_);
  });
  timed(stages_.relax, relax);
  if (!wrinkles_) return;  // no [wrinkles]: 3.5 is not scheduled at all
  for (int round = 0; round < rounds_; ++round) {
    timed(stages_.wrinkles, [&] { rewrinkle(positions_m); });
    timed(stages_.relax, relax);
  }
}

}  // namespace flagsim::infill
