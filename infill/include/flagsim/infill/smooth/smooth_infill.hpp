#pragma once
// The smooth infill: the paper's deformation step on whole fibers, filling the
// dense lattice from the coarse nodes of a physics-driven cloth.
//
// One step runs, every frame, from the coarse nodes alone:
//  3.1 boundary: the coarse nodes (the physics' own, no slack added) define
//      one smooth mean surface over the cloth (spline_surface.hpp); every
//      dense node, on the coarse lines and between them, starts on it.
//      With fold_limit_rad (the hybrid's [contact]), where the coarse cloth
//      folds sharply the surface is drawn toward the coarse triangles: the
//      spline overshoots a hairpin (on pole_wrap, a coarse column folded back
//      on the one before it, the spline alone crosses itself in 7 of 121
//      frames), and what follows a hairpin closely enough keeps the sides of
//      the coarse layers the physics keeps apart.
//  3.2 initial move: the paper interpolates the motion of a fiber's ends to
//      its inside. The surface is linear in the coarse nodes, so the surface of
//      the new nodes is the old one moved by the interpolated motion: 3.2 and
//      3.1 are one evaluation. The previous frame's dense offsets from its
//      surface are not carried over: in world axes they fold up as the
//      flapping cloth turns by tens of degrees a frame (p99 strain 0.7% vs
//      0.00% after the same projection, prototype); even turned with the
//      surface's own frames they made the projection need 10-100 rounds a
//      frame instead of 3-5 (16.8 vs 4.2 ms). What persists between frames is
//      the surface itself, a smooth function of the coarse motion.
//  3.3 length: the paper moves a fiber toward its rest length; here 3.4 does
//      the moving exactly, and 3.3 sets what "its length" is: each link's
//      target T = (1 + clamp(stretch of the coarse links around it,
//      interpolated by Catmull-Rom cubics, 0, kStretchCap)) x S and its band
//      [1 - kBand, 1 + kBand] x T. A dense link is as long as the coarse
//      physics made the coarse links around it; where those are compressed it
//      keeps its rest length (a compressed membrane wrinkles, it does not
//      shorten its fibers: the paper's property 1), and the length the
//      surface lacks there becomes relief. No slack is invented. The bands
//      so come from the material's stretch through the physics it drives (a
//      stiffer [flag] stretch: less coarse stretch, tighter bands; issue 30);
//      kStretchCap is not a second stretch modulus but the paper's 1% bound
//      on a yarn's extension (property 1), which no fabric setting moves.
//  3.4 relaxation: whole-fiber Gauss-Newton projection (fiber_projection.hpp)
//      until every link is within its band; only pinned nodes are held. Under
//      cells of 16 links or more, on every level below the finest its
//      correction is smoothed and projected again (kSmoothingCycles, below),
//      so that it hands no crease up to the next finer level.
//  3.5 (with [wrinkles]) re-move by the bending feature, on whole fibers:
//      each row and column's slack on the mean surface, dL = L - c with c the
//      fiber's length along the surface (the paper's chord |P_j1 - P_jK| of
//      eq. (12), read on the surface the wrinkles ride on), picks its wave
//      count by the balance E = e of eqs. (1), (11)-(13) (half_wave_count in
//      wrinkles.hpp: m half-waves over the whole fiber, so a wave spans as many
//      cells as the fiber's thickness asks), and the wave y = A sin(m pi s / c)
//      with the amplitude that gives the fiber back its rest length is laid
//      along the surface's normal; rows' and columns' waves add, and their sum
//      replaces each node's offset along the normal (a re-lay, as in the paper
//      solver: the same coarse nodes give the same waves). Each fiber
//      keeps the side its wave was on the frame before (the sign that best
//      matches the last frame's offsets from its surface: property 2). Then
//      3.4 again.
//
// Choice (issue 12, requirement 1): the dense lattice follows the coarse
// nodes as its mean surface, not through them exactly. Holding each coarse
// node's counterpart puts every fiber's length error on the cells around it
// and the kink on the coarse node (see fiber_projection.hpp); letting it move
// with its fiber leaves no mark. The counterparts then sit where the lengths
// put them: their largest distance from the coarse nodes is reported every
// frame (/stats/coarse_offset, m); /coarse/positions holds the physics' nodes.
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "flagsim/infill/crease_ridges.hpp"
#include "flagsim/infill/infill_method.hpp"
#include "flagsim/infill/smooth/fiber_projection.hpp"
#include "flagsim/infill/smooth/spline_surface.hpp"
#include "flagsim/infill/wrinkles.hpp"

