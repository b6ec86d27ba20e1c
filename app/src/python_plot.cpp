#include "python_plot.hpp"

#include <fmt/format.h>

#include <cstdio>

#include "flagsim/core/child_process.hpp"
#include "flagsim/core/errors.hpp"

namespace flagsim::app {

void check_plot_tools(const std::string& what, bool needs_h5py) {
  if (run_quietly({kPython, "-c", needs_h5py ? "import matplotlib, h5py" : "import matplotlib"}) !=
      0)
    throw UserError(fmt::format(
        "{} needs {} with matplotlib{} (apt-get install "
        "python3-matplotlib{})",
        what, kPython, needs_h5py ? " and h5py" : "", needs_h5py ? " python3-h5py" : ""));
}

void run_plot_script(std::string_view script, const std::vector<std::string>& args,
                     const std::string& png) {
  std::vector<std::string> argv = {kPython, "-"};
  argv.insert(argv.end(), args.begin(), args.end());
  ChildProcess python(argv, true, false);
  if (!python.valid()) throw IoError(fmt::format("{}: cannot start {}", png, kPython));
  std::fwrite(script.data(), 1, script.size(), python.input());
  const int status = python.wait();
  if (status != 0)
    throw IoError(fmt::format("{}: the plot failed ({} exited with {})", png, kPython, status));
}

}  // namespace flagsim::app
