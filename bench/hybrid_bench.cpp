// The hybrid's infill on the default scene's own coarse trajectory: the coarse
// physics (9 x 13, spring-damper) runs once for the scene's 10 s and its nodes
// are recorded; every benchmark then replays them into an infill on a J x K
// lattice, one fill per frame, timed frame by frame. Counters: median_ms,
// p99_ms and max_ms of a frame's fill (frames 1..300), ns_per_node (median over
// J K), max_strain_pct over all frames, rounds_median (the smooth solver's
// projection rounds; the paper solver's 3.4 passes).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "flagsim/coarse_physics/cloth_model.hpp"
#include "flagsim/core/strain.hpp"
#include "flagsim/infill/infill_method.hpp"
#include "flagsim/infill/strain_limit.hpp"
#include "flagsim/scene/scene_parser.hpp"
#include "flagsim/sim/simulation.hpp"

namespace {

using flagsim::Lattice;
using flagsim::Vec3;

// The default scene's coarse nodes, every frame: the scene in mass-spring
// mode on its coarse lattice is exactly the hybrid's coarse physics.
const std::vector<std::vector<Vec3>>& coarse_trajectory() {
  static const std::vector<std::vector<Vec3>> frames = [] {
    const std::vector<std::string> sets = {"scene.mode=\"mass-spring\"", "flag.fine=[9,13]"};
    const flagsim::Scene scene =
        flagsim::parse_scene(flagsim::default_scene_toml(), flagsim::kDefaultSceneName, sets);
    auto simulation = flagsim::sim::make_simulation(scene);
    std::vector<std::vector<Vec3>> recorded;
    for (int frame = 0; frame < scene.simulated_frames(); ++frame) {
      if (frame > 0) simulation->advance_frame(nullptr);
      const auto x = simulation->positions();
      recorded.emplace_back(x.begin(), x.end());
    }
    return recorded;
  }();
  return frames;
}

double percentile(std::vector<double> values, double p) {
  std::sort(values.begin(), values.end());
  return values[std::min(values.size() - 1,
                         std::size_t(std::lround(p * double(values.size() - 1))))];
}

// Args: solver (0 smooth, 1 paper), J, K, frames replayed (0: all).
void BM_InfillReplay(benchmark::State& bench) {
  const auto kind =
      bench.range(0) == 0 ? flagsim::InfillSolverKind::kSmooth : flagsim::InfillSolverKind::kPaper;
  const Lattice lattice =
      Lattice::rectangle(int(bench.range(1)), int(bench.range(2)), 1.5, 1.0, Vec3(0.0, 2.0, 0.0));
  const auto& trajectory = coarse_trajectory();
  const std::size_t frames =
      bench.range(3) > 0 ? std::min<std::size_t>(std::size_t(bench.range(3)), trajectory.size())
                         : trajectory.size();
  flagsim::infill::InfillOptions options;
  options.solver = kind;
  options.relax_sweeps = 8000;  // the hybrid's default cap for the paper solver
  // The paper solver needs slack: the hybrid hands it coarse nodes pulled in
  // to 99% of their links' rest length (its coarse_slack stage), untimed here.
  std::vector<std::vector<Vec3>> coarse = trajectory;
  if (kind == flagsim::InfillSolverKind::kPaper) {
    const Lattice coarse_lattice = Lattice::rectangle(9, 13, 1.5, 1.0, Vec3(0.0, 2.0, 0.0));
    const auto pinned = flagsim::physics::pinned_nodes(coarse_lattice, flagsim::PinSet::kLeft);
    for (std::vector<Vec3>& nodes : coarse)
      flagsim::infill::limit_stretch(coarse_lattice, pinned, nodes, -0.01, 100);
  }
  std::vector<double> ms, rounds;
  double max_strain = 0.0;
  for (auto _ : bench) {
    auto infill = flagsim::infill::make_infill(
        lattice, flagsim::infill::CellGrid::of(lattice, 9, 13), options);
    infill->hold(flagsim::physics::pinned_nodes(lattice, flagsim::PinSet::kLeft));
    std::vector<Vec3> dense = lattice.rest_positions();
    infill->fill(coarse[0], dense, nullptr);
    ms.clear();
    rounds.clear();
    for (std::size_t t = 1; t < frames; ++t) {
      const auto start = std::chrono::steady_clock::now();
      infill->fill(coarse[t], dense, nullptr);
      ms.push_back(
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count());
      rounds.push_back(infill->last_report().iterations);
      max_strain = std::max(max_strain, flagsim::link_strain(lattice, dense).max);
    }
  }
  const double median = percentile(ms, 0.5);
  bench.counters["median_ms"] = median;
  bench.counters["p99_ms"] = percentile(ms, 0.99);
  bench.counters["max_ms"] = percentile(ms, 1.0);
  bench.counters["ns_per_node"] = 1e6 * median / double(lattice.node_count());
  bench.counters["max_strain_pct"] = 100.0 * max_strain;
  bench.counters["rounds_median"] = percentile(rounds, 0.5);
}

}  // namespace

// The smooth infill over the whole 10 s at every lattice the issue names.
BENCHMARK(BM_InfillReplay)
    ->ArgNames({"paper", "J", "K", "frames"})
    ->Args({0, 33, 49, 0})
    ->Args({0, 65, 97, 0})
    ->Args({0, 129, 193, 0})
    ->Args({0, 257, 385, 0})
    ->Args({0, 513, 769, 91})  // the first 3 s: a frame takes ~0.1 s at this size
    ->Iterations(1)
    ->Unit(benchmark::kSecond);
// The paper solver, side by side, on the first 2 s (it takes ~0.5 s a frame at 129 x 193).
BENCHMARK(BM_InfillReplay)
    ->ArgNames({"paper", "J", "K", "frames"})
    ->Args({1, 33, 49, 61})
    ->Args({1, 129, 193, 61})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

BENCHMARK_MAIN();
