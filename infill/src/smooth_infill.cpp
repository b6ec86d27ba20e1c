#include "flagsim/infill/smooth_infill.hpp"

#include <algorithm>
#include <cassert>

namespace flagsim::infill {

SmoothInfill::SmoothInfill(const Lattice& fine, const CellGrid& grid)
    : lattice_(fine),
      grid_(grid),
      spline_(fine, grid),
      held_(fine.node_count(), 0),
      projection_(fine),
      coarse_row_stretch_(std::size_t(grid.coarse_rows) * std::size_t(grid.coarse_cols - 1)),
      coarse_col_stretch_(std::size_t(grid.coarse_rows - 1) * std::size_t(grid.coarse_cols)) {
  if (grid.row_stride % 2 == 0 && grid.col_stride % 2 == 0 &&
      std::min(grid.row_stride, grid.col_stride) / 2 >= kLevelStride) {
    const Lattice half = Lattice::rectangle((fine.rows + 1) / 2, (fine.cols + 1) / 2,
                                            fine.spacing_x_m * (fine.cols - 1),
                                            fine.spacing_y_m * (fine.rows - 1), fine.origin_m);
    coarser_ = std::make_unique<SmoothInfill>(
        half, CellGrid{grid.coarse_rows, grid.coarse_cols, grid.row_stride / 2, grid.col_stride / 2});
    coarser_positions_.resize(half.node_count());
    coarser_surface_.resize(half.node_count());
  }
}

void SmoothInfill::add_coarser_offsets(std::span<Vec3> positions_m) {
  const Lattice& half = coarser_->lattice_;
  const auto offset = [&](int j, int k) {
    const std::size_t i = half.index(j, k);
    return Vec3(coarser_positions_[i] - coarser_surface_[i]);
  };
  for (int j = 0; j < lattice_.rows; ++j)
    for (int k = 0; k < lattice_.cols; ++k) {
      const int j0 = j / 2, k0 = k / 2, j1 = (j + 1) / 2, k1 = (k + 1) / 2;
      positions_m[lattice_.index(j, k)] +=
          0.25 * (offset(j0, k0) + offset(j0, k1) + offset(j1, k0) + offset(j1, k1));
    }
}

void SmoothInfill::hold(std::span<const std::uint8_t> nodes) {
  for (std::size_t i = 0; i < held_.size(); ++i) held_[i] = held_[i] || nodes[i];
  projection_.hold(held_);
  if (coarser_) {
    std::vector<std::uint8_t> half(coarser_->lattice_.node_count());
    for (int j = 0; j < coarser_->lattice_.rows; ++j)
      for (int k = 0; k < coarser_->lattice_.cols; ++k)
        half[coarser_->lattice_.index(j, k)] = held_[lattice_.index(2 * j, 2 * k)];
    coarser_->hold(half);
  }
}

void SmoothInfill::register_stages(StageTimes& times) {
  stage_[0] = times.add("infill_3.1");  // with 3.2: one evaluation of the surface
  stage_[1] = times.add("infill_3.3");
  stage_[2] = times.add("infill_3.4");
}

void SmoothInfill::set_bands(std::span<const Vec3> coarse_m) {
  const int jc_count = grid_.coarse_rows, kc_count = grid_.coarse_cols;
  const int rs = grid_.row_stride, cs = grid_.col_stride;
  const double row_link_m = cs * lattice_.spacing_x_m, col_link_m = rs * lattice_.spacing_y_m;
  for (int jc = 0; jc < jc_count; ++jc)
    for (int kc = 0; kc < kc_count; ++kc) {
      const Vec3& p = coarse_m[grid_.coarse_index(jc, kc)];
      if (kc + 1 < kc_count)
        coarse_row_stretch_[std::size_t(jc) * (kc_count - 1) + std::size_t(kc)] =
            (coarse_m[grid_.coarse_index(jc, kc + 1)] - p).norm() / row_link_m - 1.0;
      if (jc + 1 < jc_count)
        coarse_col_stretch_[std::size_t(jc) * kc_count + std::size_t(kc)] =
            (coarse_m[grid_.coarse_index(jc + 1, kc)] - p).norm() / col_link_m - 1.0;
    }
  // A dense link lies between the two parallel coarse links of its cell (one,
  // on a coarse line); it may stretch as far as the more stretched of them.
  const auto upper = [](double stretch_a, double stretch_b) {
    return 1.0 + std::min(kStretchCap, std::max({kBand, stretch_a, stretch_b}));
  };
  const std::span<LinkBand> rows = projection_.row_bands(), cols = projection_.col_bands();
  const int J = lattice_.rows, K = lattice_.cols;
  for (int j = 0; j < J; ++j) {
    const int ja = j / rs, jb = std::min(jc_count - 1, (j + rs - 1) / rs);
    for (int k = 0; k + 1 < K; ++k) {
      const std::size_t kc = std::size_t(k / cs);
      rows[std::size_t(j) * (K - 1) + std::size_t(k)] = {
          1.0 - kBand, upper(coarse_row_stretch_[std::size_t(ja) * (kc_count - 1) + kc],
                             coarse_row_stretch_[std::size_t(jb) * (kc_count - 1) + kc])};
    }
  }
  for (int j = 0; j + 1 < J; ++j) {
    const std::size_t jc = std::size_t(j / rs);
    for (int k = 0; k < K; ++k) {
      const int ka = k / cs, kb = std::min(kc_count - 1, (k + cs - 1) / cs);
      cols[std::size_t(j) * K + std::size_t(k)] = {
          1.0 - kBand, upper(coarse_col_stretch_[jc * kc_count + std::size_t(ka)],
                             coarse_col_stretch_[jc * kc_count + std::size_t(kb)])};
    }
  }
}

void SmoothInfill::fill(std::span<const Vec3> coarse_m, std::span<Vec3> positions_m,
                        StageTimes* times) {
  assert(coarse_m.size() == grid_.coarse_count() && positions_m.size() == lattice_.node_count());
  if (coarser_)  // part of 3.4: the coarser levels' projections start this one's
    run_timed(times, stage_[2], [&] {
      coarser_->fill(coarse_m, coarser_positions_, nullptr);
      coarser_->spline_.evaluate(coarse_m, coarser_surface_);
    });
  run_timed(times, stage_[0], [&] {  // 3.1-3.2
    spline_.evaluate(coarse_m, positions_m);
    if (coarser_) add_coarser_offsets(positions_m);
  });
  run_timed(times, stage_[1], [&] { set_bands(coarse_m); });                        // 3.3
  ProjectionReport projected;
  run_timed(times, stage_[2], [&] {  // 3.4
    projected = projection_.project(positions_m, kProjectionTolerance, kMaxProjectionRounds,
                                    kStepsPerFiber);
  });
  report_.converged = projected.converged;
  report_.residual = projected.converged ? 0.0 : projected.worst_excess;
  report_.iterations = projected.rounds;
  report_.coarse_offset_m = 0.0;
  for (int jc = 0; jc < grid_.coarse_rows; ++jc)
    for (int kc = 0; kc < grid_.coarse_cols; ++kc)
      report_.coarse_offset_m =
          std::max(report_.coarse_offset_m, (positions_m[grid_.dense_index(lattice_, jc, kc)] -
                                             coarse_m[grid_.coarse_index(jc, kc)])
                                                .norm());
}

}  // namespace flagsim::infill
