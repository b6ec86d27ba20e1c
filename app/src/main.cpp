// The flag-sim command line (contract: "Command line").
#include <fmt/format.h>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "flagsim/core/errors.hpp"
#include "flagsim/core/version.hpp"

namespace {

using flagsim::ExitCode;

int fail(ExitCode code, const std::string& message) {
  fmt::print(stderr, "error: {}\n", message);
  return int(code);
}

}  // namespace

int main(int argc, char** argv) {
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
  run_cmd->add_option("--render", run.render, "Render frames to OUT.mp4 or DIR");
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

  // Commands of the contract that this version does not have yet: a clear
  // message and exit 2 rather than "unknown subcommand".
  std::vector<CLI::App*> unavailable;
  for (const char* name : {"render", "compare", "sweep"}) {
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
