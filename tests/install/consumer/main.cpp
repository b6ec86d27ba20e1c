// The embedded default scene at 17 x 25, FRAMES frames run through the
// installed library's frame loop (each checked): prints the middle row's
// fly-end node, m, with every digit; exit 3 if a frame diverged.
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "flagsim/scene/scene_parser.hpp"
#include "flagsim/sim/frame_runner.hpp"

int main(int argc, char** argv) {
  const int frames = argc > 1 ? std::atoi(argv[1]) : 5;
  const std::vector<std::string> overrides = {"flag.fine=[17,25]"};
  const flagsim::Scene scene =
      flagsim::parse_scene(flagsim::default_scene_toml(), flagsim::kDefaultSceneName, overrides);
  // Compiled once (checked, the cloth built); any number of simulations can share it.
  const auto model = flagsim::sim::Model::compile(scene);
  const auto simulation = flagsim::sim::make_simulation(model);
  const flagsim::sim::FrameRunResult ran =
      flagsim::sim::run_frames(*simulation, scene, 1, frames + 1, {});
  if (ran.end != flagsim::sim::FrameRunEnd::kComplete) {
    const std::string why =
        ran.divergence ? flagsim::describe(*ran.divergence, scene) : "stopped by a signal";
    std::fprintf(stderr, "frame %d: %s\n", ran.frame, why.c_str());
    return 3;
  }
  const flagsim::Lattice& lattice = simulation->lattice();
  const flagsim::Vec3 end =
      simulation->positions()[lattice.index(lattice.rows / 2, lattice.cols - 1)];
  std::printf("%.17g %.17g %.17g\n", end.x(), end.y(), end.z());
  return 0;
}
