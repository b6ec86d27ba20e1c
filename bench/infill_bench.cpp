// Cost of the infill (steps 3.1-3.4) from a 9 x 13 coarse lattice, on fine
// lattices 33x49 to 513x769, for a frame of a cloth being rolled onto a
// cylinder (a length-keeping motion, so the 1% strain bound can hold). The
// counters ms_infill_3.1 ... ms_infill_3.5 split a frame by step.
#include <benchmark/benchmark.h>

#include <cmath>
#include <optional>
#include <vector>

#include "flagsim/core/strain.hpp"
#include "flagsim/infill/paper/infill_solver.hpp"

namespace {

using flagsim::Lattice;
using flagsim::Vec3;
using flagsim::infill::CellGrid;
using flagsim::infill::InfillSolver;

Vec3 rolled(const Vec3& rest, double kappa) {
  return Vec3(std::sin(kappa * rest.x()) / kappa, rest.y(),
              (1.0 - std::cos(kappa * rest.x())) / kappa);
}

void infill_frame(benchmark::State& bench, std::optional<flagsim::infill::WrinkleParams> wrinkles) {
  const Lattice lattice =
      Lattice::rectangle(int(bench.range(0)), int(bench.range(1)), 1.5, 1.0, Vec3::Zero());
  const CellGrid grid = CellGrid::of(lattice, 9, 13);
  InfillSolver solver(lattice, grid, 100, wrinkles, 2);
  const std::vector<Vec3> rest = lattice.rest_positions();
  std::vector<Vec3> dense = rest, coarse(grid.coarse_count());
  auto coarse_at = [&](double kappa) {
    for (int jc = 0; jc < grid.coarse_rows; ++jc)
      for (int kc = 0; kc < grid.coarse_cols; ++kc)
        coarse[grid.coarse_index(jc, kc)] = rolled(rest[grid.dense_index(lattice, jc, kc)], kappa);
  };
  // Warm up: roll to kappa = 1 / m in 20 frames, then time one more frame each iteration
  // (alternating between two curvatures, so every frame has work to do).
  for (int f = 1; f <= 20; ++f) {
    coarse_at(0.05 * f);
    solver.fill(coarse, dense, nullptr);
  }
  int frame = 0;
  int sweeps = 0;
  flagsim::StageTimes times;  // each step's share, reported as counters
  solver.register_stages(times);
  for (auto _ : bench) {
    coarse_at(frame++ % 2 == 0 ? 1.05 : 1.0);
    solver.fill(coarse, dense, &times);
    sweeps += solver.last_relax_sweeps();
    benchmark::DoNotOptimize(dense.data());
  }
  bench.counters["ns_per_node"] = benchmark::Counter(
      double(lattice.node_count()) * 1e-9,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  bench.counters["relax_sweeps"] = double(sweeps) / double(bench.iterations());
  bench.counters["max_strain_pct"] = 100.0 * flagsim::link_strain(lattice, dense).max;
  for (std::size_t s = 0; s < times.names().size(); ++s)  // "ms_infill_3.4": per frame
    bench.counters["ms_" + times.names()[s]] =
        1e3 * times.seconds()[s] / double(bench.iterations());
}

void BM_InfillFrame(benchmark::State& bench) {
  infill_frame(bench, std::nullopt);
}

// With step 3.5 (r = 1 mm, E_f = 1 GPa, k' = 1 J/m^3, two 3.5/3.4 rounds).
void BM_InfillFrameWrinkles(benchmark::State& bench) {
  flagsim::infill::WrinkleParams params;
  params.k_r4 = flagsim::infill::bending_constant_k_r4(1e9, 1e-3);
  infill_frame(bench, params);
}

}  // namespace

// A fixed number of frames: the relaxation's work depends on the state the
// frames carry on, so a time-based iteration count would change the figure.
BENCHMARK(BM_InfillFrame)
    ->Args({33, 49})
    ->Args({65, 97})
    ->Args({129, 193})
    ->Args({257, 385})
    ->Args({513, 769})
    ->Iterations(100)
    ->Repetitions(3)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_InfillFrameWrinkles)
    ->Args({33, 49})
    ->Args({129, 193})
    ->Iterations(100)
    ->Repetitions(3)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
