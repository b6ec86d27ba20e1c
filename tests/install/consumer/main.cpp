// The embedded default scene at 17 x 25, stepped FRAMES frames through the
// installed library: prints the middle row's fly-end node, m, with every digit.
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "flagsim/scene/scene_parser.hpp"
#include "flagsim/sim/simulation.hpp"

int main(int argc, char** argv) {
  const int frames = argc > 1 ? std::atoi(argv[1]) : 5;
  const std::vector<std::string> overrides = {"flag.fine=[17,25]"};
  const flagsim::Scene scene =
      flagsim::parse_scene(flagsim::default_scene_toml(), flagsim::kDefaultSceneName, overrides);
  const auto simulation = flagsim::sim::make_simulation(scene);
  for (int f = 0; f < frames; ++f) simulation->advance_frame(nullptr);
  const flagsim::Lattice& lattice = simulation->lattice();
  const flagsim::Vec3 end =
      simulation->positions()[lattice.index(lattice.rows / 2, lattice.cols - 1)];
  std::printf("%.17g %.17g %.17g\n", end.x(), end.y(), end.z());
  return 0;
}
