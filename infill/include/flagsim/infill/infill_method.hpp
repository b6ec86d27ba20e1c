#pragma once
// The infill behind one small interface, so that a scene (and a sweep) can
// choose it: [infill] solver = "smooth" (smooth_infill.hpp) or "paper"
// (infill_solver.hpp).
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "flagsim/core/lattice.hpp"
#include "flagsim/core/stage_times.hpp"
#include "flagsim/infill/cell_grid.hpp"
#include "flagsim/infill/crease_ridges.hpp"
#include "flagsim/infill/wrinkles.hpp"
#include "flagsim/scene/scene.hpp"

namespace flagsim::infill {

/// What the last fill() did, for the per-frame statistics and the summary.
struct FillReport {
  /// Whether every link reached the solver's tolerance (paper: 3.4 stopped
  /// before its cap; smooth: the projection converged).
  bool converged = true;
  /// Largest relative link error left outside what the solver aimed for (0 when converged).
  double residual = 0.0;
  /// Iterations of the solver's 3.4 (paper: passes; smooth: row-then-column rounds).
  int iterations = 0;
  /// Largest distance of a coarse node's dense counterpart from the coarse node, m.
  double coarse_offset_m = 0.0;
};

/// The hybrid's [contact]: a coarse fiber turning by more than this at a
/// coarse node (57 degrees; fully past twice it) draws the smooth infill's
/// surface toward the coarse triangles there (SmoothInfill). The default
/// flag's flapping turns its 9 x 13 coarse fibers by 10-40 degrees.
inline constexpr double kContactFoldLimitRad = 1.0;

struct InfillOptions {
  InfillSolverKind solver = InfillSolverKind::kSmooth;
  int relax_sweeps = 1000;  ///< the paper solver's 3.4 cap
  std::optional<WrinkleParams> wrinkles;
  int wrinkle_rounds = 2;  ///< 3.5/3.4 alternations (paper solver)
  /// [creases]: the coarse physics' crease lines drawn as ridges (smooth solver),
  /// or in infill mode the dense lattice's own (both solvers)
  std::optional<CreaseRidgeParams> creases;
  /// Smooth solver: above this turning of a coarse fiber at a coarse node,
  /// rad, the mean surface is drawn toward the coarse triangles (SmoothInfill,
  /// fold_limit_rad); 0: never. The hybrid's [contact] sets it.
  double fold_limit_rad = 0.0;
};

class InfillMethod {
 public:
  virtual ~InfillMethod() = default;
  /// Holds these dense nodes ([J*K], 1 = held): the pinned nodes of the cloth.
  virtual void hold(std::span<const std::uint8_t> nodes) = 0;
  /// Registers the timing columns, "infill_3.1" ... in pipeline order.
  virtual void register_stages(StageTimes& times) = 0;
  /// @param coarse_m     new coarse node positions [Jc*Kc], m
  /// @param positions_m  in: the previous dense lattice [J*K]; out: the new one
  virtual void fill(std::span<const Vec3> coarse_m, std::span<Vec3> positions_m,
                    StageTimes* times) = 0;
  virtual FillReport last_report() const = 0;
  virtual const CellGrid& grid() const = 0;
  /// The coarse physics' crease rest angles (coarse bending triples'
  /// order), given before each fill with [creases]; a solver that draws no
  /// crease lines ignores them.
  virtual void set_creases(std::span<const double> /*coarse_rest_rad*/) {}
  /// The dense lattice's own crease rest angles (its bending triples' order:
  /// infill mode, where no physics holds them), given before each fill; a
  /// solver made without crease parameters ignores them.
  virtual void set_dense_creases(std::span<const double> /*dense_rest_rad*/) {}
  /// What a fill carries into the next besides the dense positions (the
  /// smooth solver's 3.5 offsets along the normals [J*K], m, with wrinkles);
  /// empty when nothing is. set_memory takes what memory() gave.
  virtual std::vector<double> memory() const { return {}; }
  virtual void set_memory(std::span<const double> /*memory*/) {}
};

std::unique_ptr<InfillMethod> make_infill(const Lattice& fine, const CellGrid& grid,
                                          const InfillOptions& options);

}  // namespace flagsim::infill
