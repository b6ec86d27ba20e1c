#pragma once
// Step 3.4 of the smooth infill: every row and every column of the flag, as a
// whole fiber, brought back to its rest spacing by Gauss-Newton steps on its
// link constraints (Goldenthal et al. 2007's fast projection, one fiber at a
// time), rows then columns, until no link is outside its band.
//
// Why per fiber: point-wise projection (3.4 of the paper solver) moves a node
// toward its four neighbours; the error of a fiber that is too long as a whole
// then leaves it only by diffusion, so the worst link falls about as
// 1/passes. A chain's link constraints couple only neighbours, so the
// Gauss-Newton system along a fiber is tridiagonal and solved exactly in
// O(links): one step fixes the fiber's length wherever along it the excess
// sits. Rows and columns disturb each other only through shear, which the
// 4-neighbour net does not resist (a fishnet drapes over a sphere), and that
// changes the other family's lengths to second order: the alternation
// converges in 3-5 rounds on the default scene.
//
// Bands: a link within [lower, upper] x S keeps its present length in a step
// (its linearised constraint holds it), so a correction travels along the
// whole fiber as along an inextensible thread; a link outside is pulled to the
// nearer bound. (Constraining only the links outside and a few beside them
// keeps corrections local but needed 2-3x the rounds: measured, slower.)
// Nodes with inverse mass 0 do not move (the pinned ones); every other node
// weighs the same, coarse counterparts included: weighting them down splits
// each fiber into per-cell chains again and puts the kinks back on the coarse
// lines (median turning ratio 3.8x at a tenth of the weight, 8.5x held).
//
// Not over-relaxed: scaling each step by 1.4 from the second round on cut the
// default scene's worst frame from 40 rounds to 20 at 129 x 193, but at
// 257 x 385 it raised the 99th-percentile frame from 62 to 288 ms, and at
// 513 x 769 frames stopped converging at all.
//
// Under-relaxed when the alternation stops making progress: each family's
// Gauss-Newton steps are exact for its own fibers, but a step of the rows can
// undo the columns (and back) where the two families are coupled (through a
// normal move, which changes both). Usually that coupling is second order and
// each round leaves fewer fibers out of their band; where it is not, the
// rounds can feed each other: the default scene's frame 32 at 513 x 769 went
// from a worst link 0.2% outside its band after the first round to 10% after
// eight, and never converged in 400 rounds (4.7% strain left in the output).
// So from the third round on, once a round leaves more fibers outside their
// bands than the round before, every later step of that projection is scaled
// by kUnderRelaxation. Measured on the default scene's first 91 frames at
// 513 x 769: every frame converges (at most 153 rounds; before, frame 32 did
// not in 400, and the next worst took 72 and 70), 124 ms a frame on average
// against 171. Lowering the factor again at each further rise (0.7, 0.49, ...
// down to 0.25) converged too but took 228 rounds in the worst frame; raising it
// back while the count falls, 323. A frame whose count keeps falling is not
// touched: of the default scene's 301 frames at 129 x 193, 5 change, by at
// most 0.12 mm.
//
// Speed: fibers that need a step are solved kLanes at a time, side by side
// (structure of arrays), so the serial recurrences of the tridiagonal solve
// overlap and the arithmetic vectorises across fibers.
#include <cstdint>
#include <span>
#include <vector>

#include "flagsim/core/lattice.hpp"

