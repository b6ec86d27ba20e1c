// The flag-sim command line (contract: "Command line").
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <iostream>
#include <optional>
#include <regex>
#include <string_view>
#include <vector>

#include "compare_command.hpp"
#include "export_command.hpp"
#include "flagsim/coarse_physics/bullet_cloth.hpp"
#include "flagsim/core/errors.hpp"
#include "flagsim/core/message.hpp"
#include "flagsim/core/near_miss.hpp"
#include "flagsim/core/version.hpp"
#include "flagsim/data/hdf5_library.hpp"
#include "flagsim/render/offscreen_context.hpp"
#include "flagsim/scene/scene_keys.hpp"
#include "info_command.hpp"
#include "plot_command.hpp"
#include "render_command.hpp"
#include "run_command.hpp"
#include "scene_commands.hpp"
#include "sweep_command.hpp"

namespace {

using flagsim::ExitCode;

int fail(ExitCode code, const std::string& message) {
  fmt::print(stderr, "error: {}\n", flagsim::one_line(message));
  return int(code);
}

// "; did you mean --frames?" for the first --option of argv that its command
// (argv[1]) does not have, when one of the command's options is a plausible
// typo of it; "" otherwise.
std::string option_hint(const CLI::App& cli, int argc, char** argv) {
  if (argc < 3) return {};
  const CLI::App* command = nullptr;
  for (const CLI::App* sub : cli.get_subcommands([](const CLI::App*) { return true; }))
    if (sub->get_name() == argv[1]) command = sub;
  if (!command) return {};
  std::vector<std::string> names;
  for (const CLI::Option* option : command->get_options())
    for (const std::string& name : option->get_lnames()) names.push_back(name);
  const std::vector<std::string_view> candidates(names.begin(), names.end());
  for (int i = 2; i < argc; ++i) {
    std::string_view typed = argv[i];
    if (typed == "--") break;
    if (!typed.starts_with("--")) continue;
    typed = typed.substr(2, typed.find('=') == std::string_view::npos ? std::string_view::npos
                                                                      : typed.find('=') - 2);
    if (std::find(names.begin(), names.end(), typed) != names.end()) continue;
    const std::string guess = flagsim::detail::closest_name(typed, candidates);
    return guess.empty() ? std::string() : fmt::format("; did you mean --{}?", guess);
  }
  return {};
}

// Integer options in plain decimal: CLI11 would read "0x10" as 16 and "0b1" as 1.
const CLI::Validator kDecimal(
    [](const std::string& text) {
      const std::size_t sign = !text.empty() && (text[0] == '-' || text[0] == '+') ? 1 : 0;
      const bool digits = text.size() > sign && text.size() <= 19 &&
                          std::all_of(text.begin() + long(sign), text.end(),
                                      [](char c) { return c >= '0' && c <= '9'; });
      return digits ? std::string()
                    : "expected a whole number in decimal digits, got '" +
                          flagsim::printable(text) + "'";
    },
    "INT");

// Real-valued options as numbers are written (digits, a point, an exponent), not
// hexadecimal floats, "inf" or "nan".
const CLI::Validator kNumber(
    [](const std::string& text) {
      static const std::regex number(R"(^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$)");
      return std::regex_match(text, number)
                 ? std::string()
                 : "expected a number, e.g. 0.5, got '" + flagsim::printable(text) + "'";
    },
    "NUMBER");

// The argument that is empty ('' or --option=), with the option it belongs
// to; nullopt when none is. An empty value is never what a user meant: an
// empty -o or --frames was silently ignored, an empty scene path read the
// default scene.
std::optional<std::string> empty_argument(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg.empty())
      return i > 1 && argv[i - 1][0] == '-' ? fmt::format("{} ''", flagsim::printable(argv[i - 1]))
                                            : fmt::format("argument {} ('')", i);
    if (arg.size() > 2 && arg.substr(0, 2) == "--" && arg.back() == '=')
      return flagsim::printable(std::string(arg));
  }
  return std::nullopt;
}

// The options compare and sweep share: the scene, its frames and overrides, the horizon.
void add_measure_options(CLI::App* cmd, std::string& scene, std::optional<long long>& frames,
                         double& horizon_s, std::vector<std::string>& sets) {
  cmd->add_option("scene", scene, "Scene file (TOML; default: the embedded one)");
  cmd->add_option("--frames", frames, "Frames per run, including t = 0")->check(kDecimal);
  cmd->add_option("--horizon", horizon_s, "Short horizon, s (default 0.5)")->check(kNumber);
  cmd->add_option("--set", sets, "Override a scene key: KEY=VALUE (TOML value)");
}

