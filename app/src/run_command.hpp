#pragma once
// `flag-sim run`: a scene simulated into an HDF5 file, and optionally rendered.
// Returns the process exit code (contract: "Exit codes"); user mistakes are
// thrown as UserError and reported by main.
#include <optional>
#include <string>
#include <vector>

namespace flagsim::app {

struct RunOptions {
  std::string scene_path;  ///< empty: the embedded default scene
  /// The scene as TOML text instead of a file (the Python module's
  /// Simulation.run), named `scene_path` in messages when that is given.
  std::optional<std::string> scene_text;
  std::string output_path;                    ///< -o; empty: output.file, else out/<name>.h5
  std::optional<std::string> mode;            ///< --mode
  std::optional<long long> frames;            ///< --frames
  std::optional<std::string> seed;            ///< --seed, as typed (checked by run)
  std::vector<std::string> sets;              ///< --set KEY=VALUE
  std::string render;                         ///< --render OUT.mp4|DIR
  std::optional<std::string> render_size;     ///< --size WxH
  std::optional<std::string> render_style;    ///< --style
  std::optional<std::string> render_texture;  ///< --texture
  std::optional<std::string> render_color;    ///< --color strain|speed
  bool quiet = false;
  /// `flag-sim refine IN.h5`: the dense frames of IN's stored coarse trajectory
  /// ([output] dense = false) instead of a simulation; its scene is IN's
  /// attribute `scene`, with `sets` of the infill's and output's keys only.
  std::string refine_input;
  /// `flag-sim run --resume OUT.h5`: continues the run in OUT.h5 from its
  /// /checkpoint to its scene's duration (`frames`, or `sets` of
  /// scene.duration only); written to `output_path`, or back to OUT.h5.
  std::string resume_input;
  /// false: no summary line and notes on standard output (a refine that
  /// render or export makes for themselves, dense_input.hpp).
  bool summary = true;
};

int run_command(const RunOptions& options);

}  // namespace flagsim::app
