#include "dense_input.hpp"

#include <fmt/format.h>
#include <stdlib.h>  // mkdtemp

#include <filesystem>
#include <vector>

#include "flagsim/core/errors.hpp"
#include "flagsim/data/output_reader.hpp"
#include "interrupt.hpp"
#include "run_command.hpp"

namespace flagsim::app {

namespace fs = std::filesystem;

DenseInput::DenseInput(const std::string& h5_path) : path_(h5_path) {
  int frames = 0;
  {
    const data::OutputReader reader(h5_path);
    if (reader.dense()) return;
    frames = reader.frame_count();
  }
  std::string pattern = (fs::temp_directory_path() / "flag-sim-refine.XXXXXX").string();
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  if (!::mkdtemp(name.data()))
    throw IoError(fmt::format("{}: cannot make a temporary directory to refine it in ({})", h5_path,
                              pattern));
  directory_ = name.data();
  RunOptions refine;
  refine.refine_input = h5_path;
  refine.output_path = (fs::path(directory_) / "dense.h5").string();
  refine.quiet = true;
  refine.summary = false;
  fmt::print(
      "note: {} keeps the coarse trajectory only (output.dense = false): refining its {} "
      "frames first\n",
      h5_path, frames);
  std::fflush(stdout);
  const int code = run_command(refine);
  if (code == int(ExitCode::kInterrupted))
    throw Interrupted(fmt::format("stopped while refining {}; nothing was written", h5_path));
  path_ = refine.output_path;
}

DenseInput::~DenseInput() {
  if (directory_.empty()) return;
  std::error_code ec;
  fs::remove_all(directory_, ec);
}

}  // namespace flagsim::app