int run_main(int argc, char** argv) {
  flagsim::data::skip_hdf5_exit_cleanup();
  CLI::App cli{"flag-sim: flag and cloth simulation (Agui, Nishii & Nakajima 1990 hybrid)",
               "flag-sim"};
  cli.set_version_flag("--version", [] {
    // The libraries as this binary runs them (HDF5, Bullet, Mesa) or was built
    // with (header-only ones): what a bug report needs.
    return fmt::format(
        "flag-sim {}\nHDF5 {}, Bullet {}, Eigen {}.{}.{}, Mesa (OSMesa) GL {}, toml++ {}.{}.{}, "
        "fmt {}.{}.{}, CLI11 {}",
        flagsim::version(), flagsim::data::hdf5_version(), flagsim::physics::bullet_version(),
        EIGEN_WORLD_VERSION, EIGEN_MAJOR_VERSION, EIGEN_MINOR_VERSION,
        flagsim::render::osmesa_gl_version(), TOML_LIB_MAJOR, TOML_LIB_MINOR, TOML_LIB_PATCH,
        FMT_VERSION / 10000, FMT_VERSION / 100 % 100, FMT_VERSION % 100, CLI11_VERSION);
  });
  cli.require_subcommand(1);

  flagsim::app::RunOptions run;
  CLI::App* run_cmd =
      cli.add_subcommand("run", "Simulate a scene (default: the embedded one) to HDF5");
  run_cmd->add_option("scene", run.scene_path, "Scene file (TOML)");
  run_cmd->add_option("-o,--output", run.output_path, "Output file (.h5)");
  run_cmd->add_option("--mode", run.mode, "Override scene.mode");
  run_cmd->add_option("--frames", run.frames, "Number of frames to write, including t = 0")
      ->check(kDecimal);
  run_cmd->add_option("--seed", run.seed, "Override scene.seed");
  run_cmd->add_option("--set", run.sets, "Override a scene key: KEY=VALUE (TOML value)");
  run_cmd->add_option("--render", run.render,
                      "Also render the frames to OUT.mp4|.mkv|.webm|.gif or DIR (PNGs)");
  run_cmd->add_option("--size", run.render_size, "Rendered image size WxH (default 1280x720)");
  run_cmd->add_option("--style", run.render_style, "wireframe, shaded (default) or textured");
  run_cmd->add_option("--texture", run.render_texture, "PNG for --style textured");
  run_cmd->add_option("--color", run.render_color, "Colour the rendered cloth by strain or speed");
  run_cmd->add_flag("-q,--quiet", run.quiet, "No progress line, only the summary");
  run_cmd->add_option(
      "--resume", run.resume_input,
      "Continue the run in OUT.h5 (interrupted or complete) to its scene's "
      "duration, or to --frames N / --set scene.duration=T; -o writes it elsewhere");

  flagsim::app::RunOptions refine;
  CLI::App* refine_cmd = cli.add_subcommand(
      "refine", "Recompute the dense frames of a run that kept its coarse trajectory only");
  refine_cmd->add_option("input", refine.refine_input, "Output of a run with output.dense = false")
      ->required();
  refine_cmd->add_option("-o,--output", refine.output_path, "Output file (.h5)")->required();
  refine_cmd->add_option("--set", refine.sets,
                         "Override flag.fine, infill.*, wrinkles.*, limits.* or output.*");
  refine_cmd->add_flag("-q,--quiet", refine.quiet, "No progress line, only the summary");

  std::string validate_path;
  std::vector<std::string> validate_sets;
  CLI::App* validate_cmd = cli.add_subcommand("validate", "Check a scene file without running it");
  validate_cmd->add_option("scene", validate_path, "Scene file (TOML; default: the embedded one)");
  validate_cmd->add_option("--set", validate_sets, "Override a scene key: KEY=VALUE (TOML value)");

  std::string info_path;
  CLI::App* info_cmd = cli.add_subcommand("info", "Summarise an output file");
  info_cmd->add_option("file", info_path, "flag-sim output (.h5)")->required();
  bool info_json = false;
  info_cmd->add_flag("--json", info_json, "Everything info prints, as one JSON object");

  bool print_default = false;
  std::string scene_path;
  std::vector<std::string> scene_sets;
  CLI::App* scene_cmd =
      cli.add_subcommand("scene", "Print a scene as run would take it (after --set), as TOML");
  scene_cmd->add_option("scene", scene_path, "Scene file (TOML; default: the embedded one)");
  scene_cmd->add_flag("--default", print_default, "The embedded default scene");
  scene_cmd->add_option("--set", scene_sets, "Override a scene key (TOML value)");

  std::string render_input;
  flagsim::app::RenderRequest render;
  CLI::App* render_cmd =
      cli.add_subcommand("render", "Draw the frames of an output file to PNGs or a video");
  render_cmd->add_option("file", render_input, "flag-sim output (.h5)")->required();
  render_cmd
      ->add_option("-o,--output", render.output,
                   "OUT.mp4|.mkv|.webm|.gif, a directory for PNG frames, or STILL.png (one frame)")
      ->required();
  render_cmd->add_option("--size", render.size, "Image size WxH (default 1280x720)");
  render_cmd->add_option("--style", render.style, "wireframe, shaded (default) or textured");
  render_cmd->add_option("--texture", render.texture, "PNG for --style textured");
  render_cmd->add_option(
      "--frames", render.frames,
      "Frames A:B (A to B - 1) or frame N, as Python indexes the file's frames (-1: the last)");
  render_cmd->add_option("--camera", render.camera, "three-quarter (default), front or side");
  render_cmd->add_option("--eye", render.eye, "Camera position X,Y,Z in m (instead of --camera)");
  render_cmd->add_option("--target", render.target,
                         "What the --eye camera looks at, X,Y,Z in m (default: the run's centre)");
  render_cmd->add_option("--color", render.color,
                         "Colour the shaded cloth by strain or speed (one scale for all frames)");
  render_cmd->add_option("--antialias", render.antialias,
                         "Samples along each side of a pixel, averaged: 1 (none) to 4 (default 2)");
  render_cmd->add_flag("-q,--quiet", render.quiet, "No progress line, only the summary");

  std::string export_input;
  flagsim::app::ExportOptions export_options;
  CLI::App* export_cmd = cli.add_subcommand(
      "export",
      "The dense lattice for Blender and other DCC tools: PC2 point cache + OBJ, or OBJs");
  export_cmd->add_option("file", export_input, "flag-sim output (.h5)")->required();
  export_cmd
      ->add_option("-o,--output", export_options.output,
                   "NAME.pc2 (and NAME.obj), NAME.obj (one frame) or DIR/ (an OBJ per frame)")
      ->required();
  export_cmd->add_option(
      "--frames", export_options.frames,
      "Frames A:B (A to B - 1) or frame N, as Python indexes the file's frames (-1: the last)");

  std::string plot_input, plot_output;
  CLI::App* plot_cmd = cli.add_subcommand(
      "plot", "A run's strain, kinetic energy and ms per frame over time (PNG, SVG or PDF)");
  plot_cmd->add_option("file", plot_input, "flag-sim output (.h5)")->required();
  plot_cmd->add_option("-o,--output", plot_output, "STATS.png|.svg|.pdf")->required();

  flagsim::app::CompareOptions compare;
  CLI::App* compare_cmd = cli.add_subcommand(
      "compare", "Hybrid against a full-lattice reference: accuracy and cost (CSV + table)");
  add_measure_options(compare_cmd, compare.scene_path, compare.frames, compare.horizon_s,
                      compare.sets);
  compare_cmd->add_option(
      "--reference", compare.reference,
      "mass-spring (default), bullet, implicit, xpbd, or all (errors against the first)");
  compare_cmd->add_option("-o,--output", compare.output, "Report CSV");
  compare_cmd->add_flag("-q,--quiet", compare.quiet, "No progress lines");
  compare_cmd
      ->add_option("--seeds", compare.seeds,
                   "Also the flap and mean shape over N seeds with their spread, and whether "
                   "the reference is converged (N x the runs)")
      ->check(kDecimal);

  flagsim::app::SweepOptions sweep;
  CLI::App* sweep_cmd = cli.add_subcommand(
      "sweep", "A grid of hybrid settings against full-lattice references (CSV, optional plot)");
  add_measure_options(sweep_cmd, sweep.scene_path, sweep.frames, sweep.horizon_s, sweep.sets);
  sweep_cmd->add_option("--coarse", sweep.coarse, "Coarse lattices, e.g. 5x7,9x13,17x25");
  sweep_cmd->add_option("--substeps", sweep.substeps, "Minimum substeps per frame, e.g. 1,8");
  sweep_cmd->add_option("--relax", sweep.relax, "The paper infill's 3.4 cap, e.g. 100,8000");
  sweep_cmd->add_option("--infill", sweep.infill, "Infill solvers side by side: smooth,paper");
  sweep_cmd->add_option("--backend", sweep.backend,
                        "Coarse physics side by side: spring-damper,bullet,implicit,xpbd");
  sweep_cmd->add_option("--pole-radius", sweep.pole_radius,
                        "Solid pole radii side by side, m; 0: the scene's own pole, e.g. 0,0.04");
  sweep_cmd->add_option("--contact-thickness", sweep.contact_thickness,
                        "Self-contact thicknesses side by side, m; 0: the scene's own [contact], "
                        "e.g. 0,0.005");
  sweep_cmd->add_option("--references", sweep.references,
                        "Full-lattice reference rows: mass-spring (default; every error is "
                        "against it), plus any of bullet,implicit,xpbd");
  sweep_cmd->add_option("-o,--output", sweep.output, "Sweep CSV");
  sweep_cmd->add_option("--plot", sweep.plot, "Error against ms per frame, PNG");
  sweep_cmd->add_option("--jobs", sweep.jobs, "Points run at a time (child processes)")
      ->check(kDecimal);
  sweep_cmd->add_option("--point", sweep.point, "Run only point I (0: the mass-spring reference)")
      ->check(kDecimal);
  sweep_cmd->add_option("--merge", sweep.merge, "Join these point CSVs instead of running");
  sweep_cmd->add_flag("-q,--quiet", sweep.quiet, "No progress lines");
  sweep_cmd
      ->add_option("--seeds", sweep.seeds,
                   "Every point at N seeds, each against the reference of its seed; prints the "
                   "mean +- seed-to-seed sd per point (N x the runs)")
      ->check(kDecimal);
  sweep_cmd->add_option("--reference-file", sweep.reference_file,
                        "The reference run: read if there, else run and saved there");
  sweep_cmd->add_flag("--list", sweep.list, "Print the points (index, label, settings) and exit");
  sweep_cmd->add_flag("--resume", sweep.resume,
                      "With --point: do nothing when -o already holds the point's row");
  sweep_cmd->add_option("--slurm", sweep.slurm_dir,
                        "Write DIR/reference.sbatch, sweep.sbatch (array), merge.sbatch instead");
  sweep_cmd->add_flag("--submit", sweep.submit, "With --slurm: submit the jobs with sbatch");
  sweep_cmd
      ->add_option("--slurm-arg", sweep.slurm_args,
                   "An #SBATCH option for every job, e.g. --slurm-arg=--partition=short")
      ->allow_extra_args(false);
  std::vector<std::string> arguments(argv, argv + argc);

  // `flag-sim help [COMMAND]`, and a misspelt command named as such (CLI11
  // would say only "A subcommand is required").
  const std::vector<CLI::App*> subcommands =
      cli.get_subcommands([](const CLI::App*) { return true; });
  if (const std::optional<std::string> empty = empty_argument(argc, argv))
    return fail(ExitCode::kBadInput,
                fmt::format("{}: an empty value; give one or leave the option out", *empty));
  if (argc == 1) {  // bare `flag-sim`: what there is to run, on the one error line
    std::vector<std::string> names;
    names.reserve(subcommands.size());
    for (const CLI::App* sub : subcommands) names.push_back(sub->get_name());
    return fail(ExitCode::kBadInput,
                fmt::format("no command given: flag-sim COMMAND, with COMMAND one of {}, help "
                            "(flag-sim help COMMAND for its options)",
                            fmt::join(names, ", ")));
  }
  const bool help = argc >= 2 && std::string_view(argv[1]) == "help";
  const char* command = help ? (argc >= 3 ? argv[2] : nullptr) : (argc >= 2 ? argv[1] : nullptr);
  if (help && (!command || std::string_view(command) == "help")) {
    fmt::print("{}", cli.help());
    return int(ExitCode::kSuccess);
  }
  if (help && std::string_view(command) == "keys") {  // every scene key, from the parser
    try {
      fmt::print("{}", flagsim::keys_reference());
    } catch (const flagsim::UserError& e) {  // the reference scenes are the parser's own
      return fail(ExitCode::kInternal, e.what());
    }
    return int(ExitCode::kSuccess);
  }
  if (command && command[0] != '-') {
    std::vector<std::string_view> names = {"help"};
    if (help) names.push_back("keys");  // flag-sim help keys
    for (const CLI::App* sub : subcommands) {
      if (sub->get_name() != command) {
        names.push_back(sub->get_name());
        continue;
      }
      if (help) {
        fmt::print("{}", sub->help());
        return int(ExitCode::kSuccess);
      }
      names.clear();  // a command: CLI11 parses the rest
      break;
    }
    if (!names.empty()) {
      const std::string guess = flagsim::detail::closest_name(command, names);
      return fail(
          ExitCode::kBadInput,
          fmt::format("unknown command '{}'{} (see flag-sim --help)", flagsim::printable(command),
                      guess.empty() ? "" : fmt::format(" (did you mean '{}'?)", guess)));
    }
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
    const bool known = argc > 1 && !cli.get_subcommands([&](const CLI::App* sub) {
                                         return sub->get_name() == argv[1];
                                       })
                                        .empty();
    return fail(ExitCode::kBadInput,
                fmt::format("{}{} (see flag-sim {})", e.what(), option_hint(cli, argc, argv),
                            known ? fmt::format("help {}", argv[1]) : std::string("--help")));
  }

  try {
    if (*run_cmd) return flagsim::app::run_command(run);
    if (*refine_cmd) return flagsim::app::run_command(refine);
    if (*validate_cmd) return flagsim::app::validate_command(validate_path, validate_sets);
    if (*info_cmd) return flagsim::app::info_command(info_path, info_json);
    if (*scene_cmd) return flagsim::app::scene_command(scene_path, print_default, scene_sets);
    if (*render_cmd) return flagsim::app::render_command(render_input, render);
    if (*plot_cmd) return flagsim::app::plot_command(plot_input, plot_output);
    if (*export_cmd) return flagsim::app::export_command(export_input, export_options);
    if (*compare_cmd) return flagsim::app::compare_command(compare);
    if (*sweep_cmd) return flagsim::app::sweep_command(sweep, arguments);
  } catch (const flagsim::UserError& e) {
    return fail(ExitCode::kBadInput, e.what());
  } catch (const flagsim::IoError& e) {
    return fail(ExitCode::kIoFailure, e.what());
  } catch (const flagsim::Interrupted& e) {
    fmt::print(stderr, "interrupted: {}\n", flagsim::one_line(e.what()));
    return int(ExitCode::kInterrupted);
  } catch (const std::bad_alloc&) {
    return fail(ExitCode::kBadInput,
                "out of memory: the lattice or run is too large for this machine");
  } catch (const std::filesystem::filesystem_error& e) {  // a file system call failed mid-work
    return fail(ExitCode::kIoFailure,
                fmt::format("{}: {}", flagsim::printable(e.path1().string()), e.code().message()));
  }
  return int(ExitCode::kBadInput);
}

