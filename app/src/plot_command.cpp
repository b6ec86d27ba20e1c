// `flag-sim plot`: a run's statistics over time as an image (stats_plot.py).
#include "plot_command.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>

#include "flagsim/core/errors.hpp"
#include "flagsim/core/message.hpp"
#include "flagsim/data/output_reader.hpp"
#include "flagsim/os/file_roles.hpp"
#include "interrupt.hpp"
#include "python_plot.hpp"

namespace flagsim::app {
namespace fs = std::filesystem;

int plot_command(const std::string& h5_path, const std::string& output) {
  const InterruptGuard interrupt;  // SIGINT / SIGTERM: python is stopped, exit 130, nothing left
  if (output.empty()) throw UserError("plot: -o STATS.png is required");
  const fs::path target(output);
  const std::string extension = target.extension().string();
  if (extension != ".png" && extension != ".svg" && extension != ".pdf")
    throw UserError(
        fmt::format("-o {}: expected an image name ending in .png, .svg or .pdf", output));
  // Drawn under a temporary name with the same extension (matplotlib picks the
  // format from it), renamed when whole: a failed plot leaves nothing.
  const std::string partial = partial_image_of(output);
  FileRoles files;
  files.input(h5_path, "the input");
  files.output(output, "-o");
  files.output(partial, "-o (while drawn)");
  files.check();
  int frames = 0;
  {
    const data::OutputReader reader(h5_path);  // a missing or foreign file: exit 2 here
    frames = reader.frame_count();
    if (frames == 0) throw UserError(fmt::format("{}: has no frames to plot", h5_path));
  }
  check_plot_tools("plot", true);
  const fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  if (!fs::is_directory(dir) || access(dir.c_str(), W_OK) != 0)
    throw UserError(fmt::format("-o {}: cannot write to {}", output, dir.string()));
  draw_plot(stats_plot_script(), {h5_path, output}, 1, output);
  fmt::print("plotted {} of {} -> {}\n", counted(frames, "frame"), h5_path, output);
  return int(ExitCode::kSuccess);
}

}  // namespace flagsim::app
