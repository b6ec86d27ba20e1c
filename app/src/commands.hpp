#pragma once
// The flag-sim subcommands. Each returns the process exit code (contract:
// "Exit codes"); user mistakes are thrown as UserError and reported by main.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "flagsim/core/scene.hpp"
#include "flagsim/core/scene_parser.hpp"

namespace flagsim::app {

struct RunOptions {
  std::string scene_path;                     ///< empty: the embedded default scene
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

/// Reads the scene a command names (or the default one), with the overrides.
Scene load_scene(const std::string& scene_path, std::span<const Override> overrides);
Scene load_scene(const std::string& scene_path, const std::vector<std::string>& overrides);

int run_command(const RunOptions& options);
int validate_command(const std::string& scene_path, const std::vector<std::string>& sets);
/// `info`: the run in `path`, as text or (json) as one JSON object.
int info_command(const std::string& path, bool json);
/// `scene`: the embedded default scene as shipped (--default), or a scene (a
/// file, or the default one) with its --set overrides applied, as TOML.
int scene_command(const std::string& scene_path, bool print_default,
                  const std::vector<std::string>& sets);
struct CompareOptions {
  std::string scene_path;
  std::string reference = "mass-spring";
  std::string output;  ///< -o REPORT.csv; empty: the table only
  std::vector<std::string> sets;
  std::optional<long long> frames;
  double horizon_s = 0.5;
};
int compare_command(const CompareOptions& options);

/// Checks that a report can be written at `path` (its directory exists and is
/// writable); empty is fine. Throws UserError.
void check_report_path(const std::string& path);

struct SweepOptions {
  std::string scene_path;
  std::string coarse, substeps, relax, infill, backend;  ///< comma-separated lists
  std::string output, plot;
  std::vector<std::string> sets;
  std::optional<long long> frames;
  std::optional<int> point;
  int jobs = 1;
  double horizon_s = 0.5;
  std::vector<std::string> merge;  ///< CSVs to join instead of running
  /// The reference run, shared: read from this file when it is there, else
  /// run and saved there (sweep --jobs uses one in its points' directory).
  std::string reference_file;
  bool list = false;      ///< print the points and exit
  bool resume = false;    ///< with --point: nothing to do when -o already holds its row
  std::string slurm_dir;  ///< --slurm DIR: write Slurm batch jobs instead of running
  bool submit = false;    ///< --submit: and sbatch them
  std::vector<std::string> slurm_args;  ///< --slurm-arg: extra #SBATCH options
  bool quiet = false;
};
/// argv: the command line that started this sweep (children re-run it with --point).
int sweep_command(const SweepOptions& options, const std::vector<std::string>& argv);

struct ExportOptions {
  std::string output;                 ///< -o NAME.pc2 | NAME.obj | DIR/
  std::optional<std::string> frames;  ///< --frames A:B
};
/// `export`: the dense lattice of an output file as a PC2 point cache and its
/// OBJ (NAME.pc2), one OBJ (NAME.obj) or an OBJ per frame (DIR/).
int export_command(const std::string& h5_path, const ExportOptions& options);

/// `plot`: strain, kinetic energy and wall time per frame of an output file, as an image.
int plot_command(const std::string& h5_path, const std::string& output);

struct RenderRequest;
int render_command(const std::string& h5_path, const RenderRequest& request);

}  // namespace flagsim::app
