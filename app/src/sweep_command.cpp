// `flag-sim sweep`: a grid of hybrid settings (coarse lattice x substeps x
// relaxation passes) and the two full-lattice references, each point a run
// measured against the mass-spring reference (report.hpp). Points are
// independent: --point I runs one, --jobs N runs N at a time as child
// processes, --merge joins the CSVs of points run anywhere.
#include "sweep_command.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <spawn.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>

#include "flagsim/core/errors.hpp"
#include "flagsim/core/message.hpp"
#include "flagsim/os/child_process.hpp"
#include "flagsim/os/file_roles.hpp"
#include "flagsim/os/staged_file.hpp"
#include "interrupt.hpp"
#include "progress.hpp"
#include "python_plot.hpp"
#include "report.hpp"
#include "run_record.hpp"
#include "scene_commands.hpp"
#include "slurm_sweep.hpp"
#include "sweep_grid.hpp"

extern char** environ;

namespace flagsim::app {
namespace fs = std::filesystem;
namespace {

std::vector<std::string> base_sets(const SweepOptions& o) {
  std::vector<std::string> sets = o.sets;
  if (o.frames) {
    if (*o.frames < 2)
      throw UserError(fmt::format("--frames {}: a sweep needs at least 2 frames", *o.frames));
    sets.push_back(fmt::format("scene.frames={}", *o.frames));
  }
  return sets;
}

// The scene of `point` at the sweep's seed number `seed` (0 .. --seeds - 1):
// scene.seed + seed.
Scene scene_of(const SweepOptions& o, const SweepPoint& point, int seed = 0) {
  std::vector<std::string> sets = base_sets(o);
  sets.insert(sets.end(), point.sets.begin(), point.sets.end());
  if (seed > 0) {
    const std::uint64_t first = load_scene(o.scene_path, sets).seed;
    sets.push_back(fmt::format("scene.seed={}", first + std::uint64_t(seed)));
  }
  return load_scene(o.scene_path, sets);
}

// Where the reference of seed number `seed` is saved: `file` for the first,
// FILE.seedN for the others (N = 1 .. --seeds - 1).
std::string reference_file_of(const std::string& file, int seed) {
  return file.empty() || seed == 0 ? file : fmt::format("{}.seed{}", file, seed);
}

// The seeds' summary a sweep prints after its table: per point, the flap and
// the errors against the reference of the same seed, mean +- seed-to-seed sd.
std::string seed_summary(const std::vector<ReportRow>& rows) {
  std::map<int, std::vector<const ReportRow*>> by_point;
  for (const ReportRow& row : rows) by_point[row.point].push_back(&row);
  std::string out =
      "over the seeds, mean +- seed-to-seed sd (errors against the reference of the same seed):\n";
  for (const auto& [point, seeds] : by_point) {
    std::vector<double> flap, error, shape;
    for (const ReportRow* row : seeds) {
      if (row->status != RunState::kComplete) continue;
      if (row->flap_hz && *row->flap_hz > 0.0) flap.push_back(*row->flap_hz);
      if (row->flap_rel_error && std::isfinite(*row->flap_rel_error))
        error.push_back(100.0 * *row->flap_rel_error);
      if (row->mean_shape_rms_m) shape.push_back(1e3 * *row->mean_shape_rms_m);
    }
    const auto field = [&](const std::vector<double>& v, const char* unit) {
      if (v.empty()) return std::string("-");
      const Spread s = spread_of(v);
      return fmt::format("{:.2f} +- {:.2f}{}", s.mean, s.sd, unit);
    };
    out += fmt::format("  {:<38} {} seed(s): flap {}, |flap error| {}, mean shape {}\n",
                       seeds.front()->label, seeds.size(), field(flap, " Hz"), field(error, "%"),
                       field(shape, " mm"));
  }
  return out;
}

void write_rows(const std::string& path, const std::vector<std::string>& lines) {
  // Whole or not at all: a full disk leaves nothing under the sweep's name (exit 4).
  std::string text = csv_header() + "\n";
  for (const std::string& line : lines) text += line + "\n";
  write_file_whole(path, text);
}

int point_of_line(const std::string& line) {
  return std::stoi(line.substr(0, line.find(',')));
}

// The reference (point 0) run: read from `file` when it is there, else run
// and, with a file named, saved to it for the other points.
RunRecord reference_run(const SweepOptions& o, const std::vector<SweepPoint>& grid,
                        const std::string& file, int seed) {
  std::error_code ec;
  const Scene reference_scene = scene_of(o, grid[0], seed);
  if (!file.empty() && fs::exists(file, ec)) {
    RunRecord saved = load_record(file);
    // A record of another sweep's reference would measure every point against the wrong run.
    if (saved.scene_toml != reference_scene.toml_text)
      throw UserError(fmt::format(
          "--reference-file {}: the reference of another scene or sweep (its scene differs from "
          "this sweep's point 0); remove it or name another file",
          file));
    return saved;
  }
  Progress progress(Progress::wanted(o.quiet), reference_scene.simulated_frames(),
                    o.seeds > 1 ? fmt::format("reference (point 0), seed {}", reference_scene.seed)
                                : std::string("reference (point 0)"));
  RunRecord reference = record_run(reference_scene, &progress);
  if (!file.empty()) save_record(reference, file);
  return reference;
}

// Runs `points` (indices) in this process, each seed against the reference of
// that seed (one reference held at a time); rows by point, then seed.
std::vector<std::string> run_points(const SweepOptions& o, const std::vector<SweepPoint>& grid,
                                    const std::vector<int>& points) {
  const MetricWindow window{o.horizon_s};
  std::map<std::pair<int, int>, std::string> lines;
  for (int seed = 0; seed < o.seeds; ++seed) {
    // Read from the saved file when one is given and there, else run (and saved there).
    const RunRecord reference =
        reference_run(o, grid, reference_file_of(o.reference_file, seed), seed);
    for (int i : points) {
      const Scene scene = scene_of(o, grid[std::size_t(i)], seed);
      const std::string of_seed = o.seeds > 1 ? fmt::format(", seed {}", scene.seed) : "";
      Progress progress(Progress::wanted(o.quiet), scene.simulated_frames(),
                        fmt::format("point {} ({}){}", i, grid[std::size_t(i)].label, of_seed));
      const RunRecord run = i == 0 ? reference : record_run(scene, &progress);
      ReportRow row = describe(scene, run, reference, nullptr, window);
      row.point = i;
      row.label = grid[std::size_t(i)].label;
      lines[{i, seed}] = csv_line(row);
      if (!o.quiet)
        fmt::print(stderr, "point {}: {}{} done, {:.1f} ms/frame\n", i, row.label, of_seed,
                   row.ms_per_frame);
    }
  }
  std::vector<std::string> rows;
  rows.reserve(lines.size());
  for (auto& [key, line] : lines) rows.push_back(std::move(line));
  return rows;
}

// The command line minus what only the parent does (-o, --plot, --jobs, --quiet).
std::vector<std::string> child_arguments(const std::vector<std::string>& argv) {
  std::vector<std::string> args;
  for (std::size_t i = 0; i < argv.size(); ++i) {
    const std::string& a = argv[i];
    if (a == "-o" || a == "--output" || a == "--plot" || a == "--jobs") {
      ++i;  // and its value
      continue;
    }
    if (a.starts_with("--output=") || a.starts_with("--plot=") || a.starts_with("--jobs=") ||
        a == "-q" || a == "--quiet")
      continue;
    args.push_back(a);
  }
  return args;
}

// Runs every point in child processes `flag-sim sweep ... --point I`, `jobs` at
// a time, each reading the reference from `reference_file` (run once, here).
std::vector<std::string> run_children(const std::vector<std::string>& argv, int count, int jobs,
                                      const fs::path& dir, const std::string& reference_file) {
  std::vector<std::string> lines;
  std::map<pid_t, int> running;
  const bool has_reference_file = std::any_of(argv.begin(), argv.end(), [](const std::string& a) {
    return a == "--reference-file" || a.starts_with("--reference-file=");
  });
  int next = 0, failed = -1;
  // SIGINT / SIGTERM to this process (the caller's InterruptGuard): stop
  // starting points, pass SIGTERM on to every worker, wait for them all (none
  // is left orphaned), exit 130.
  auto reap = [&] {
    int status = 0;
    const pid_t pid = waitpid(-1, &status, 0);  // a signal interrupts it (EINTR)
    if (pid <= 0) return;
    const int point = running[pid];
    running.erase(pid);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) failed = point;
  };
  while ((next < count && failed < 0) || !running.empty()) {
    if (InterruptGuard::requested()) {
      const std::size_t stopped = running.size();
      for (const auto& [pid, point] : running) kill(pid, SIGTERM);
      while (!running.empty()) {
        int status = 0;
        const pid_t pid = waitpid(-1, &status, 0);
        if (pid > 0)
          running.erase(pid);
        else if (errno != EINTR)
          break;
      }
      std::error_code ec;
      fs::remove_all(dir, ec);
      throw Interrupted(
          fmt::format("sweep: stopped by a signal after {} of {} points; the {} "
                      "running were stopped, nothing is written",
                      next - int(stopped), count, stopped));
    }
    if (next < count && int(running.size()) < jobs && failed < 0) {
      std::vector<std::string> args = child_arguments(argv);
      args.insert(args.end(), {"--point", std::to_string(next), "-o",
                               (dir / fmt::format("point_{}.csv", next)).string(), "--quiet"});
      if (!has_reference_file) args.insert(args.end(), {"--reference-file", reference_file});
      std::vector<char*> c_args = exec_argv(args);
      pid_t pid = 0;
      if (posix_spawn(&pid, "/proc/self/exe", nullptr, nullptr, c_args.data(), environ) != 0)
        throw IoError("sweep: cannot start a worker process");
      running[pid] = next++;
    } else {
      reap();
    }
  }
  if (failed >= 0)
    throw IoError(
        fmt::format("sweep: point {} failed (run it alone with --point {})", failed, failed));
  for (int i = 0; i < count; ++i) {
    const auto rows = csv_rows((dir / fmt::format("point_{}.csv", i)).string());
    lines.insert(lines.end(), rows.begin(), rows.end());
  }
  return lines;
}

// The arguments that make this sweep's points, for commands run elsewhere
// (Slurm jobs): flag-sim's absolute path, "sweep", the scene and the grid.
std::vector<std::string> point_command(const SweepOptions& o) {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  std::vector<std::string> args = {ec ? std::string("flag-sim") : exe.string(), "sweep"};
  if (!o.scene_path.empty()) args.push_back(fs::absolute(o.scene_path).lexically_normal().string());
  const auto add = [&](const char* flag, const std::string& value) {
    if (!value.empty()) args.insert(args.end(), {flag, value});
  };
  add("--coarse", o.coarse);
  add("--substeps", o.substeps);
  add("--relax", o.relax);
  add("--infill", o.infill);
  add("--backend", o.backend);
  add("--pole-radius", o.pole_radius);
  add("--contact-thickness", o.contact_thickness);
  if (o.frames) add("--frames", std::to_string(*o.frames));
  if (o.seeds > 1) add("--seeds", std::to_string(o.seeds));
  add("--horizon", fmt::format("{}", o.horizon_s));
  for (const std::string& set : o.sets) add("--set", set);
  return args;
}

// The workers' directory OUT.points is the sweep's own, marked by an flock on
// OUT.points/.lock that the sweep and its workers (which inherit the open
// file) hold while any of them lives. The kernel drops it when the last one
// dies, however it died: a directory whose lock can be taken was left by a
// killed sweep and is taken over; one still locked is another live sweep's;
// one without a .lock is not a sweep's at all. Neither of those is touched.
class PointsLock {
 public:
  explicit PointsLock(const fs::path& dir) {
    std::error_code ec;
    const fs::path lock = dir / ".lock";
    if (fs::exists(fs::symlink_status(dir, ec))) {
      const int old = fs::is_directory(fs::symlink_status(dir, ec))
                          ? ::open(lock.c_str(), O_RDWR | O_CLOEXEC | O_NOFOLLOW)
                          : -1;
      if (old < 0)
        throw UserError(fmt::format(
            "{}: exists and is not a sweep's points directory (no .lock); sweep --jobs writes its "
            "points there: remove it or choose another -o",
            printable(dir.string())));
      const bool free = ::flock(old, LOCK_EX | LOCK_NB) == 0;
      if (!free) {
        ::close(old);
        throw UserError(fmt::format(
            "{}: another sweep --jobs is writing its points there now; wait for it or choose "
            "another -o",
            printable(dir.string())));
      }
      // Its sweep is gone: taken over. Moved aside while its lock is held (a
      // second sweep taking it over at the same moment finds it locked), then removed.
      const fs::path aside = dir.string() + fmt::format(".stale.{}", ::getpid());
      fs::rename(dir, aside, ec);
      ::close(old);
      if (ec)
        throw IoError(
            fmt::format("{}: cannot take it over: {}", printable(dir.string()), ec.message()));
      fs::remove_all(aside, ec);
      fmt::print(stderr, "note: {} was left by a sweep that was killed; taken over\n",
                 printable(dir.string()));
    }
    if (!fs::create_directory(dir, ec))  // atomic: of two sweeps, one makes it
      throw UserError(
          fmt::format("{}: cannot create the points directory ({}); another sweep "
                      "may have just made it",
                      printable(dir.string()), ec ? ec.message() : std::string("it exists")));
    // The lock is taken before the file has its name: no other sweep ever sees
    // an unlocked .lock in a live directory. Not close-on-exec: the workers
    // inherit the locked file and hold it with us.
    const fs::path unnamed = dir / fmt::format(".lock.{}", ::getpid());
    fd_ = ::open(unnamed.c_str(), O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW, 0644);
    if (fd_ < 0 || ::flock(fd_, LOCK_EX | LOCK_NB) != 0 ||
        std::rename(unnamed.c_str(), lock.c_str()) != 0)
      throw IoError(fmt::format("{}: cannot lock the points directory", printable(dir.string())));
  }
  ~PointsLock() {
    if (fd_ >= 0) ::close(fd_);
  }
  PointsLock(const PointsLock&) = delete;
  PointsLock& operator=(const PointsLock&) = delete;

