#pragma once
// The paper's infill (section 3): from the new positions of the coarse nodes
// and the previous dense lattice, the new dense lattice.
//
// One deformation step runs, in order:
//  3.1 boundary: every cell edge (the dense nodes between two neighbouring
//      coarse nodes) placed from its ends (boundary.hpp). Edges shared by two
//      cells are computed once: the lattice is seamless.
//  3.2 initial move of each cell's interior, in the cell's co-moving frame:
//      the rigid motion that best carries the cell's edges moves its previous
//      interior, then the rest of the motions of a node's row ends and column
//      ends (on the cell's edges), interpolated and weighted by end_weight(),
//      averaged, is added.
//  3.3 length search on every row, then every column, of every cell.
//  3.4 relaxation of the whole lattice with the coarse nodes held.
//  3.5 (only when given WrinkleParams) re-move by the bending feature on every
//      cell row, then column (wrinkles.hpp), then 3.4 again; `rounds` times.
// Big motions are cut (3.1): if a coarse node moves more than kMaxStepFraction
// of the smaller cell side, the motion is split into equal deformation steps,
// each run in full (at most kMaxCutSteps). The state carried between frames is the dense lattice
// itself: every fill starts from the previous one, which is what lets a shape
// persist (property 2). Work buffers are kept: fill() does not allocate.
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "flagsim/core/lattice.hpp"
#include "flagsim/core/stage_times.hpp"
#include "flagsim/infill/cell_grid.hpp"
#include "flagsim/infill/fiber.hpp"
#include "flagsim/infill/infill_method.hpp"
#include "flagsim/infill/paper/length_search.hpp"
#include "flagsim/infill/wrinkles.hpp"

namespace flagsim::infill {

/// Largest coarse-node motion per deformation step, as a fraction of the smaller
/// cell side: a node that crosses a whole cell in one frame is a "big motion".
/// (At a quarter cell, a flag frame took 2-3 deformation steps, each a full
/// 3.1-3.4, for no gain in strain.)
inline constexpr double kMaxStepFraction = 1.0;
/// At most this many deformation steps a frame, whatever the motion: a coarse
/// node that jumps across 64 cells at once gets steps longer than a cell (and
/// the frame reports itself unconverged) rather than a frame that never ends.
inline constexpr int kMaxCutSteps = 64;
/// 3.3 runs on a fiber whose length is off its rest length by more than this
/// (relative). Small on purpose: the weighted move of 3.2 leaves the middle of
/// every fiber behind a little each frame, and at 0.5% that lag piled up over
/// frames (sheared.toml: 4.5% strain; 0.53% at 0.01%).
inline constexpr double kLengthTolerance = 0.0001;
/// 3.4 stops once every link is within this of its rest length (relative):
/// half the 1% strain bound. (At 0.1% the relaxation ran to its sweep cap on
/// every frame, 30x the time, while the worst link sat at 0.08-0.1%.)
inline constexpr double kRelaxTolerance = 0.005;

/// The paper solver: [infill] solver = "paper".
class InfillSolver final : public InfillMethod {
 public:
  /// @param relax_sweeps  most passes of 3.4 per deformation step ([infill] relax_iterations)
  /// @param wrinkles      step 3.5, or nullopt to leave it out (no [wrinkles] table)
  /// @param rounds        3.5/3.4 alternations per deformation step
  /// @param creases       with [creases] in infill mode: the dense lattice's own
  ///                      creases drawn as ridges (set_dense_creases), or nullopt
  InfillSolver(const Lattice& fine, const CellGrid& grid, int relax_sweeps,
               std::optional<WrinkleParams> wrinkles = std::nullopt, int rounds = 2,
               std::optional<CreaseRidgeParams> creases = std::nullopt);

  /// Holds these dense nodes ([J*K], 1 = held) in 3.4 as well as the coarse
  /// ones: the pinned nodes of a physics-driven cloth, which lie on coarse
  /// lines between pinned coarse nodes and are placed there by 3.1.
  void hold(std::span<const std::uint8_t> nodes) override;

  /// Registers the timing columns "infill_3.1" ... "infill_3.4" (and "infill_3.5").
  void register_stages(StageTimes& times) override;

  /// @param coarse_m     new coarse node positions [Jc*Kc], m
  /// @param positions_m  in: the previous dense lattice [J*K]; out: the new one
  void fill(std::span<const Vec3> coarse_m, std::span<Vec3> positions_m,
            StageTimes* times) override;
  FillReport last_report() const override { return report_; }

  int last_deformation_steps() const { return last_steps_; }
  int last_relax_sweeps() const { return last_sweeps_; }
  const CellGrid& grid() const override { return grid_; }
  /// Infill mode's creases (crease_ridges.hpp: add_dense_ridges), laid on after
  /// the last deformation step and relaxed once more (3.4). The lattice carried
  /// to the next fill is the one before them, so they do not pile up frame on
  /// frame: memory() holds it (1 then [J*K] x 3 positions, m; 0 first when
  /// none was laid), empty without [creases].
  void set_dense_creases(std::span<const double> dense_rest_rad) override;
  std::vector<double> memory() const override;
  void set_memory(std::span<const double> memory) override;

 private:
  void deform(std::span<const Vec3> coarse_target_m, std::span<Vec3> positions_m,
              StageTimes* times);
  /// The cloth's normal over the cell whose top-left dense node is `corner`.
  Vec3 cell_normal(std::size_t corner, std::span<const Vec3> positions_m) const;
  /// Dense index of the top-left node of the cell holding fiber node `node`.
  std::size_t cell_corner_of(std::size_t node) const;
  void rewrinkle(std::span<Vec3> positions_m);

  Lattice lattice_;
  CellGrid grid_;
  int relax_sweeps_;
  std::optional<WrinkleParams> wrinkles_;
  int rounds_;
  std::optional<CreaseRidgeParams> crease_params_;
  std::optional<CreaseRidges> dense_creases_;
  std::vector<Vec3> unridged_;  ///< [J*K] the last fill before its ridges
  bool ridged_ = false;         ///< whether the last fill laid ridges on unridged_
  std::vector<Vec3> dense_normals_, dense_copy_;  ///< add_dense_ridges' scratch
  /// A cell edge, with the dense indices of the coarse nodes one cell before
  /// its start and one cell after its end on the same coarse line (-1: none).
  struct Edge {
    Fiber fiber;
    std::ptrdiff_t before = -1;
    std::ptrdiff_t after = -1;
    std::array<std::ptrdiff_t, 2> cells = {-1, -1};  ///< top-left dense node of the cells beside it
  };

  std::vector<Edge> edges_;         ///< every cell edge, once
  std::vector<Fiber> cell_rows_;    ///< interior rows of every cell, ends on the cell's side edges
  std::vector<Fiber> cell_cols_;    ///< interior columns of every cell
  std::vector<std::uint8_t> held_;  ///< coarse nodes and pinned ones
  std::vector<std::size_t> coarse_dense_;  ///< dense index of each coarse node
  std::vector<Vec3> previous_;             ///< the lattice before the current deformation step
  LengthSearchScratch length_scratch_;     ///< step 3.3's working space
  std::vector<Vec3> coarse_start_, coarse_step_;
  /// Columns of the frame's StageTimes, one per step (-1: not timed).
  struct Stages {
    int boundary = -1, initial_move = -1, length = -1, relax = -1, wrinkles = -1, creases = -1;
  } stages_;
  int last_steps_ = 0, last_sweeps_ = 0;
  bool capped_ = false;  ///< some 3.4 call of the last fill() ran to its cap
  FillReport report_;
};

}  // namespace flagsim::infill
