#pragma once
// The points of `flag-sim sweep`: its comma-separated lists (--coarse,
// --backend, --substeps, --infill, --relax) parsed and crossed into runs.
#include <string>
#include <vector>

#include "sweep_command.hpp"

namespace flagsim::app {

/// One run of a sweep: a label for the tables and the scene keys that make it.
struct SweepPoint {
  std::string label;
  std::vector<std::string> sets;  ///< what makes this point: mode, coarse, substeps, relax
};

/// Point 0: the mass-spring reference; then the other full-lattice references
/// of --references (bullet, implicit, xpbd; default none); then the hybrid grid, coarse lattice
/// slowest, then backend, pole radius, substeps, infill solver, relaxation fastest (the paper
/// solver's cap only: the smooth infill gets one point). An empty list keeps the scene's own value.
/// Throws UserError naming the flag and the item it cannot read; --coarse is required.
std::vector<SweepPoint> sweep_grid(const SweepOptions& o);

}  // namespace flagsim::app