 private:
  int fd_ = -1;
};

// --slurm DIR: the sweep as batch jobs (slurm_sweep.hpp), nothing run here.
int slurm_sweep(const SweepOptions& o) {
  if (o.point || o.jobs > 1 || !o.merge.empty())
    throw UserError("--slurm: runs every point as a Slurm job; leave out --point, --jobs, --merge");
  if (!(o.horizon_s > 0.0))
    throw UserError(fmt::format("--horizon {}: expected a duration > 0 s", o.horizon_s));
  const std::vector<SweepPoint> grid = sweep_grid(o);
  for (const SweepPoint& point : grid) scene_of(o, point);  // checked now, not on the cluster
  CreatedDirectories directories;  // removed again if nothing is written there
  check_report_path(o.output, &directories);
  if (!o.plot.empty()) check_report_path(o.plot, &directories);
  FileRoles files;
  files.input(o.scene_path, "the scene");
  files.output(o.output, "the sweep CSV");
  files.output(o.plot, "--plot");
  if (!o.plot.empty()) files.output(partial_image_of(o.plot), "--plot (while drawn)");
  std::vector<std::string> scripts;
  for (const char* name : {"reference.sbatch", "sweep.sbatch", "merge.sbatch"})
    scripts.insert(scripts.end(), {name, std::string(name) + ".partial"});
  files.outputs_in(o.slurm_dir, scripts, "--slurm");
  files.check();
  const std::string csv = fs::absolute(o.output).lexically_normal().string();
  const std::string plot = o.plot.empty() ? "" : fs::absolute(o.plot).lexically_normal().string();
  fmt::print("{}", write_slurm_sweep({o.slurm_dir, o.submit, o.slurm_args, o.seeds},
                                     point_command(o), int(grid.size()), csv, plot));
  return int(ExitCode::kSuccess);
}

}  // namespace