// Everything printed reached standard output: a full disk or a closed pipe
// behind it is a failure (exit 4), as GNU tools make it, not a silent success.
int check_standard_output(int code) {
  std::cout.flush();
  const bool failed = std::fflush(stdout) != 0 || std::ferror(stdout) || !std::cout;
  if (!failed) return code;
  const int error = errno;
  std::fputs("error: cannot write to standard output: ", stderr);
  std::fputs(error != 0 ? std::strerror(error) : "write error", stderr);
  std::fputs("\n", stderr);
  return code == int(ExitCode::kSuccess) ? int(ExitCode::kIoFailure) : code;
}

}  // namespace

// Anything run_main does not turn into one of the contract's exit codes is a
// bug in flag-sim: one error line and exit 1, never an abort (std::terminate).
// Plain C stdio here: the handler itself must not throw.
int main(int argc, char** argv) {
  // A file-size limit (RLIMIT_FSIZE) makes a write fail with EFBIG, reported
  // as exit 4 like a full disk, instead of killing flag-sim with SIGXFSZ.
  std::signal(SIGXFSZ, SIG_IGN);
  // Helpers and test reads are waited for: SIGCHLD ignored by whoever started
  // flag-sim would make the kernel reap them first (waitpid: ECHILD).
  std::signal(SIGCHLD, SIG_DFL);
  try {
    return check_standard_output(run_main(argc, argv));
  } catch (const std::exception& e) {
    std::fputs("error: internal error (a bug in flag-sim, please report it): ", stderr);
    std::fputs(flagsim::one_line(e.what()).c_str(), stderr);
    std::fputs("\n", stderr);
  } catch (...) {
    std::fputs("error: internal error (a bug in flag-sim, please report it)\n", stderr);
  }
  return int(ExitCode::kInternal);
}
