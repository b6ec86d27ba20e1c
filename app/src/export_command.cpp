// `flag-sim export`: an output file's dense lattice for DCC tools (Blender):
// a PC2 point cache with an OBJ of the topology, one OBJ, or an OBJ per frame.
#include "export_command.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>
#include <optional>

#include "dense_input.hpp"
#include "flagsim/core/errors.hpp"
#include "flagsim/core/stop_request.hpp"
#include "flagsim/data/mesh_export.hpp"
#include "flagsim/data/output_reader.hpp"
#include "flagsim/os/file_roles.hpp"
#include "flagsim/os/staged_file.hpp"
#include "frame_range.hpp"
#include "interrupt.hpp"

namespace flagsim::app {
namespace fs = std::filesystem;
namespace {

enum class ExportKind { kPointCache, kObj, kObjPerFrame };

// Files written under a temporary name and renamed into place only when all
// of them are whole: a failed or interrupted export leaves none of them.
class StagedFiles {
 public:
  std::string stage(const std::string& path) {
    finals_.push_back(path);
    partials_.push_back(path + ".partial");
    return partials_.back();
  }
  void commit() {
    for (std::size_t i = 0; i < finals_.size(); ++i) {
      std::error_code ec;
      fs::rename(partials_[i], finals_[i], ec);
      if (ec)
        throw IoError(
            fmt::format("{}: cannot rename to {}: {}", partials_[i], finals_[i], ec.message()));
    }
    partials_.clear();
  }
  ~StagedFiles() {
    std::error_code ec;
    for (const std::string& partial : partials_) fs::remove(partial, ec);
  }

 private:
  std::vector<std::string> finals_, partials_;
};

void check_interrupt(int done, int total, const std::string& output) {
  if (stop_requested())
    throw Interrupted(
        fmt::format("export to {} stopped by a signal after {} of {} frames", output, done, total));
}

}  // namespace

int export_command(const std::string& h5_path, const ExportOptions& options) {
  const InterruptGuard interrupt;
  const std::string& output = options.output;
  if (output.empty()) throw UserError("export: -o NAME.pc2, NAME.obj or DIR/ is required");
  const fs::path target(output);
  const std::string extension = target.extension().string();
  ExportKind kind;
  std::error_code no_such;  // set when the target does not exist yet
  const bool directory = fs::is_directory(target, no_such);
  if (directory && output.back() != '/' && (extension == ".obj" || extension == ".pc2"))
    throw UserError(fmt::format(
        "-o {}: is a directory; give another name for the {} file, or {}/ (a trailing '/') for "
        "an OBJ per frame in it",
        printable(output), extension, printable(output)));
  if (output.back() == '/' || directory)
    kind = ExportKind::kObjPerFrame;
  else if (extension == ".pc2")
    kind = ExportKind::kPointCache;
  else if (extension == ".obj")
    kind = ExportKind::kObj;
  else
    throw UserError(fmt::format(
        "-o {}: expected NAME.pc2 (a point cache and NAME.obj), NAME.obj (one frame) or a "
        "directory DIR/ (an OBJ per frame)",
        output));
  const std::string obj_path = kind == ExportKind::kPointCache
                                   ? fs::path(target).replace_extension(".obj").string()
                                   : output;
  FileRoles files;
  files.input(h5_path, "the input");
  files.check();  // the input: a regular file, before it is opened
  if (kind != ExportKind::kObjPerFrame) {
    files.output(output, "-o");
    files.output(output + ".partial", "-o (while written)");
    if (kind == ExportKind::kPointCache) {
      files.output(obj_path, "-o (its OBJ)");
      files.output(obj_path + ".partial", "-o (its OBJ, while written)");
    }
  }
  const std::optional<std::pair<int, int>> range =
      options.frames ? std::optional(parse_frame_range(*options.frames)) : std::nullopt;

  const DenseInput dense(h5_path);  // a coarse trajectory's frames refined first
  const data::OutputReader reader(dense.path());
  const int rows = reader.rows(), cols = reader.cols();
  const auto [first, last] =
      resolve_frame_range(range.value_or(kAllFrames), reader.frame_count(), h5_path);
  if (kind == ExportKind::kObjPerFrame) {  // every file it will write, however the names fall
    std::vector<std::string> names;
    for (int t = first; t < last; ++t) {
      names.push_back(fmt::format("frame_{:05d}.obj", t));
      names.push_back(fmt::format("frame_{:05d}.obj.partial", t));
    }
    files.outputs_in(output, names, "-o");
  }
  files.check();
  const int count = kind == ExportKind::kObj ? 1 : last - first;
  const std::string comment =
      fmt::format("flag-sim {} of {}, frame {{}} (t = {{:.6g}} s)", reader.attribute("version"),
                  fs::path(h5_path).filename().string());
  const std::vector<double> times = reader.times_s();
  const auto obj_of = [&](int frame) {
    return data::obj_text(rows, cols, reader.positions(frame),
                          fmt::format(fmt::runtime(comment), frame, times[std::size_t(frame)]));
  };

  CreatedDirectories directories;  // removed again if the export fails before writing into them
  std::error_code ec;
  const fs::path dir = kind == ExportKind::kObjPerFrame ? target : target.parent_path();
  if (!dir.empty()) directories.create(dir.string(), ec);
  const fs::path probe = dir.empty() ? fs::path(".") : dir;
  if (ec || !fs::is_directory(probe) || access(probe.c_str(), W_OK) != 0)
    throw UserError(fmt::format("-o {}: cannot write to {} (check the path and its permissions)",
                                output, probe.string()));
  if (kind != ExportKind::kObjPerFrame && fs::is_directory(target))
    throw UserError(fmt::format("-o {}: is a directory", output));

  std::string written;
  if (kind == ExportKind::kObjPerFrame) {
    // Frames written so far are kept when a signal stops the export (as render's PNGs).
    for (int t = first; t < last; ++t) {
      check_interrupt(t - first, count, output);
      write_file_whole((target / fmt::format("frame_{:05d}.obj", t)).string(), obj_of(t));
    }
    written = fmt::format("{}frame_{:05d}.obj ... frame_{:05d}.obj", (target / "").string(), first,
                          last - 1);
  } else {
    StagedFiles staged;
    if (kind == ExportKind::kPointCache) {
      // Blender's sample rate is frames between samples: the file's frames are consecutive.
      data::Pc2Writer cache(staged.stage(output), rows * cols, count, float(first), 1.0f);
      for (int t = first; t < last; ++t) {
        check_interrupt(t - first, count, output);
        cache.write_sample(reader.positions(t));
      }
      cache.finish();
    }
    StagedFile obj(obj_path);  // checked writes, under OBJ.partial until both are whole
    obj.write(obj_of(first));
    obj.close();  // both whole before either is renamed
    staged.commit();
    obj.commit();
    written = kind == ExportKind::kPointCache ? fmt::format("{} and {}", output, obj_path) : output;
  }
  fmt::print("exported {} frame{} of {} x {} nodes -> {}\n", count, count == 1 ? "" : "s", rows,
             cols, written);
  return int(ExitCode::kSuccess);
}

}  // namespace flagsim::app
