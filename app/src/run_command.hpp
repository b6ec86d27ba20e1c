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
};

int run_command(const RunOptions& options);

}  // namespace flagsim::app
