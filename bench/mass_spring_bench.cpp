// Cost of the spring-damper baseline on the default scene's cloth: one whole
// substep, and each force term alone, at the lattices of the README's table;
// and one XPBD frame of 320 substeps (its cost per substep in the counters).
// Per-node figures are in the counters (ns per node = 1e9 / nodes_per_second).
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "flagsim/coarse_physics/spring_damper.hpp"
#include "flagsim/coarse_physics/xpbd.hpp"
#include "flagsim/scene/scene_parser.hpp"

namespace {

using flagsim::Scene;
using flagsim::Vec3;
using flagsim::physics::ClothState;
using flagsim::physics::SpringDamperSolver;

Scene default_scene_at(int rows, int cols, std::vector<std::string> sets = {}) {
  sets.push_back("flag.fine=[" + std::to_string(rows) + "," + std::to_string(cols) + "]");
  return flagsim::parse_scene(flagsim::default_scene_toml(), flagsim::kDefaultSceneName, sets);
}

// A state a few frames into the run, so that the wind and springs are loaded.
ClothState warmed_up(SpringDamperSolver& solver) {
  ClothState state = solver.initial_state();
  for (int f = 0; f < 3; ++f) solver.advance_frame(state, nullptr);
  return state;
}

void BM_Substep(benchmark::State& bench) {
  const Scene scene = default_scene_at(int(bench.range(0)), int(bench.range(1)));
  SpringDamperSolver solver(scene);
  ClothState state = warmed_up(solver);
  for (auto _ : bench) {
    solver.step(state, solver.substep_s(), nullptr);
    benchmark::DoNotOptimize(state.x_m.data());
  }
  const double nodes = double(solver.model().lattice.node_count());
  bench.counters["nodes"] = nodes;
  bench.counters["substeps_per_frame"] = solver.substeps_per_frame();
  // Output frames simulated per second of CPU: 1 / (substeps * time per substep).
  bench.counters["frames_per_s"] = benchmark::Counter(
      1.0 / solver.substeps_per_frame(), benchmark::Counter::kIsIterationInvariantRate);
  bench.counters["nodes_per_second"] =
      benchmark::Counter(nodes, benchmark::Counter::kIsIterationInvariantRate);
}

void BM_ForceTerm(benchmark::State& bench) {
  const Scene scene = default_scene_at(int(bench.range(0)), int(bench.range(1)));
  SpringDamperSolver solver(scene);
  const ClothState state = warmed_up(solver);
  const auto& term = *solver.terms().at(std::size_t(bench.range(2)));
  bench.SetLabel(std::string(term.name()));
  std::vector<Vec3> forces(state.x_m.size(), Vec3::Zero());
  for (auto _ : bench) {
    term.add_forces(state.x_m, state.v_m_s, forces);
    benchmark::DoNotOptimize(forces.data());
  }
  bench.counters["nodes_per_second"] =
      benchmark::Counter(double(state.x_m.size()), benchmark::Counter::kIsIterationInvariantRate);
}

void BM_XpbdFrame(benchmark::State& bench) {
  const Scene scene = default_scene_at(int(bench.range(0)), int(bench.range(1)),
                                       {"scene.mode=\"xpbd\"", "solver.substeps=320"});
  flagsim::physics::Xpbd solver(scene);
  for (int f = 0; f < 3; ++f) solver.advance_frame(nullptr);  // loaded by the wind
  for (auto _ : bench) {
    solver.advance_frame(nullptr);
    benchmark::DoNotOptimize(solver.state().x_m.data());
  }
  bench.counters["substeps"] = benchmark::Counter(
      solver.substeps_per_frame(),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

}  // namespace

BENCHMARK(BM_XpbdFrame)
    ->Args({33, 49})
    ->Args({65, 97})
    ->Args({129, 193})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Substep)
    ->Args({33, 49})
    ->Args({65, 97})
    ->Args({129, 193})
    ->Unit(benchmark::kMicrosecond);
// Terms of the default scene, in pipeline order: stretch, gravity, wind.
BENCHMARK(BM_ForceTerm)->ArgsProduct({{65}, {97}, {0, 1, 2}})->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