namespace flagsim::infill {

/// Half-width of every link's band around its target length (relative). With
/// kProjectionTolerance a converged link is within 0.1% of its target (issue
/// 34). It was 0.005 around the rest length (the paper solver's 1%): the
/// projection stopped as soon as a link entered the band, so a third of the
/// links sat at its edges and the dense strain was the tolerance's, not the
/// physics' (default scene, frames after 1 s: 28% of row links within 0.02% of
/// +-0.5%, now 0.2%; p99 |dense - coarse strain| 0.69% -> 0.24%, by
/// ../shared/tools/cloth_checks.py mottle).
inline constexpr double kBand = 0.0005;
/// Most stretch a dense link follows from the coarse physics (relative): the
/// 1% bound on fibers (property 1), less kProjectionTolerance and a margin. A coarse link the
/// physics stretched more (the 9 x 13 default reaches 1.3% in gusts) gets dense links at this
/// length, and its nodes' dense counterparts move closer together.
inline constexpr double kStretchCap = 0.009;
/// The projection stops when no link is outside its band by more than this.
inline constexpr double kProjectionTolerance = 5e-4;
/// Rows-then-columns rounds at most per frame: the default scene needs 3 in
/// the median frame, ~40 where the coarse cloth folds back on itself (at
/// 513 x 769 a few fold frames need more than 100, one of 91 more than 400).
/// Past it the frame is reported as not converged.
inline constexpr int kMaxProjectionRounds = 400;
/// A coarser level is made while the cells of the halved lattice still have
/// at least this many links a side.
inline constexpr int kLevelStride = 4;
/// On every level below the finest (since 2026-12-08; before, the coarsest
/// only: the lattice without a coarser one, kLevelStride to 2 kLevelStride - 1
/// links a cell side), the projection's correction is low-passed and projected
/// again kSmoothingCycles times, with
/// kSmoothingPasses passes of a binomial filter each way (standard deviation
/// sqrt(passes / 2) = 1.4 links, a third of a cell of 4). Why: a Gauss-Newton
/// step changes a link's length by a normal move only as much as the fiber
/// turns there (to first order), so the projection puts its normal corrections
/// where the fiber already bends most: on the nodes where the coarse physics
/// bends, the coarse lines; the correction has a crease there, and the finer
/// levels inherit it. Smoothed and projected again, it spreads over the cell.
/// Measured (frames after 1 s with the median turning on coarse lines over
/// 1.3x that between, worst frame; default / cells of 8 / taller / wider than
/// tall): without, 1 (1.36) / 0 (1.14) / 0 (1.22) / 1 (1.35); 4 passes, 3
/// cycles, 0 (1.19) / 0 (1.14) / 0 (1.20) / 0 (1.29). 1-8 cycles and 2-8 passes
/// gave 1.13-1.25 on the default scene; the wide flag stays near 1.3 with any
/// (1.29-1.42: its surface alone, before any projection, gives 1.33 there).
/// Only where the output's cells have kSmoothedCellLinks links or more: with
/// shorter cells the crease the finer levels inherit stays under the 1.3 of
/// issue 12 unsmoothed, and the cycles would cost 4 projections of the
/// coarsest level, a quarter of the nodes under cells of 8 (65 x 97: 0.51 ->
/// 0.82 ms a frame). Measured (91 frames, 9 x 13 coarse unless said; worst
/// frame without / with): cells of 4 (33 x 49) 1.25 / 1.18, 8 (65 x 97) 1.14 /
/// 1.14, 8 (97 x 49 from 13 x 7) 1.22 / 1.20, 9 (73 x 109, no coarser level)
/// 1.14 / 1.16, 12 (97 x 145) 1.20 / 1.15, 14 (113 x 169) 1.20 / 1.14; but 16
/// (the default, 129 x 193) 1.34 / 1.19 and 18 (145 x 217) 1.27 / 1.14.
/// One cycle since 2026-12-06 (was 3; each cycle is a projection of the
/// coarsest level, about 0.1 ms a frame on the default scene). Measured on
/// today's physics (0.25 m air panels; worst-frame imprint, crease-line ratio
/// median / p90 by ../shared/tools/cloth_checks.py), 0 / 1 / 3 cycles: default
/// scene 10 s 1.17 / 1.15 / 1.14, crease lines 3.22 / 4.84, 3.15 / 4.63, 3.19 /
/// 4.64, relief and band-edge figures unchanged (2.02 / 2.05 mm taut, 2.1%);
/// cells of 18 (91 frames) 1.14 / 1.12 at 1 / 3 cycles, crease lines 3.59 / 5.16
/// against 3.35 / 4.68; the storm with wrinkles at 129 x 193 (6 s) 1.33 / 1.30,
/// crease lines 6.52 / 10.2 against 6.27 / 9.13. So the second and third cycles
/// buy nothing on the default scene and about a tenth of the crease-line ratio
/// on finer cells and in a storm, for 0.2 ms a frame.
/// Every level below the finest since 2026-12-08: each level's projection puts
/// its normal corrections where its fibers bend most and the level above
/// inherits them, so the coarsest level's smoothing alone left creases that the
/// intermediate levels made (default scene 10 s, crease lines median / p90 2.74
/// / 4.05 -> 2.60 / 3.84; gusts 2.82 / 3.82 -> 2.77 / 3.76; the storm at
/// 129 x 193 7.07 / 11.55 -> 6.83 / 9.97). At 513 x 769 the finest level's rows
/// and columns, which had undone each other for tens of rounds in a quarter of
/// the frames (from a start with those creases), converge in 3 rounds in the
/// median frame again (mean 17.6 -> 5.3 rounds over 301 frames). The finest
/// level does not smooth: it hands nothing on, and its cycle is a projection of
/// the whole output (one cycle there: 2.56 / 3.72 for +1.2 ms a frame). Cost at
/// 129 x 193: the 65 x 97 level's cycle, 0.2-0.3 ms a frame (docs/dense_surface.md).
inline constexpr int kSmoothedCellLinks = 16;
inline constexpr int kSmoothingPasses = 4;
inline constexpr int kSmoothingCycles = 1;
/// Gauss-Newton steps per fiber per round (a fiber that converges stops early).
inline constexpr int kStepsPerFiber = 4;

class SmoothInfill final : public InfillMethod {
 public:
  /// @param wrinkles  step 3.5, or nullopt to leave it out (no [wrinkles] table)
  /// @param creases   the coarse physics' creases drawn as ridges (crease_ridges.hpp;
  ///                   this level only: the coarser levels have none), or nullopt
  /// @param fold_limit_rad  where a coarse row or column turns by more than this
  ///                   at a coarse node, 3.1's surface is drawn toward the coarse
  ///                   triangles (follow_sharp_folds); 0: never
  SmoothInfill(const Lattice& fine, const CellGrid& grid,
               std::optional<WrinkleParams> wrinkles = std::nullopt,
               std::optional<CreaseRidgeParams> creases = std::nullopt,
               double fold_limit_rad = 0.0);

