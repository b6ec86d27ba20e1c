// Cost of writing a frame to HDF5 (FrameWriter: float32 positions, stats,
// flush every 10 frames) per dense lattice. Writes under /tmp.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "flagsim/data/frame_writer.hpp"

namespace {

using flagsim::Lattice;
using flagsim::Vec3;

void BM_WriteFrame(benchmark::State& bench) {
  const Lattice lattice =
      Lattice::rectangle(int(bench.range(0)), int(bench.range(1)), 1.5, 1.0, Vec3::Zero());
  const std::string path = "/tmp/flagsim_output_bench_" + std::to_string(getpid()) + ".h5";
  flagsim::data::RunInfo info;
  info.mode = "mass-spring";
  info.stages = {"stretch", "output"};
  info.output_stage = 1;
  std::vector<Vec3> x = lattice.rest_positions();
  const std::vector<Vec3> v(x.size(), Vec3(0.1, 0.2, 0.3));
  const std::vector<float> strain(x.size(), 1e-3f);
  {
    flagsim::data::FrameWriter writer(path, lattice, info, 10);
    const std::vector<double> stage_seconds = {0.001, 0.0};
    int frame = 0;
    for (auto _ : bench) {
      x[0].z() = 1e-3 * frame;  // not the same bytes every frame
      writer.write_frame(frame / 30.0, {x, v, strain}, {0.01, 0.001, stage_seconds, 0.01, 1.0, {}});
      ++frame;
    }
    writer.finish({flagsim::RunState::kComplete, "all frames written"});
  }
  bench.SetBytesProcessed(std::int64_t(bench.iterations()) * std::int64_t(x.size() * 28));
  std::filesystem::remove(path);
  std::filesystem::remove(std::filesystem::path(path).replace_extension(".xdmf"));
}

}  // namespace

BENCHMARK(BM_WriteFrame)
    ->Args({33, 49})
    ->Args({129, 193})
    ->Args({257, 385})
    ->Iterations(300)
    ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
