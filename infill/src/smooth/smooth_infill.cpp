#include "flagsim/infill/smooth/smooth_infill.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>
#include <utility>

#include "flagsim/core/lanes.hpp"

namespace flagsim::infill {

SmoothInfill::SmoothInfill(const Lattice& fine, const CellGrid& grid,
                           std::optional<WrinkleParams> wrinkles,
                           std::optional<CreaseRidgeParams> creases, double fold_limit_rad)
    : lattice_(fine),
      grid_(grid),
      spline_(fine, grid),
      held_(fine.node_count(), 0),
      projection_(fine),
      coarse_row_stretch_(std::size_t(grid.coarse_rows) * std::size_t(grid.coarse_cols - 1)),
      coarse_col_stretch_(std::size_t(grid.coarse_rows - 1) * std::size_t(grid.coarse_cols)),
      wrinkles_(wrinkles) {
  surface_.resize(fine.node_count());
  fold_limit_rad_ = fold_limit_rad;
  if (fold_limit_rad_ > 0.0) {
    fold_weight_.resize(grid.coarse_count());
    flat_.resize(fine.node_count());
  }
  correction_.resize(fine.node_count());
  smoothed_.resize(fine.node_count());
  // 3.3's weights along the rows: row links between coarse row-link midpoints,
  // column links between coarse columns.
  for (int k = 0; k + 1 < fine.cols; ++k)
    row_link_taps_.push_back(taps_at((k + 0.5) / grid.col_stride - 0.5, grid.coarse_cols - 1));
  for (int k = 0; k < fine.cols; ++k)
    col_node_taps_.push_back(taps_at(double(k) / grid.col_stride, grid.coarse_cols));
  if (creases) creases_.emplace(fine, grid, *creases);
  crease_params_ = creases;
  if (wrinkles_ || creases_) normals_.resize(fine.node_count());
  if (wrinkles_) {
    last_offset_.assign(fine.node_count(), 0.0);
    wave_.resize(std::size_t(std::max(fine.rows, fine.cols)));
  }
  if (grid.row_stride % 2 == 0 && grid.col_stride % 2 == 0 &&
      std::min(grid.row_stride, grid.col_stride) / 2 >= kLevelStride) {
    const Lattice half = Lattice::rectangle((fine.rows + 1) / 2, (fine.cols + 1) / 2,
                                            fine.spacing_x_m * (fine.cols - 1),
                                            fine.spacing_y_m * (fine.rows - 1), fine.origin_m);
    coarser_ = std::make_unique<SmoothInfill>(
        half,
        CellGrid{grid.coarse_rows, grid.coarse_cols, grid.row_stride / 2, grid.col_stride / 2},
        wrinkles, std::nullopt, fold_limit_rad);
    coarser_positions_.resize(half.node_count());
    coarser_offsets_.resize(std::size_t(half.rows) * std::size_t(fine.cols));
  }
  // Whether the levels below smooth is decided by the cells of the lattice the
  // user sees: each level sets it for the levels below it, and the finest
  // level, constructed last, has the final word. Every level below the finest
  // smooths (each hands its correction to the next); a level alone, the
  // coarsest without a finer one, decides for itself.
  const bool smooth = std::min(grid.row_stride, grid.col_stride) >= kSmoothedCellLinks;
  if (!coarser_) smooths_ = smooth;
  for (SmoothInfill* level = coarser_.get(); level; level = level->coarser_.get())
    level->smooths_ = smooth;
}

// Weights of the coarser samples that give fine sample `i` (of `n`): the
// sample itself when i is even; between two, the 4-point interpolatory
// subdivision of Dubuc and Deslauriers ((-1, 9, 9, -1) / 16, exact for cubics),
// linear next to an end. Bilinear midpoints instead leave a kink at every
// coarser node, which the projection (it corrects lengths, not angles) keeps:
// turning-angle spikes every 4th row, measured.
struct Upsample {
  int first = 0, count = 1;
  double weight[4] = {1.0, 0.0, 0.0, 0.0};
};

static Upsample upsample_weights(int i, int coarse_count) {
  Upsample u;
  if (i % 2 == 0) {
    u.first = i / 2;
    return u;
  }
  const int left = i / 2;  // between coarser samples left and left + 1
  if (left >= 1 && left + 2 < coarse_count) {
    u.first = left - 1;
    u.count = 4;
    u.weight[0] = -1.0 / 16.0;
    u.weight[1] = 9.0 / 16.0;
    u.weight[2] = 9.0 / 16.0;
    u.weight[3] = -1.0 / 16.0;
  } else {
    u.first = left;
    u.count = 2;
    u.weight[0] = u.weight[1] = 0.5;
  }
  return u;
}

namespace {

// to[i] += w * from[i] for i < n: Vec3's own operations, a coordinate at a
// time (so the same bits), vectorised over the whole row.
FLAGSIM_LANES_CLONES void add_scaled(double w, const double* from, std::size_t n, double* to) {
  for (std::size_t i = 0; i < n; ++i) to[i] += w * from[i];
}

}  // namespace

void SmoothInfill::add_coarser_offsets(std::span<Vec3> positions_m) {
  const Lattice& half = coarser_->lattice_;
  const int K = lattice_.cols;
  // Separable: along the rows into [half.rows x K], then down the columns.
  for (int jh = 0; jh < half.rows; ++jh)
    for (int k = 0; k < K; ++k) {
      const Upsample uk = upsample_weights(k, half.cols);
      Vec3 sum = Vec3::Zero();
      for (int b = 0; b < uk.count; ++b) {
        const std::size_t i = half.index(jh, uk.first + b);
        sum += uk.weight[b] * (coarser_positions_[i] - coarser_->surface_[i]);
      }
      coarser_offsets_[std::size_t(jh) * std::size_t(K) + std::size_t(k)] = sum;
    }
  for (int j = 0; j < lattice_.rows; ++j) {
    const Upsample uj = upsample_weights(j, half.rows);
    static_assert(sizeof(Vec3) == 3 * sizeof(double));
    for (int a = 0; a < uj.count; ++a)
      add_scaled(uj.weight[a], coarser_offsets_[std::size_t(uj.first + a) * std::size_t(K)].data(),
                 3 * std::size_t(K), positions_m[lattice_.index(j, 0)].data());
  }
}

void SmoothInfill::smooth_correction(std::span<Vec3> positions_m) {
  const int J = lattice_.rows, K = lattice_.cols;
  for (std::size_t i = 0; i < correction_.size(); ++i)
    correction_[i] = positions_m[i] - surface_[i];
  // Binomial (1, 2, 1) / 4 along the rows, then down the columns, ends
  // repeated; kSmoothingPasses times.
  for (int pass = 0; pass < kSmoothingPasses; ++pass) {
    for (int j = 0; j < J; ++j) {
      const Vec3* in = &correction_[lattice_.index(j, 0)];
      Vec3* out = &smoothed_[lattice_.index(j, 0)];
      for (int k = 0; k < K; ++k)
        out[k] = 0.5 * in[k] + 0.25 * (in[std::max(k - 1, 0)] + in[std::min(k + 1, K - 1)]);
    }
    for (int j = 0; j < J; ++j) {
      const Vec3* up = &smoothed_[lattice_.index(std::max(j - 1, 0), 0)];
      const Vec3* here = &smoothed_[lattice_.index(j, 0)];
      const Vec3* down = &smoothed_[lattice_.index(std::min(j + 1, J - 1), 0)];
      Vec3* out = &correction_[lattice_.index(j, 0)];
      for (int k = 0; k < K; ++k) out[k] = 0.5 * here[k] + 0.25 * (up[k] + down[k]);
    }
  }
  for (std::size_t i = 0; i < correction_.size(); ++i)
    if (!held_[i]) positions_m[i] = surface_[i] + correction_[i];
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
  stages_.surface = times.add("infill_3.1", StageGroup::kInfill);  // with 3.2: one evaluation
  stages_.bands = times.add("infill_3.3", StageGroup::kInfill);
  stages_.projection = times.add("infill_3.4", StageGroup::kInfill);
  if (wrinkles_) stages_.wrinkles = times.add("infill_3.5", StageGroup::kInfill);
  if (creases_) stages_.creases = times.add("infill_creases", StageGroup::kInfill);
}

void SmoothInfill::set_dense_creases(std::span<const double> dense_rest_rad) {
  if (!crease_params_) return;  // made without [creases]: draws none
  if (!dense_creases_)
    dense_creases_.emplace(lattice_, CellGrid::of(lattice_, lattice_.rows, lattice_.cols),
                           *crease_params_);
  dense_creases_->set_rest(dense_rest_rad);
}

void SmoothInfill::set_normals() {
  // The surface's normal at every node, from its neighbours along both fibers.
  const NodeView surface(lattice_, std::as_const(surface_));
  const NodeView normals(lattice_, normals_);
  for (int j = 0; j < lattice_.rows; ++j)
    for (int k = 0; k < lattice_.cols; ++k) {
      const Vec3 along_row = surface.clamped(j, k + 1) - surface.clamped(j, k - 1);
      const Vec3 along_col = surface.clamped(j + 1, k) - surface.clamped(j - 1, k);
      normals.at(j, k) = along_row.cross(along_col).normalized();
    }
}

void SmoothInfill::add_wrinkles(std::span<Vec3> positions_m) {
  const int J = lattice_.rows, K = lattice_.cols;
  set_normals();
  std::vector<double> offset(lattice_.node_count(), 0.0);
  const auto fiber_wave = [&](std::size_t first, std::size_t stride, int segments, double rest_m) {
    double length = 0.0;  // c: the fiber along the surface
    for (int i = 0; i < segments; ++i)
      length += (surface_[first + std::size_t(i + 1) * stride] -
                 surface_[first + std::size_t(i) * stride])
                    .norm();
    const double slack = segments * rest_m - length;  // dL of eq. (13)
    if (slack <= 0.0 || wrinkles_->k_r4 <= 0.0) return;
    const int half_waves = half_wave_count(length, slack, segments, *wrinkles_);
    // y = A sin(m pi s / c) over the fiber, as long as the fiber's rest length.
    const double amplitude = wave_amplitude_m(length, segments * rest_m, half_waves, segments);
    double walked = 0.0, match = 0.0;
    for (int i = 0; i <= segments; ++i) {
      const std::size_t node = first + std::size_t(i) * stride;
      if (i > 0) walked += (surface_[node] - surface_[node - stride]).norm();
      wave_[std::size_t(i)] = amplitude * std::sin(half_waves * std::numbers::pi * walked / length);
      match += wave_[std::size_t(i)] * last_offset_[node];
    }
    const double sign = match < 0.0 ? -1.0 : 1.0;  // the side it was on (property 2)
    for (int i = 0; i <= segments; ++i)
      offset[first + std::size_t(i) * stride] += sign * wave_[std::size_t(i)];
  };
  for (int j = 0; j < J; ++j) fiber_wave(lattice_.index(j, 0), 1, K - 1, lattice_.spacing_x_m);
  for (int k = 0; k < K; ++k)
    fiber_wave(lattice_.index(0, k), std::size_t(K), J - 1, lattice_.spacing_y_m);
  // The re-lay: each node's offset along the normal becomes the waves'.
  for (std::size_t i = 0; i < positions_m.size(); ++i)
    if (!held_[i])
      positions_m[i] += (offset[i] - (positions_m[i] - surface_[i]).dot(normals_[i])) * normals_[i];
}

SmoothInfill::Taps SmoothInfill::taps_at(double x, int count) {
  // x in samples 0 .. count - 1 (clamped), between samples a and a + 1 at t.
  Taps taps;
  if (count < 2) return taps;
  const double clamped = std::clamp(x, 0.0, double(count - 1));
  const int a = std::min(int(clamped), count - 2);
  const double t = clamped - a, t2 = t * t, t3 = t2 * t;
  const double weight[4] = {0.5 * (-t3 + 2.0 * t2 - t), 0.5 * (3.0 * t3 - 5.0 * t2 + 2.0),
                            0.5 * (-3.0 * t3 + 4.0 * t2 + t), 0.5 * (t3 - t2)};
  for (int i = 0; i < 4; ++i) {
    taps.index[i] = std::clamp(a - 1 + i, 0, count - 1);
    taps.weight[i] = weight[i];
  }
  return taps;
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
  // A dense link may stretch as far as the coarse links around it: their
  // stretch interpolated (cubic, Catmull-Rom: C1), across the cell (between
  // the parallel coarse links) and along the fiber (between the midpoints of
  // consecutive coarse links). Linear interpolation across left the row
  // fibers' lengths with a kink in j at every coarse row, which the columns
  // between them follow: default scene, frames after 1 s with the median
  // turning on coarse rows over 1.3x that between, 3 of 271 (linear) -> 1. A band that stepped at
  // each coarse line (each cell's own, the more stretched of its two links) made the fibers on a
  // coarse line shorter or longer than their neighbours, and changed every
  // fiber's correction abruptly where it crossed one: a crease there
  // (measured: turning angles on coarse rows up to 1.6x those between).
  // Separable: first along each coarse line (to every dense link position
  // on it), then across, between the two coarse lines on either side.
  // (The weights along the rows depend on the lattice only: kept from the
  // constructor, row_link_taps_ and col_node_taps_.)
  // The band around the target: the coarse stretch, none where compressed.
  const auto band = [](double stretch) {
    const double target = 1.0 + std::clamp(stretch, 0.0, kStretchCap);
    return LinkBand{target * (1.0 - kBand), target * (1.0 + kBand)};
  };
  LinkField<LinkBand>& bands = projection_.bands();
  const int J = lattice_.rows, K = lattice_.cols;
  // Row links: coarse row links lie on coarse rows jc, their midpoints at kc + 1/2.
  const auto at = [](const Taps& w, const double* line, std::size_t stride) {
    return w.weight[0] * line[std::size_t(w.index[0]) * stride] +
           w.weight[1] * line[std::size_t(w.index[1]) * stride] +
           w.weight[2] * line[std::size_t(w.index[2]) * stride] +
           w.weight[3] * line[std::size_t(w.index[3]) * stride];
  };
  along_.resize(std::size_t(std::max(jc_count * (K - 1), (J - 1) * kc_count)));
  for (int jc = 0; jc < jc_count; ++jc) {
    const double* line = &coarse_row_stretch_[std::size_t(jc) * std::size_t(kc_count - 1)];
    for (int k = 0; k + 1 < K; ++k)
      along_[std::size_t(jc) * std::size_t(K - 1) + std::size_t(k)] =
          at(row_link_taps_[std::size_t(k)], line, 1);
  }
  for (int j = 0; j < J; ++j) {
    // at(w, ...) with its four lines fixed for the row: one loop down k.
    const Taps w = taps_at(double(j) / rs, jc_count);
    const double* line[4];
    for (int t = 0; t < 4; ++t) line[t] = &along_[std::size_t(w.index[t]) * std::size_t(K - 1)];
    LinkBand* out = &bands.row(j, 0);
    for (int k = 0; k + 1 < K; ++k)
      out[k] = band(w.weight[0] * line[0][k] + w.weight[1] * line[1][k] + w.weight[2] * line[2][k] +
                    w.weight[3] * line[3][k]);
  }
  // Column links: coarse column links lie on coarse columns kc, midpoints at jc + 1/2.
  for (int j = 0; j + 1 < J; ++j) {
    const Taps w = taps_at((j + 0.5) / rs - 0.5, jc_count - 1);
    for (int kc = 0; kc < kc_count; ++kc)
      along_[std::size_t(j) * std::size_t(kc_count) + std::size_t(kc)] =
          at(w, &coarse_col_stretch_[std::size_t(kc)], std::size_t(kc_count));
  }
  for (int j = 0; j + 1 < J; ++j) {
    const double* line = &along_[std::size_t(j) * std::size_t(kc_count)];
    LinkBand* out = &bands.col(j, 0);
    for (int k = 0; k < K; ++k) out[k] = band(at(col_node_taps_[std::size_t(k)], line, 1));
  }
}

std::vector<double> SmoothInfill::memory() const {
  // This level's offsets, then every coarser level's (each has 3.5 too).
  std::vector<double> memory = last_offset_;
  if (coarser_) {
    const std::vector<double> coarser = coarser_->memory();
    memory.insert(memory.end(), coarser.begin(), coarser.end());
  }
  return memory;
}

void SmoothInfill::set_memory(std::span<const double> memory) {
  assert(memory.size() == this->memory().size());
  std::copy_n(memory.begin(), last_offset_.size(), last_offset_.begin());
  if (coarser_) coarser_->set_memory(memory.subspan(last_offset_.size()));
}

void SmoothInfill::follow_sharp_folds(std::span<const Vec3> coarse_m) {
  // Each coarse node's weight from the sharpest turn of its row or column
  // there: 1 (the spline) up to fold_limit_rad_, 0 (the coarse triangles) from
  // twice that, linear between. The weights are interpolated over each cell
  // bilinearly, and a dense node with a weight under 1 moves from the spline to
  // flat + weight (spline - flat).
  const int Jc = grid_.coarse_rows, Kc = grid_.coarse_cols;
  const auto turn = [&](std::size_t a, std::size_t b, std::size_t c) {
    const Vec3 in = coarse_m[b] - coarse_m[a], out = coarse_m[c] - coarse_m[b];
    const double lengths = in.norm() * out.norm();
    return lengths > 0.0 ? std::acos(std::clamp(in.dot(out) / lengths, -1.0, 1.0)) : 0.0;
  };
  bool any = false;
  for (int jc = 0; jc < Jc; ++jc) {
    for (int kc = 0; kc < Kc; ++kc) {
      double sharpest = 0.0;
      if (kc > 0 && kc + 1 < Kc)
        sharpest = turn(grid_.coarse_index(jc, kc - 1), grid_.coarse_index(jc, kc),
                        grid_.coarse_index(jc, kc + 1));
      if (jc > 0 && jc + 1 < Jc)
        sharpest =
            std::max(sharpest, turn(grid_.coarse_index(jc - 1, kc), grid_.coarse_index(jc, kc),
                                    grid_.coarse_index(jc + 1, kc)));
      const double weight = std::clamp(2.0 - sharpest / fold_limit_rad_, 0.0, 1.0);
      fold_weight_[grid_.coarse_index(jc, kc)] = weight;
      any = any || weight < 1.0;
    }
  }
  if (!any) return;  // the spline everywhere, to the bit
  grid_.coarse_surface(lattice_, coarse_m, flat_);
  for (int j = 0; j < lattice_.rows; ++j) {
    for (int k = 0; k < lattice_.cols; ++k) {
      const auto [jc, kc, u, v] = grid_.place(j, k);
      const double weight = (1.0 - v) * ((1.0 - u) * fold_weight_[grid_.coarse_index(jc, kc)] +
                                         u * fold_weight_[grid_.coarse_index(jc, kc + 1)]) +
                            v * ((1.0 - u) * fold_weight_[grid_.coarse_index(jc + 1, kc)] +
                                 u * fold_weight_[grid_.coarse_index(jc + 1, kc + 1)]);
      if (weight >= 1.0) continue;
      const std::size_t i = lattice_.index(j, k);
      surface_[i] = flat_[i] + weight * (surface_[i] - flat_[i]);
    }
  }
}

void SmoothInfill::fill(std::span<const Vec3> coarse_m, std::span<Vec3> positions_m,
                        StageTimes* times) {
  assert(coarse_m.size() == grid_.coarse_count() && positions_m.size() == lattice_.node_count());
  if (coarser_)  // part of 3.4: the coarser levels' projections start this one's
    run_timed(times, stages_.projection,
              [&] { coarser_->fill(coarse_m, coarser_positions_, nullptr); });
  run_timed(times, stages_.surface, [&] {  // 3.1-3.2: the surface, kept for the level above and 3.5
    spline_.evaluate(coarse_m, surface_);
    if (fold_limit_rad_ > 0.0) follow_sharp_folds(coarse_m);
    std::copy(surface_.begin(), surface_.end(), positions_m.begin());
    if (coarser_) add_coarser_offsets(positions_m);
  });
  run_timed(times, stages_.bands, [&] { set_bands(coarse_m); });  // 3.3
  ProjectionReport projected;
  const auto relax = [&] {  // 3.4
    projected = projection_.project(positions_m, kProjectionTolerance, kMaxProjectionRounds,
                                    kStepsPerFiber);
  };
  // The crease lines' ridges, laid on before the last projection (the wrinkles'
  // re-lay would replace them): crease_ridges.hpp.
  const bool coarse_ridges = creases_ && creases_->any();
  const bool dense_ridges = dense_creases_ && dense_creases_->any();
  const bool ridges = coarse_ridges || dense_ridges;
  const auto add_ridges = [&] {
    run_timed(times, stages_.creases, [&] {
      if (coarse_ridges) {
        if (!wrinkles_) set_normals();  // else 3.5 has just set them
        const std::vector<double>& offsets = creases_->offsets(coarse_m, surface_, normals_);
        for (std::size_t i = 0; i < positions_m.size(); ++i)
          if (!held_[i]) positions_m[i] += offsets[i] * normals_[i];  // the pole holds its edge
      }
      if (dense_ridges)
        add_dense_ridges(*dense_creases_, lattice_, positions_m, held_, dense_normals_,
                         dense_copy_);
    });
  };
  if (ridges && !wrinkles_) add_ridges();
  run_timed(times, stages_.projection, relax);
  if (smooths_)  // a level below the finest: its correction at its own scale, smoothed
    for (int cycle = 0; cycle < kSmoothingCycles; ++cycle) {
      run_timed(times, stages_.projection, [&] { smooth_correction(positions_m); });
      run_timed(times, stages_.projection, relax);
    }
  if (wrinkles_) {
    run_timed(times, stages_.wrinkles, [&] { add_wrinkles(positions_m); });
    if (ridges) add_ridges();
    run_timed(times, stages_.projection, relax);
    for (std::size_t i = 0; i < positions_m.size(); ++i)
      last_offset_[i] = (positions_m[i] - surface_[i]).dot(normals_[i]);
  }
  report_.converged = projected.converged;
  report_.residual = projected.converged ? 0.0 : projected.worst_excess;
  report_.iterations = projected.rounds;
  report_.coarse_offset_m = 0.0;
  for (int jc = 0; jc < grid_.coarse_rows; ++jc)
    for (int kc = 0; kc < grid_.coarse_cols; ++kc)
      report_.coarse_offset_m = std::max(
          report_.coarse_offset_m,
          (positions_m[grid_.dense_index(lattice_, jc, kc)] - coarse_m[grid_.coarse_index(jc, kc)])
              .norm());
}

}  // namespace flagsim::infill
