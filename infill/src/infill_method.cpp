#include "flagsim/infill/infill_method.hpp"

#include "flagsim/infill/paper/infill_solver.hpp"
#include "flagsim/infill/smooth/smooth_infill.hpp"

namespace flagsim::infill {

std::unique_ptr<InfillMethod> make_infill(const Lattice& fine, const CellGrid& grid,
                                          const InfillOptions& options) {
  if (options.solver == InfillSolverKind::kPaper)
    return std::make_unique<InfillSolver>(fine, grid, options.relax_sweeps, options.wrinkles,
                                          options.wrinkle_rounds, options.creases);
  return std::make_unique<SmoothInfill>(fine, grid, options.wrinkles, options.creases,
                                        options.fold_limit_rad);
}

}  // namespace flagsim::infill
