// `flag-sim info OUT.h5`: what a run was and how it went.
#include <fmt/format.h>

#include <algorithm>
#include <numeric>

#include "commands.hpp"
#include "flagsim/core/errors.hpp"
#include "flagsim/data/output_reader.hpp"

namespace flagsim::app {

int info_command(const std::string& path) {
  const data::OutputReader reader(path);
  const std::vector<double> times = reader.times_s();
  fmt::print("file      {}\n", path);
  fmt::print("status    {}\n", reader.attribute("status"));
  const std::string reason = reader.attribute("status_reason");
  if (!reason.empty()) fmt::print("reason    {}\n", reason);
  fmt::print("mode      {}\n", reader.attribute("mode"));
  fmt::print("lattice   {} x {} ({} nodes)\n", reader.rows(), reader.cols(),
             reader.rows() * reader.cols());
  if (times.empty())
    fmt::print("frames    0\n");
  else
    fmt::print("frames    {}, t = {:.4g} .. {:.4g} s\n", reader.frame_count(), times.front(),
               times.back());
  fmt::print("effects   {}\n", reader.attribute("effects"));
  fmt::print("seed      {}\n", reader.seed());
  fmt::print("version   {}\n", reader.attribute("version"));
  const double substeps = reader.number_attribute("substeps_per_frame", 0.0);
  if (substeps > 0)
    fmt::print("substeps  {:.0f} per frame of {:.3g} s (stability limit {:.3g} s)\n", substeps,
               reader.number_attribute("substep_seconds", 0.0),
               reader.number_attribute("stable_substep_seconds", 0.0));
  const std::vector<double> max_strain = reader.stat("max_strain");
  const std::vector<double> mean_strain = reader.stat("mean_strain");
  if (!max_strain.empty())
    fmt::print("strain    max {:.3f}%, mean {:.3f}% (over all frames)\n",
               100.0 * *std::max_element(max_strain.begin(), max_strain.end()),
               100.0 * std::accumulate(mean_strain.begin(), mean_strain.end(), 0.0) /
                   double(std::max<std::size_t>(1, mean_strain.size())));
  const std::vector<double> wall = reader.stat("wall_seconds");
  // Frame 0 is the initial state (no physics): leave it out of the average.
  if (wall.size() > 1) {
    const double per_frame =
        std::accumulate(wall.begin() + 1, wall.end(), 0.0) / double(wall.size() - 1);
    std::string split;
    const std::vector<std::string> names = reader.stage_names();
    const auto stages = reader.stage_seconds();
    for (std::size_t s = 0; s < names.size(); ++s) {
      double sum = 0.0;
      for (std::size_t t = 1; t < stages.size(); ++t) sum += stages[t][s];
      split += fmt::format("{}{} {:.2f}", split.empty() ? "" : ", ", names[s],
                           1000.0 * sum / double(stages.size() - 1));
    }
    fmt::print("timing    {:.2f} ms/frame ({})\n", 1000.0 * per_frame, split);
  }
  return int(ExitCode::kSuccess);
}

}  // namespace flagsim::app