  void hold(std::span<const std::uint8_t> nodes) override;
  void register_stages(StageTimes& times) override;
  void fill(std::span<const Vec3> coarse_m, std::span<Vec3> positions_m,
            StageTimes* times) override;
  FillReport last_report() const override { return report_; }
  const CellGrid& grid() const override { return grid_; }
  std::vector<double> memory() const override;
  void set_memory(std::span<const double> memory) override;
  void set_creases(std::span<const double> coarse_rest_rad) override {
    if (creases_) creases_->set_rest(coarse_rest_rad);
  }
  void set_dense_creases(std::span<const double> dense_rest_rad) override;

 private:
  /// 3.3: every link's band from the coarse links it lies between.
  void set_bands(std::span<const Vec3> coarse_m);
  /// normals_: the surface's normal at every node.
  void set_normals();
  /// 3.5: each node's offset along the surface's normal set to the whole fibers' waves.
  void add_wrinkles(std::span<Vec3> positions_m);
  /// The coarser level's offsets from its surface, interpolated to this
  /// lattice (4-point subdivision, separable) and added to `positions_m`
  /// (this level's surface).
  void add_coarser_offsets(std::span<Vec3> positions_m);
  /// Part of 3.4 on the coarsest level: the offsets of `positions_m` from the
  /// surface low-passed (kSmoothingPasses), held nodes left where they are.
  void smooth_correction(std::span<Vec3> positions_m);

