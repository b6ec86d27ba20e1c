#include "python_plot.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <filesystem>

#include "flagsim/core/errors.hpp"
#include "flagsim/core/stop_request.hpp"
#include "flagsim/os/child_process.hpp"

namespace flagsim::app {

void check_plot_tools(const std::string& what, bool needs_h5py) {
  const int status =
      run_quietly({kPython, "-c", needs_h5py ? "import matplotlib, h5py" : "import matplotlib"});
  if (stop_requested())  // the signal ended the check, not a missing module
    throw Interrupted(fmt::format("{} stopped by a signal; nothing was written", what));
  if (status != 0)
    throw UserError(fmt::format(
        "{} needs {} with matplotlib{} (apt-get install "
        "python3-matplotlib{})",
        what, kPython, needs_h5py ? " and h5py" : "", needs_h5py ? " python3-h5py" : ""));
}

void run_plot_script(std::string_view script, const std::vector<std::string>& args,
                     const std::string& png) {
  std::vector<std::string> argv = {kPython, "-"};
  argv.insert(argv.end(), args.begin(), args.end());
  ChildProcess python(argv, true, ChildOutput::kCapture);
  if (!python.valid()) throw IoError(fmt::format("{}: cannot start {}", png, kPython));
  std::fwrite(script.data(), 1, script.size(), python.input());
  const int status = python.wait();
  if (stop_requested())
    throw Interrupted(fmt::format("plotting {} stopped by a signal; nothing was written", png));
  if (status != 0) {  // its last line: "OSError: [Errno 28] No space left on device", ...
    const std::string said = python.captured();
    throw IoError(fmt::format("{}: the plot failed ({} exited with {}{})", png, kPython, status,
                              said.empty() ? "" : ": " + said));
  }
}

std::string partial_image_of(const std::string& image) {
  const std::filesystem::path target(image);
  return (target.parent_path() /
          (target.stem().string() + ".partial" + target.extension().string()))
      .string();
}

void draw_plot(std::string_view script, std::vector<std::string> args, std::size_t image_arg,
               const std::string& image) {
  const std::string partial = partial_image_of(image);
  args.at(image_arg) = partial;
  try {
    run_plot_script(script, args, image);
    std::error_code ec;
    std::filesystem::rename(partial, image, ec);
    if (ec) throw IoError(fmt::format("{}: cannot rename to {}: {}", partial, image, ec.message()));
  } catch (...) {
    std::error_code ec;
    std::filesystem::remove(partial, ec);
    throw;
  }
}

}  // namespace flagsim::app
