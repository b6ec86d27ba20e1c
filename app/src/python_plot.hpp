#pragma once
// The plots flag-sim draws (`sweep --plot`, `plot`): Python scripts compiled
// into the binary, run by /usr/bin/python3 with matplotlib, each path an
// argument (never a word of a shell command).
#include <string>
#include <string_view>
#include <vector>

namespace flagsim::app {

inline constexpr const char* kPython = "/usr/bin/python3";

/// app/src/sweep_plot.py: `- CSV PNG`, error against cost of a sweep's rows.
std::string_view sweep_plot_script();
/// app/src/stats_plot.py: `- OUT.h5 PNG`, a run's statistics over time.
std::string_view stats_plot_script();

/// Throws UserError naming `what` (the flag or command) unless kPython can
/// import matplotlib (and, with `needs_h5py`, h5py).
void check_plot_tools(const std::string& what, bool needs_h5py = false);

/// Runs `script` as `kPython - args...`; throws IoError naming `png` when it fails.
void run_plot_script(std::string_view script, const std::vector<std::string>& args,
                     const std::string& png);

/// Where an image is drawn before it is whole: STEM.partial.EXT beside it
/// (matplotlib takes the format from the extension).
std::string partial_image_of(const std::string& image);

/// Runs `script` with args[image_arg] = partial_image_of(image) and renames
/// the result onto `image`: a failed or interrupted plot leaves nothing.
void draw_plot(std::string_view script, std::vector<std::string> args, std::size_t image_arg,
               const std::string& image);

}  // namespace flagsim::app
