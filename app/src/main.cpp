// The flag-sim command line (contract: "Command line").
#include <fmt/format.h>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "flagsim/core/errors.hpp"
#include "flagsim/core/version.hpp"
#include "flagsim/data/frame_writer.hpp"
#include "render_command.hpp"

namespace {

using flagsim::ExitCode;

int fail(ExitCode code, const std::string& message) {
  fmt::print(stderr, "error: {}\n", message);
  return int(code);
}

}  // namespace

int main(int argc, char** argv) {
  flagsim::data::skip_hdf5_exit_cleanup();
  CLI::App cli{"flag-sim: flag and cloth simulation (Agui, Nishii & Nakajima 1990 hybrid)"};
  cli.set_version_flag("--version", std::string(flagsim::version()));
  cli.require_subcommand(1);

  flagsim::app::RunOptions run;
  CLI::App* run_cmd =
      cli.add_subcommand("run", "Simulate a scene (default: the embedded one) to HDF5");
  run_cmd->add_option("scene", run.scene_path, "Scene file (TOML)");
  run_cmd->add_option("-o,--output", run.output_path, "Output file (.h5)");
  run_cmd->add_option("--mode", run.mode, "Override scene.mode");
  run_cmd->add_option("--frames", run.frames, "Number of frames to write, including t = 0");
  run_cmd->add_option("--seed", run.seed, "Override scene.seed");
  run_cmd->add_option("--set", run.sets, "Override a scene key: KEY=VALUE (TOML value)");
  run_cmd->add_option("--render", run.render, "Also render the frames to OUT.mp4 or DIR (PNGs)");
  run_cmd->add_option("--size", run.render_size, "Rendered image size WxH (default 1280x720)");
  run_cmd->add_option("--style", run.render_style, "wireframe, shaded (default) or textured");
  run_cmd->add_option("--texture", run.render_texture, "PNG for --style textured");
  run_cmd->add_flag("-q,--quiet", run.quiet, "No progress line, only the summary");

  std::string validate_path;
  CLI::App* validate_cmd = cli.add_subcommand("validate", "Check a scene file without running it");
  validate_cmd->add_option("scene", validate_path, "Scene file (TOML)")->required();

  std::string info_path;
  CLI::App* info_cmd = cli.add_subcommand("info", "Summarise an output file");
  info_cmd->add_option("file", info_path, "flag-sim output (.h5)")->required();

  bool print_default = false;
  CLI::App* scene_cmd = cli.add_subcommand("scene", "Print a scene");
  scene_cmd->add_flag("--default", print_default, "Print the embedded default scene");

  std::string render_input;
  flagsim::app::RenderRequest render;
  CLI::App* render_cmd =
      cli.add_subcommand("render", "Draw the frames of an output file to PNGs or an MP4");
  render_cmd->add_option("file", render_input, "flag-sim output (.h5)")->required();
  render_cmd->add_option("-o,--output", render.output, "OUT.mp4, or a directory for PNG frames")
      ->required();
  render_cmd->add_option("--size", render.size, "Image size WxH (default 1280x720)");
  render_cmd->add_option("--style", render.style, "wireframe, shaded (default) or textured");
  render_cmd->add_option("--texture", render.texture, "PNG for --style textured");

  // Commands of the contract that this version does not have yet: a clear
  // message and exit 2 rather than "unknown subcommand".
  std::vector<CLI::App*> unavailable;
  for (const char* name : {"compare", "sweep"}) {
    CLI::App* cmd =
        cli.add_subcommand(name, fmt::format("({} is not available in this version)", name));
    cmd->allow_extras();
    unavailable.push_back(cmd);
  }

  try {
    cli.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return cli.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return cli.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return cli.exit(e);
  } catch (const CLI::ParseError& e) {
    return fail(ExitCode::kBadInput, fmt::format("{} (see flag-sim --help)", e.what()));
  }

  try {
    if (*run_cmd) return flagsim::app::run_command(run);
    if (*validate_cmd) return flagsim::app::validate_command(validate_path);
    if (*info_cmd) return flagsim::app::info_command(info_path);
    if (*scene_cmd) return flagsim::app::scene_command(print_default);
    if (*render_cmd) return flagsim::app::render_command(render_input, render);
    for (CLI::App* cmd : unavailable)
      if (*cmd)
        return fail(
            ExitCode::kBadInput,
            fmt::format("'{}' is not available in this version of flag-sim", cmd->get_name()));
  } catch (const flagsim::UserError& e) {
    return fail(ExitCode::kBadInput, e.what());
  } catch (const flagsim::IoError& e) {
    return fail(ExitCode::kIoFailure, e.what());
  } catch (const std::bad_alloc&) {
    return fail(ExitCode::kBadInput,
                "out of memory: the lattice or run is too large for this machine");
  }
  return int(ExitCode::kBadInput);
}
