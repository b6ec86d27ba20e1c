#include "slurm_sweep.hpp"

#include <fmt/format.h>
#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "flagsim/core/errors.hpp"
#include "flagsim/core/message.hpp"
#include "flagsim/os/child_process.hpp"
#include "flagsim/os/file_roles.hpp"
#include "flagsim/os/staged_file.hpp"
#include "report.hpp"

namespace flagsim::app {
namespace fs = std::filesystem;
namespace {

// #SBATCH lines are not shell words: Slurm splits them at blanks and reads no
// quotes. Paths that appear in them are held to characters that need none.
bool plain_path(const std::string& path) {
  return !path.empty() && std::all_of(path.begin(), path.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '/' ||
           c == '.' || c == '_' || c == '-' || c == '+';
  });
}

std::string point_csv(const fs::path& dir, int point) {
  return (dir / fmt::format("point_{}.csv", point)).string();
}

}  // namespace

bool sweep_point_done(const std::string& csv, int point, int seeds) {
  std::error_code ec;
  if (!fs::is_regular_file(csv, ec)) return false;
  try {
    const std::vector<std::string> rows = csv_rows(csv);
    return rows.size() == std::size_t(seeds) &&
           std::all_of(rows.begin(), rows.end(),
                       [&](const std::string& row) { return parse_csv_line(row).point == point; });
  } catch (const UserError&) {
    return false;  // half-written or not ours: run it again
  }
}

namespace {

// Point lists as Slurm's --array takes them: "1-3,5,7-9".
std::string array_spec(const std::vector<int>& points) {
  std::string spec;
  for (std::size_t i = 0; i < points.size();) {
    std::size_t j = i;
    while (j + 1 < points.size() && points[j + 1] == points[j] + 1) ++j;
    spec +=
        fmt::format("{}{}", spec.empty() ? "" : ",",
                    j > i ? fmt::format("{}-{}", points[i], points[j]) : std::to_string(points[i]));
    i = j + 1;
  }
  return spec;
}

void write_script(const fs::path& path, const std::string& text) {
  // chmod before the rename: the script is never there without its x bit.
  StagedFile script(path.string());
  script.write(text);
  ::chmod(StagedFile::partial_of(path.string()).c_str(), 0755);
  script.commit();
}

std::string header(const std::string& name, const std::string& log, const std::string& what,
                   const std::vector<std::string>& sbatch_args) {
  std::string text = fmt::format(
      "#!/bin/sh\n"
      "# {}\n"
      "# Written by `flag-sim sweep ... --slurm`; written again when that runs again.\n"
      "#SBATCH --job-name={}\n"
      "#SBATCH --output={}\n"
      "#SBATCH --ntasks=1\n"
      "#SBATCH --cpus-per-task=1\n",
      what, name, log);
  for (const std::string& arg : sbatch_args) text += fmt::format("#SBATCH {}\n", arg);
  return text;
}

// sbatch --parsable: "JOBID" or "JOBID;CLUSTER".
std::string submit(const std::vector<std::string>& argv, const std::string& script) {
  std::string output;
  const int code = run_capturing(argv, output);
  std::string id = output.substr(0, output.find_first_of(";\n"));
  if (code != 0 || id.empty() ||
      !std::all_of(id.begin(), id.end(), [](char c) { return c >= '0' && c <= '9'; }))
    throw IoError(fmt::format("sbatch {}: {}", script,
                              code < 0
                                  ? std::string("cannot run sbatch (is Slurm's client installed?)")
                                  : fmt::format("exit {}: {}", code, output)));
  return id;
}

}  // namespace

std::string shell_quoted(const std::vector<std::string>& argv) {
  std::string line;
  for (const std::string& arg : argv) {
    std::string quoted = "'";
    for (char c : arg) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    line += (line.empty() ? "" : " ") + quoted + "'";
  }
  return line;
}