int sweep_command(const SweepOptions& o, const std::vector<std::string>& argv) {
  if (o.seeds < 1 || o.seeds > 64)
    throw UserError(fmt::format("--seeds {}: expected 1 to 64 seeds", o.seeds));
  if (o.list) {  // the points, as --point and the CSV number them; nothing runs
    const std::vector<SweepPoint> grid = sweep_grid(o);
    for (const SweepPoint& point : grid) scene_of(o, point);  // each checked, as a run would
    for (std::size_t i = 0; i < grid.size(); ++i)
      fmt::print("{:>3}  {:<40} {}\n", i, grid[i].label, fmt::join(grid[i].sets, " "));
    return int(ExitCode::kSuccess);
  }
  if (o.output.empty()) throw UserError("sweep: -o SWEEP.csv is required");
  if (o.submit && o.slurm_dir.empty()) throw UserError("--submit: goes with --slurm DIR");
  if (!o.slurm_args.empty() && o.slurm_dir.empty())
    throw UserError("--slurm-arg: goes with --slurm DIR");
  if (o.resume && !o.point) throw UserError("--resume: goes with --point I");
  if (!o.slurm_dir.empty()) return slurm_sweep(o);
  CreatedDirectories directories;  // -o in a new directory: made, and removed if nothing is written
  check_report_path(o.output, &directories);
  if (!o.plot.empty()) {
    check_report_path(o.plot, &directories);
    check_plot_tools("--plot");
  }
  FileRoles files;
  files.input(o.scene_path, "the scene");
  for (const std::string& file : o.merge) files.input(file, "--merge");
  files.output(o.output, "the sweep CSV");
  files.output(o.plot, "--plot");
  if (!o.plot.empty()) files.output(partial_image_of(o.plot), "--plot (while drawn)");
  for (int seed = 0; seed < o.seeds && !o.reference_file.empty(); ++seed) {
    // Read when it is there, written when it is not; a seed's own file after the first.
    const std::string file = reference_file_of(o.reference_file, seed);
    std::error_code ec;
    if (fs::exists(file, ec))
      files.input(file, "--reference-file");
    else
      files.output(file, "--reference-file");
  }
  files.check();
  std::vector<std::string> lines;
  std::string plot_title;  // lattice, frames and duration, when the scene is known here
  if (!o.merge.empty()) {  // join the CSVs of points run separately
    std::map<std::pair<int, std::uint64_t>, std::string> by_point;  // by point, then seed
    for (const std::string& file : o.merge)
      for (const std::string& line : csv_rows(file)) {
        const std::uint64_t seed = parse_csv_line(line).seed;
        if (!by_point.emplace(std::pair{point_of_line(line), seed}, line).second)
          throw UserError(fmt::format("--merge {}: point {} appears twice (seed {})", file,
                                      point_of_line(line), seed));
      }
    for (const auto& [point, line] : by_point) lines.push_back(line);
  } else {
    if (!(o.horizon_s > 0.0))
      throw UserError(fmt::format("--horizon {}: expected a duration > 0 s", o.horizon_s));
    const std::vector<SweepPoint> grid = sweep_grid(o);
    // Every point's scene is checked before anything runs (a coarse lattice
    // that does not divide the fine one is exit 2 now, not an hour in).
    for (const SweepPoint& point : grid) scene_of(o, point);
    {
      const Scene reference = scene_of(o, grid[0]);
      const int frames = reference.simulated_frames();
      plot_title = fmt::format(
          "What accuracy costs: {} x {} dense lattice, {} frames ({:.3g} s at {:.3g} fps), "
          "against the mass-spring reference",
          reference.flag.fine_rows, reference.flag.fine_cols, frames, (frames - 1) / reference.fps,
          reference.fps);
    }
    const int count = int(grid.size());
    if (o.point && (*o.point < 0 || *o.point >= count))
      throw UserError(
          fmt::format("--point {}: this sweep has points 0 to {}", *o.point, count - 1));
    if (o.jobs < 1) throw UserError(fmt::format("--jobs {}: expected at least 1", o.jobs));
    // SIGINT / SIGTERM: the run in progress stops at its next substep (exit
    // 130, nothing written); with --jobs, the workers are stopped too.
    const InterruptGuard interrupt;
    if (o.point && o.resume && sweep_point_done(o.output, *o.point)) {
      if (!o.quiet) fmt::print("sweep: point {} is already in {}\n", *o.point, o.output);
      return int(ExitCode::kSuccess);
    }
    if (o.point) {
      lines = run_points(o, grid, {*o.point});
    } else if (o.jobs > 1) {
      const fs::path dir = fs::path(o.output).string() + ".points";
      std::error_code ec;
      const PointsLock lock(dir);
      // The reference once, before the workers: each reads it instead of re-running it.
      const std::string reference_file =
          o.reference_file.empty() ? (dir / "reference.rec").string() : o.reference_file;
      try {
        for (int seed = 0; seed < o.seeds; ++seed)
          reference_run(o, grid, reference_file_of(reference_file, seed), seed);
      } catch (const Interrupted&) {
        fs::remove_all(dir, ec);
        throw Interrupted(fmt::format(
            "sweep: stopped by a signal while running the reference (point 0); no worker had "
            "started, nothing is written"));
      } catch (...) {
        fs::remove_all(dir, ec);
        throw;
      }
      lines = run_children(argv, count, o.jobs, dir, reference_file);
      fs::remove_all(dir);
    } else {
      std::vector<int> all(static_cast<std::size_t>(count));
      for (int i = 0; i < count; ++i) all[std::size_t(i)] = i;
      lines = run_points(o, grid, all);
    }
  }
  write_rows(o.output, lines);
  if (!o.plot.empty()) {
    std::vector<std::string> args = {o.output, o.plot};
    if (!plot_title.empty()) args.push_back(plot_title);
    draw_plot(sweep_plot_script(), args, 1, o.plot);
  }
  // The table compare prints, for the whole sweep (a single --point prints only its CSV row).
  if (!o.point) {
    std::vector<ReportRow> rows;
    rows.reserve(lines.size());
    for (const std::string& line : lines) rows.push_back(parse_csv_line(line));
    const bool seeded = std::any_of(rows.begin(), rows.end(),
                                    [&](const ReportRow& r) { return r.seed != rows[0].seed; });
    std::vector<ReportRow> shown = rows;
    if (seeded)
      for (ReportRow& r : shown) r.label += fmt::format(" seed {}", r.seed);
    fmt::print("{}", text_table(shown));
    if (seeded) fmt::print("{}", seed_summary(rows));
  }
  if (!o.quiet)
    fmt::print("sweep: {} points -> {}{}\n", lines.size(), o.output,
               o.plot.empty() ? "" : fmt::format(", {}", o.plot));
  return int(ExitCode::kSuccess);
}

}  // namespace flagsim::app