namespace flagsim::infill {

/// Allowed relative length of a link: [lower, upper] x rest spacing.
struct LinkBand {
  double lower = 1.0;
  double upper = 1.0;
};

/// How a projection ended.
struct ProjectionReport {
  int rounds = 0;       ///< row-then-column rounds made
  int fiber_steps = 0;  ///< Gauss-Newton steps over all fibers
  /// Fraction of each Gauss-Newton step taken in the last round (1: full
  /// steps; less once the rounds stopped making progress, see kUnderRelaxation).
  double relaxation = 1.0;
  /// Largest relative distance of a link outside its band, after; measured
  /// only when not converged (0 otherwise: every link is within tolerance).
  double worst_excess = 0.0;
  bool converged = false;  ///< worst_excess <= the tolerance
};

/// Levenberg-Marquardt damping added to the tridiagonal system's diagonal
/// (whose entries are 1 or 2): keeps it regular where a straight fiber held
/// at both ends makes it singular, and moves a converging step by ~1e-9.
inline constexpr double kDamping = 1e-9;
/// Largest motion of a node in one Gauss-Newton step, as a fraction of the
/// fiber's rest length (a fiber 10% too long moves its free end by 10%).
inline constexpr double kMaxStep = 0.1;

/// Fraction of each step taken once a round has left more fibers outside their
/// bands than the round before (see the header).
inline constexpr double kUnderRelaxation = 0.7;

/// Fibers solved side by side: two vectors of four.
inline constexpr int kLanes = 8;

class FiberProjection {
 public:
  /// @param fine  the dense lattice (its rest spacings); no node held
  explicit FiberProjection(const Lattice& fine);

  /// @param held  [J*K], 1 for nodes that must not move (replaces any earlier)
  void hold(std::span<const std::uint8_t> held);

  /// The band of each link, relative to its rest spacing.
  LinkField<LinkBand>& bands() { return bands_; }
  void set_uniform_band(double band);

  /// Rounds of rows-then-columns until every link is within its band to
  /// `tolerance` (relative), at most `max_rounds`; each fiber takes up to
  /// `steps_per_fiber` Gauss-Newton steps per round.
  /// @param positions_m  [J*K] row-major, m; moved in place
  ProjectionReport project(std::span<Vec3> positions_m, double tolerance, int max_rounds,
                           int steps_per_fiber);

  /// Largest relative distance of any link outside its band (0: all inside).
  double worst_excess(std::span<const Vec3> positions_m) const;

 private:
  /// One family (rows or columns): a round over its fibers, each with a link
  /// outside its band by more than the tolerance solved (with `check` false:
  /// every fiber, unchecked). Returns whether any fiber made a step.
  /// `relaxation` scales every step; `fibers_outside` gets how many fibers
  /// were found outside their bands (all of them when not checked).
  bool project_family(bool rows, std::span<Vec3> positions_m, double tolerance, int steps,
                      double relaxation, int* steps_made, int* fibers_outside, bool check);
  /// Gauss-Newton steps on the kLanes fibers gathered in the lane buffers, the
  /// first `distinct` of them counted into steps_made (the rest repeat the last).
  void step_lanes(int links, int distinct, double rest_m, double tolerance, int steps,
                  double relaxation, int* steps_made);

  Lattice lattice_;
  std::vector<double> inverse_mass_;  ///< [J*K]
  LinkField<LinkBand> bands_;
  LinkField<std::uint8_t> fixed_;         ///< links with both ends held
  std::vector<int> active_;               ///< fibers of the family being worked on that need a step
  std::vector<std::uint8_t> fiber_flag_;  ///< each fiber: a link out of bounds, in the check
  /// Per family (rows, columns): the fibers its last pass solved, ascending.
  std::vector<int> solved_[2];
  std::vector<std::uint8_t> dirty_;  ///< the check's link positions the other family touched
  std::vector<int> dirty_list_;      ///< the same as a list
  std::vector<double> row_low2_, row_high2_, col_low2_, col_high2_;  ///< bounds with tolerance, m^2
  // Lane buffers, [node or link][lane]: positions, inverse masses, bands, link
  // lengths and directions, the tridiagonal system and the step.
  std::vector<double> x_, y_, z_, w_, lower_, upper_, length_, nx_, ny_, nz_, diag_, off_, rhs_,
      dx_, dy_, dz_;
};

}  // namespace flagsim::infill