std::string write_slurm_sweep(const SlurmSweep& slurm,
                              const std::vector<std::string>& point_command, int points,
                              const std::string& csv, const std::string& plot) {
  const fs::path dir = fs::absolute(slurm.dir).lexically_normal();
  if (!plain_path(dir.string()))
    throw UserError(fmt::format(
        "--slurm {}: use a directory path of letters, digits and / . _ - + only (Slurm's #SBATCH "
        "lines cannot quote)",
        slurm.dir));
  for (const std::string& arg : slurm.sbatch_args)
    if (!arg.starts_with("--") || arg.find_first_of(" \t\n\r") != std::string::npos)
      throw UserError(
          fmt::format("--slurm-arg={}: expected one sbatch option as --name=value (e.g. "
                      "--slurm-arg=--partition=short), no blanks",
                      printable(arg)));
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw UserError(fmt::format("--slurm {}: exists and is not a directory", slurm.dir));
  CreatedDirectories created;  // removed again when no script could be written into it
  if (!created.create(dir.string(), ec))
    throw UserError(fmt::format("--slurm {}: cannot create it: {}", slurm.dir, ec.message()));

  const std::string reference = (dir / "reference.rec").string();
  const bool reference_done =
      fs::exists(reference, ec) && sweep_point_done(point_csv(dir, 0), 0, slurm.seeds);
  std::vector<int> missing;
  for (int i = 1; i < points; ++i)
    if (!sweep_point_done(point_csv(dir, i), i, slurm.seeds)) missing.push_back(i);

  // reference.sbatch: point 0, saving the reference.
  std::vector<std::string> reference_command = point_command;
  reference_command.insert(reference_command.end(),
                           {"--point", "0", "--reference-file", reference, "-o", point_csv(dir, 0),
                            "--quiet", "--resume"});
  write_script(
      dir / "reference.sbatch",
      header("flag-sim-reference", (dir / "reference-%j.out").string(),
             "The sweep's reference (point 0), saved for the other points.", slurm.sbatch_args) +
          "exec " + shell_quoted(reference_command) + "\n");
  // sweep.sbatch: one task per point not yet done, each reading the reference.
  std::vector<std::string> task_command = point_command;
  task_command.insert(task_command.end(), {"--point"});
  const std::string task_tail = shell_quoted({"--reference-file", reference, "-o"});
  const std::string array = missing.empty() ? std::string("1-1") : array_spec(missing);
  write_script(dir / "sweep.sbatch",
               header("flag-sim-points", (dir / "point-%A_%a.out").string(),
                      fmt::format("The sweep's points {} (one array task each), after the "
                                  "reference.",
                                  array),
                      slurm.sbatch_args) +
                   fmt::format("#SBATCH --array={}\n", array) + "exec " +
                   shell_quoted(task_command) + " \"$SLURM_ARRAY_TASK_ID\" " + task_tail + " " +
                   shell_quoted({(dir / "point_").string()}) + "\"$SLURM_ARRAY_TASK_ID\"'.csv' " +
                   shell_quoted({"--quiet", "--resume"}) + "\n");
  // merge.sbatch: every point's CSV into the sweep's.
  std::vector<std::string> merge_command = {point_command[0], "sweep", "--quiet", "-o", csv};
  if (!plot.empty()) merge_command.insert(merge_command.end(), {"--plot", plot});
  merge_command.push_back("--merge");
  for (int i = 0; i < points; ++i) merge_command.push_back(point_csv(dir, i));
  write_script(
      dir / "merge.sbatch",
      header("flag-sim-merge", (dir / "merge-%j.out").string(),
             fmt::format("Merges the {} points into {}.", points, csv), slurm.sbatch_args) +
          "exec " + shell_quoted(merge_command) + "\n");

  std::string said = fmt::format(
      "sweep: {} points as Slurm jobs in {}: reference.sbatch ({}), sweep.sbatch (points {}), "
      "merge.sbatch (-> {})",
      points, dir.string(), reference_done ? "done, left out" : "point 0",
      missing.empty() ? std::string("none left") : array_spec(missing), csv);
  if (!slurm.submit) return said + "\n";
  // Each job after the one before it; what is already done is not submitted.
  std::string after, ids;
  const auto sbatch = [&](const std::string& script, const std::string& what) {
    std::vector<std::string> argv = {"sbatch", "--parsable"};
    if (!after.empty()) argv.push_back("--dependency=afterok:" + after);
    argv.push_back((dir / script).string());
    after = submit(argv, (dir / script).string());
    ids += fmt::format("{}{} {}", ids.empty() ? "" : ", ", what, after);
  };
  if (!reference_done) sbatch("reference.sbatch", "reference");
  if (!missing.empty()) sbatch("sweep.sbatch", "points");
  sbatch("merge.sbatch", "merge");
  return said + fmt::format("\nsubmitted: {}\n", ids);
}

}  // namespace flagsim::app