  Lattice lattice_;
  CellGrid grid_;
  SplineSurface spline_;
  std::vector<std::uint8_t> held_;
  FiberProjection projection_;
  std::vector<double> coarse_row_stretch_, coarse_col_stretch_;
  /// Cubic (Catmull-Rom) interpolation of samples: four samples and their
  /// weights (ends repeated), exact for linear data, C1 across the samples.
  struct Taps {
    int index[4] = {0, 0, 0, 0};
    double weight[4] = {1.0, 0.0, 0.0, 0.0};
  };
  static Taps taps_at(double x, int count);
  std::vector<Taps> row_link_taps_, col_node_taps_;  ///< 3.3's weights along the rows
  std::vector<double>
      along_;  ///< 3.3: the coarse stretch interpolated along coarse lines, work buffer

  /// Columns of the frame's StageTimes (-1: not timed): 3.1-3.2, 3.3, 3.4 (with
  /// the coarser levels' projections), 3.5.
  struct Stages {
    int surface = -1, bands = -1, projection = -1, wrinkles = -1, creases = -1;
  } stages_;
  std::optional<WrinkleParams> wrinkles_;
  std::optional<CreaseRidges> creases_;  ///< the crease lines' ridges ([creases])
  std::optional<CreaseRidgeParams> crease_params_;
  std::optional<CreaseRidges> dense_creases_;     ///< infill mode's, at dense resolution
  std::vector<Vec3> dense_normals_, dense_copy_;  ///< add_dense_ridges' scratch
  std::vector<Vec3> surface_;  ///< this frame's mean surface (3.1), read by 3.5 and the level above
  /// Where the coarse cloth folds sharply, the surface between its coarse
  /// nodes drawn toward the coarse triangles (see the constructor).
  void follow_sharp_folds(std::span<const Vec3> coarse_m);
  double fold_limit_rad_ = 0.0;
  std::vector<double> fold_weight_;  ///< [Jc*Kc] per coarse node: 1 spline, 0 coarse triangles
  std::vector<Vec3> flat_;           ///< [J*K] the coarse triangles at the dense nodes
  /// This level runs the kSmoothingCycles (set by the finest level for those below it).
  bool smooths_ = false;
  std::vector<Vec3> correction_, smoothed_;  ///< smooth_correction's work buffers
  std::vector<Vec3> normals_;                ///< 3.5 and the ridges: the surface's normals
  std::vector<double> last_offset_;          ///< 3.5: last frame's offset along its normal, m
  std::vector<double> wave_;                 ///< 3.5: one fiber's wave, work buffer
  FillReport report_;

  // The same infill on the lattice of every other dense row and column, when
  // that still has at least kLevelStride links per cell side: its converged
  // offsets from the surface start this level's projection.
  std::unique_ptr<SmoothInfill> coarser_;
  std::vector<Vec3> coarser_positions_;  ///< the coarser level's result
  std::vector<Vec3> coarser_offsets_;    ///< its offsets upsampled along the rows [half.rows x K]
};

}  // namespace flagsim::infill
