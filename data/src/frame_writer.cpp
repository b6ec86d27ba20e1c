#include "flagsim/data/frame_writer.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "flagsim/core/errors.hpp"
#include "flagsim/data/disk_room.hpp"
#include "flagsim/os/file_roles.hpp"
#include "h5_handle.hpp"

namespace flagsim::data {
namespace fs = std::filesystem;

namespace {

// Growable dataset of `element_type` with shape [T, tail...], chunked one
// frame (or, for small rows, 256 frames) at a time, with its `units` attribute
// (an invalid handle when either cannot be made).
h5::Handle make_series(hid_t parent, const char* name, hid_t element_type,
                       const std::vector<hsize_t>& tail, const char* units, int compression = 0) {
  std::vector<hsize_t> dims{0}, max_dims{H5S_UNLIMITED}, chunk{1};
  hsize_t row = 1;
  for (hsize_t d : tail) {
    dims.push_back(d);
    max_dims.push_back(d);
    chunk.push_back(d);
    row *= d;
  }
  if (row < 64) chunk[0] = 256;
  h5::Handle space =
      h5::dataspace(H5Screate_simple(int(dims.size()), dims.data(), max_dims.data()));
  h5::Handle props = h5::plist(H5Pcreate(H5P_DATASET_CREATE));
  H5Pset_chunk(props.get(), int(chunk.size()), chunk.data());
  if (compression > 0) {  // the bytes of each float regrouped first: deflate finds far more
    H5Pset_shuffle(props.get());
    H5Pset_deflate(props.get(), unsigned(compression));
  }
  H5Pset_obj_track_times(props.get(), false);  // no timestamps: same input, same bytes
  h5::Handle set = h5::dataset(
      H5Dcreate2(parent, name, element_type, space.get(), H5P_DEFAULT, props.get(), H5P_DEFAULT));
  if (set.valid() && !h5::write_string_attribute(set.get(), "units", units)) return {};
  return set;
}

h5::Handle make_group(hid_t parent, const char* name) {
  h5::Handle props = h5::plist(H5Pcreate(H5P_GROUP_CREATE));
  H5Pset_obj_track_times(props.get(), false);
  return h5::group(H5Gcreate2(parent, name, H5P_DEFAULT, props.get(), H5P_DEFAULT));
}

// Appends one row (frame `index`) of `count` elements to a series dataset.
bool append_row(hid_t dataset, hsize_t index, hid_t memory_type, const void* data) {
  h5::Handle space = h5::dataspace(H5Dget_space(dataset));
  const int rank = H5Sget_simple_extent_ndims(space.get());
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  dims[0] = index + 1;
  if (H5Dset_extent(dataset, dims.data()) < 0) return false;
  h5::Handle file_space = h5::dataspace(H5Dget_space(dataset));
  std::vector<hsize_t> start(std::size_t(rank), 0), count = dims;
  start[0] = index;
  count[0] = 1;
  H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(),
                      nullptr);
  h5::Handle memory_space = h5::dataspace(H5Screate_simple(rank, count.data(), nullptr));
  return H5Dwrite(dataset, memory_type, memory_space.get(), file_space.get(), H5P_DEFAULT, data) >=
         0;
}

}  // namespace

// /coarse/rows, /coarse/cols (int32) and the growing /coarse/positions [T, Jc, Kc, 3].
bool write_index_list(hid_t group, const char* name, const std::vector<int>& values) {
  const hsize_t count = values.size();
  h5::Handle space = h5::dataspace(H5Screate_simple(1, &count, nullptr));
  h5::Handle props = h5::plist(H5Pcreate(H5P_DATASET_CREATE));
  H5Pset_obj_track_times(props.get(), false);
  h5::Handle set = h5::dataset(
      H5Dcreate2(group, name, H5T_STD_I32LE, space.get(), H5P_DEFAULT, props.get(), H5P_DEFAULT));
  return set.valid() && h5::write_string_attribute(set.get(), "units", "1") &&
         H5Dwrite(set.get(), H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) >= 0;
}

struct FrameWriter::Impl {
  CreatedDirectories directories;  // the output's missing parents: gone again if left empty
  h5::Handle file;
  h5::Handle time, positions, velocity, strain, max_strain, mean_strain, stage_seconds,
      wall_seconds, kinetic;
  h5::Handle coarse_positions, trajectory, memory;
  std::size_t memory_size = 0;  ///< RunInfo::coarse_memory_size, when /coarse/memory is made
  std::vector<h5::Handle> series;
  std::vector<std::string> series_names;              ///< RunInfo::series' names, as `series`
  h5::Handle checkpoint;                              ///< /checkpoint, once written
  std::vector<float> position_buffer, coarse_buffer;  ///< float32 xyz, as stored
  std::vector<double> times;
  std::vector<std::string> fields;  ///< RunInfo::fields
  std::size_t stage_count = 0;
  int output_stage = -1;
};

FrameWriter::FrameWriter(std::string path, const Lattice& lattice, const RunInfo& info,
                         int flush_every)
    : impl_(std::make_unique<Impl>()),
      path_(std::move(path)),
      lattice_(lattice),
      flush_every_(flush_every) {
  h5::silence_library_errors();
  const fs::path target(path_);
  std::error_code ec;
  if (target.has_parent_path()) impl_->directories.create(target.parent_path().string(), ec);
  if (fs::is_directory(target, ec))
    throw UserError(fmt::format("{}: is a directory; give an output file name such as {}", path_,
                                (target / "run.h5").lexically_normal().string()));
  const std::string partial = partial_path();
  // A .partial left by a killed run is replaced; one that another run is
  // writing (HDF5 holds an exclusive lock on a file it writes) is not touched.
  if (const int fd = ::open(partial.c_str(), O_RDONLY | O_CLOEXEC); fd >= 0) {
    const bool locked = ::flock(fd, LOCK_EX | LOCK_NB) != 0 && errno == EWOULDBLOCK;
    ::close(fd);
    if (locked)
      throw UserError(fmt::format(
          "{}: being written by another run ({} is locked); wait for it or choose another -o",
          path_, partial));
  }
  fs::remove(partial, ec);
  h5::Handle create = h5::plist(H5Pcreate(H5P_FILE_CREATE));
  H5Pset_obj_track_times(create.get(), false);
  impl_->file = h5::file(H5Fcreate(partial.c_str(), H5F_ACC_TRUNC, create.get(), H5P_DEFAULT));
  if (!impl_->file.valid()) {
    fs::remove(partial, ec);  // HDF5 may have made it before failing
    const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
    if (fs::is_directory(dir, ec) && ::access(dir.c_str(), W_OK) == 0)  // then: no room
      throw IoError(fmt::format(
          "{}: cannot create the output file (the disk or the file size limit leaves no "
          "room); nothing was written",
          path_));
    throw UserError(
        fmt::format("{}: cannot create the output file (is the directory writable?)", path_));
  }

  const hid_t root = impl_->file.get();
  bool ok =
      h5::write_string_attribute(root, "format", kFormat) &&
      h5::write_string_attribute(root, "status", std::string(to_string(RunState::kRunning))) &&
      h5::write_string_attribute(root, "mode", info.mode) &&
      h5::write_string_attribute(root, "effects",
                                 fmt::format("{}", fmt::join(info.effects, ","))) &&
      h5::write_string_attribute(root, "scene", info.scene_toml) &&
      h5::write_string_attribute(root, "version", info.version) &&
      h5::write_int_attribute(root, "seed", (long long)info.seed) &&
      h5::write_string_attribute(root, "seed.units", "1");
  for (const NamedNumber& number : info.numbers)
    ok = ok &&
         (number.integer ? h5::write_int_attribute(root, number.name.c_str(),
                                                   (long long)std::llround(number.value))
                         : h5::write_double_attribute(root, number.name.c_str(), number.value)) &&
         h5::write_string_attribute(root, (number.name + ".units").c_str(), number.units);

  const hsize_t rows = hsize_t(lattice.rows), cols = hsize_t(lattice.cols);
  const int level = info.compression;
  h5::Handle frames = make_group(root, "frames");
  h5::Handle stats = make_group(root, "stats");
  h5::Handle lattice_group = make_group(root, "lattice");
  impl_->time = make_series(frames.get(), "time", H5T_IEEE_F64LE, {}, "s");
  if (info.dense)
    impl_->positions =
        make_series(frames.get(), "positions", H5T_IEEE_F32LE, {rows, cols, 3}, "m", level);
  else
    ok = ok && h5::write_int_attribute(root, "dense", 0);
  const auto wants = [&info](const char* field) {
    return info.dense &&
           std::find(info.fields.begin(), info.fields.end(), field) != info.fields.end();
  };
  if (info.dense) impl_->fields = info.fields;
  if (wants("velocity"))
    impl_->velocity =
        make_series(frames.get(), "velocity", H5T_IEEE_F32LE, {rows, cols, 3}, "m/s", level);
  if (wants("strain"))
    impl_->strain = make_series(frames.get(), "strain", H5T_IEEE_F32LE, {rows, cols}, "1", level);
  impl_->max_strain = make_series(stats.get(), "max_strain", H5T_IEEE_F32LE, {}, "1");
  impl_->mean_strain = make_series(stats.get(), "mean_strain", H5T_IEEE_F32LE, {}, "1");
  impl_->stage_count = info.stages.size();
  impl_->output_stage = info.output_stage;
  impl_->stage_seconds =
      make_series(stats.get(), "stage_seconds", H5T_IEEE_F64LE, {impl_->stage_count}, "s");
  impl_->wall_seconds = make_series(stats.get(), "wall_seconds", H5T_IEEE_F64LE, {}, "s");
  impl_->kinetic = make_series(stats.get(), "kinetic_energy", H5T_IEEE_F64LE, {}, "J");
  ok = ok && h5::write_string_list_attribute(impl_->stage_seconds.get(), "stages", info.stages);
  for (const RunInfo::Series& series : info.series) {
    impl_->series.push_back(
        make_series(stats.get(), series.name.c_str(), H5T_IEEE_F64LE, {}, series.units.c_str()));
    impl_->series_names.push_back(series.name);
    ok = ok && impl_->series.back().valid();
  }
  if (!info.coarse_rows.empty()) ok = ok && write_coarse_layout(root, info);
  if (!info.dense && info.coarse_rows.empty())
    throw std::invalid_argument("FrameWriter: a file without dense frames needs the coarse layout");

  // /lattice/rest_positions [J, K, 3] float32
  const hsize_t rest_dims[3] = {rows, cols, 3};
  h5::Handle rest_space = h5::dataspace(H5Screate_simple(3, rest_dims, nullptr));
  h5::Handle rest_props = h5::plist(H5Pcreate(H5P_DATASET_CREATE));
  H5Pset_obj_track_times(rest_props.get(), false);
  h5::Handle rest =
      h5::dataset(H5Dcreate2(lattice_group.get(), "rest_positions", H5T_IEEE_F32LE,
                             rest_space.get(), H5P_DEFAULT, rest_props.get(), H5P_DEFAULT));
  std::vector<float>& buffer = impl_->position_buffer;
  buffer.resize(lattice.node_count() * 3);
  const std::vector<Vec3> rest_positions = lattice.rest_positions();
  for (std::size_t i = 0; i < rest_positions.size(); ++i)
    for (int c = 0; c < 3; ++c) buffer[3 * i + c] = float(rest_positions[i][c]);
  ok = ok && rest.valid() && h5::write_string_attribute(rest.get(), "units", "m") &&
       H5Dwrite(rest.get(), H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()) >= 0;
  ok = ok && impl_->time.valid() && (impl_->positions.valid() || !info.dense) &&
       (impl_->velocity.valid() || !wants("velocity")) &&
       (impl_->strain.valid() || !wants("strain")) && impl_->max_strain.valid() &&
       impl_->mean_strain.valid() && impl_->stage_seconds.valid() && impl_->wall_seconds.valid() &&
       impl_->kinetic.valid() && H5Fflush(root, H5F_SCOPE_GLOBAL) >= 0;
  if (!ok) {  // the directory was writable a moment ago: the disk is full or the size limited
    impl_.reset();
    fs::remove(partial, ec);
    throw IoError(fmt::format(
        "{}: cannot write the output file's header (no room on the disk or under the file size "
        "limit); nothing was written",
        path_));
  }
}

bool FrameWriter::write_coarse_layout(hid_t root, const RunInfo& info) {
  h5::Handle coarse = make_group(root, "coarse");
  const hsize_t rows = info.coarse_rows.size(), cols = info.coarse_cols.size();
  impl_->coarse_positions = make_series(coarse.get(), "positions", H5T_IEEE_F32LE, {rows, cols, 3},
                                        "m", info.compression);
  impl_->coarse_buffer.assign(rows * cols * 3, 0.0f);
  if (!info.dense) {
    impl_->trajectory = make_series(coarse.get(), "trajectory", H5T_IEEE_F64LE, {rows, cols, 3},
                                    "m", info.compression);
    if (!impl_->trajectory.valid() ||
        !h5::write_string_attribute(
            impl_->trajectory.get(), "meaning",
            "the coarse nodes the infill took at every simulated frame n (t = n / fps), "
            "output.every or not; `flag-sim refine` fills the dense frames from them"))
      return false;
    if (info.coarse_memory_size > 0) {
      impl_->memory_size = info.coarse_memory_size;
      impl_->memory = make_series(coarse.get(), "memory", H5T_IEEE_F64LE,
                                  {hsize_t(info.coarse_memory_size)}, "1", info.compression);
      if (!impl_->memory.valid() ||
          !h5::write_string_attribute(
              impl_->memory.get(), "meaning",
              "what the coarse physics remembered at every simulated frame of "
              "/coarse/trajectory (the creases' rest and held angles, rad: ClothState::memory); "
              "`flag-sim refine` draws the creases from it"))
        return false;
    }
  }
  return impl_->coarse_positions.valid() &&
         write_index_list(coarse.get(), "rows", info.coarse_rows) &&
         write_index_list(coarse.get(), "cols", info.coarse_cols);
}

FrameWriter::~FrameWriter() = default;  // an unfinished run leaves its .partial file

void FrameWriter::discard() noexcept {
  const CreatedDirectories directories = std::move(impl_->directories);
  impl_.reset();  // closes every dataset and the file
  std::error_code ec;
  fs::remove(partial_path(), ec);
}  // the directories made for it go too, now empty

namespace {

// Vectors as float32 xyz, the layout of /frames/positions and /frames/velocity.
void to_float_xyz(std::span<const Vec3> vectors, std::vector<float>& buffer) {
  buffer.resize(3 * vectors.size());
  for (std::size_t i = 0; i < vectors.size(); ++i)
    for (int c = 0; c < 3; ++c) buffer[3 * i + c] = float(vectors[i][c]);
}

}  // namespace

void FrameWriter::write_frame(double time_s, const FrameFields& fields, const FrameStats& stats) {
  const auto start = std::chrono::steady_clock::now();
  const std::size_t nodes = lattice_.node_count();
  const bool velocity = impl_->velocity.valid(), strain = impl_->strain.valid();
  const bool dense = impl_->positions.valid();
  if ((dense && fields.positions_m.size() != nodes) ||
      (velocity && fields.velocities_m_s.size() != nodes) ||
      (strain && fields.strain.size() != nodes))
    throw std::invalid_argument(fmt::format(
        "FrameWriter::write_frame: {} positions, {} velocities, {} strains for {} nodes",
        fields.positions_m.size(), fields.velocities_m_s.size(), fields.strain.size(), nodes));
  const hsize_t index = hsize_t(frames_);
  bool ok = true;
  if (impl_->coarse_positions.valid()) {
    if (fields.coarse_m.size() * 3 != impl_->coarse_buffer.size())
      throw std::invalid_argument(fmt::format("FrameWriter::write_frame: {} coarse nodes for {}",
                                              fields.coarse_m.size(),
                                              impl_->coarse_buffer.size() / 3));
    to_float_xyz(fields.coarse_m, impl_->coarse_buffer);
    ok = append_row(impl_->coarse_positions.get(), index, H5T_NATIVE_FLOAT,
                    impl_->coarse_buffer.data());
  }
  std::vector<float>& buffer = impl_->position_buffer;
  ok = ok && append_row(impl_->time.get(), index, H5T_NATIVE_DOUBLE, &time_s);
  if (dense) {
    to_float_xyz(fields.positions_m, buffer);
    ok = ok && append_row(impl_->positions.get(), index, H5T_NATIVE_FLOAT, buffer.data());
  }
  if (velocity) {
    to_float_xyz(fields.velocities_m_s, buffer);
    ok = ok && append_row(impl_->velocity.get(), index, H5T_NATIVE_FLOAT, buffer.data());
  }
  if (strain)
    ok = ok && append_row(impl_->strain.get(), index, H5T_NATIVE_FLOAT, fields.strain.data());
  std::vector<double> stage_row(stats.stage_seconds.begin(), stats.stage_seconds.end());
  stage_row.resize(impl_->stage_count, 0.0);
  const double write_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (impl_->output_stage >= 0 && std::size_t(impl_->output_stage) < stage_row.size())
    stage_row[std::size_t(impl_->output_stage)] += write_s;
  const float max_strain = float(stats.max_strain), mean_strain = float(stats.mean_strain);
  const double wall_s = stats.wall_seconds + write_s;
  ok = ok && append_row(impl_->max_strain.get(), index, H5T_NATIVE_FLOAT, &max_strain) &&
       append_row(impl_->mean_strain.get(), index, H5T_NATIVE_FLOAT, &mean_strain) &&
       (impl_->stage_count == 0 ||
        append_row(impl_->stage_seconds.get(), index, H5T_NATIVE_DOUBLE, stage_row.data())) &&
       append_row(impl_->wall_seconds.get(), index, H5T_NATIVE_DOUBLE, &wall_s) &&
       append_row(impl_->kinetic.get(), index, H5T_NATIVE_DOUBLE, &stats.kinetic_energy_j);
  for (std::size_t i = 0; i < impl_->series.size(); ++i) {
    const double value = i < stats.series.size() ? stats.series[i] : 0.0;
    ok = ok && append_row(impl_->series[i].get(), index, H5T_NATIVE_DOUBLE, &value);
  }
  if (!ok)
    throw IoError(fmt::format("{}: writing frame {} failed (disk full?)", partial_path(), frames_));
  if (frames_ > 0) wall_after_first_s_ += wall_s;  // as info averages it
  ++frames_;
  impl_->times.push_back(time_s);
  if (frames_ % flush_every_ == 0 && H5Fflush(impl_->file.get(), H5F_SCOPE_GLOBAL) < 0)
    throw IoError(fmt::format("{}: flushing to disk failed (disk full?)", partial_path()));
}

void FrameWriter::append_trajectory(std::span<const Vec3> coarse_m,
                                    std::span<const double> memory) {
  if (!impl_->trajectory.valid() || coarse_m.size() * 3 != impl_->coarse_buffer.size())
    throw std::invalid_argument(
        fmt::format("FrameWriter::append_trajectory: {} coarse nodes for {}, in a file {} dense",
                    coarse_m.size(), impl_->coarse_buffer.size() / 3,
                    impl_->trajectory.valid() ? "not" : "that is"));
  if (memory.size() != impl_->memory_size)
    throw std::invalid_argument(
        fmt::format("FrameWriter::append_trajectory: {} remembered values for the {} the file "
                    "was made with (RunInfo::coarse_memory_size)",
                    memory.size(), impl_->memory_size));
  static_assert(sizeof(Vec3) == 3 * sizeof(double));
  const bool written =
      append_row(impl_->trajectory.get(), hsize_t(trajectory_frames_), H5T_NATIVE_DOUBLE,
                 coarse_m.front().data()) &&
      (!impl_->memory.valid() || append_row(impl_->memory.get(), hsize_t(trajectory_frames_),
                                            H5T_NATIVE_DOUBLE, memory.data()));
  if (!written)
    throw IoError(fmt::format("{}: writing the coarse trajectory's frame {} failed (disk full?)",
                              partial_path(), trajectory_frames_));
  ++trajectory_frames_;
}

std::optional<std::string> FrameWriter::out_of_room() const {
  // positions and velocities (float32 xyz), strain (float32); or the trajectory's float64 xyz
  const std::uintmax_t node_bytes = (impl_->positions.valid() ? 12 : 0) +
                                    (impl_->velocity.valid() ? 12 : 0) +
                                    (impl_->strain.valid() ? 4 : 0);
  const std::uintmax_t frame_bytes =
      std::uintmax_t(lattice_.node_count()) * node_bytes + impl_->coarse_buffer.size() * 4 +
      (impl_->trajectory.valid() ? impl_->coarse_buffer.size() * 8 + impl_->memory_size * 8 : 0) +
      impl_->stage_count * 8 + 64;
  const std::uintmax_t pending = std::uintmax_t(frames_ % flush_every_) + 1;
  const std::uintmax_t need = 2 * pending * frame_bytes + (std::uintmax_t(1) << 20);
  return no_room_for(partial_path(), need);
}

void FrameWriter::write_checkpoint(const Checkpoint& checkpoint) {
  const hid_t root = impl_->file.get();
  bool ok = true;
  if (!impl_->checkpoint.valid()) {
    impl_->checkpoint = make_group(root, "checkpoint");
    ok = impl_->checkpoint.valid() &&
         h5::write_string_attribute(
             impl_->checkpoint.get(), "meaning",
             "the simulation's state after frame `frame`, float64 as it held it: what `flag-sim "
             "run --resume` continues from");
  }
  const hid_t group = impl_->checkpoint.get();
  for (const Checkpoint::Part& part : checkpoint.parts) {
    if (!ok) break;
    const std::span<const double> values = part.values();
    const hsize_t count = values.size();
    h5::Handle set;
    if (H5Lexists(group, part.name.c_str(), H5P_DEFAULT) > 0) {
      set = h5::dataset(H5Dopen2(group, part.name.c_str(), H5P_DEFAULT));
      h5::Handle space = h5::dataspace(H5Dget_space(set.get()));
      if (hsize_t(H5Sget_simple_extent_npoints(space.get())) != count) {
        set.reset();
        ok = H5Ldelete(group, part.name.c_str(), H5P_DEFAULT) >= 0;
      }
    }
    if (ok && !set.valid()) {
      h5::Handle space = h5::dataspace(H5Screate_simple(1, &count, nullptr));
      h5::Handle props = h5::plist(H5Pcreate(H5P_DATASET_CREATE));
      H5Pset_obj_track_times(props.get(), false);
      set = h5::dataset(H5Dcreate2(group, part.name.c_str(), H5T_IEEE_F64LE, space.get(),
                                   H5P_DEFAULT, props.get(), H5P_DEFAULT));
      ok = set.valid() && h5::write_string_attribute(set.get(), "units", part.units);
    }
    if (ok && count > 0)
      ok =
          H5Dwrite(set.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) >= 0;
    ok = ok && h5::write_int_attribute(set.get(), "checksum",
                                       static_cast<long long>(checkpoint_checksum(values)));
  }
  ok = ok && h5::write_int_attribute(group, "frame", checkpoint.frame) &&
       h5::write_int_attribute(group, "written_frames", checkpoint.written_frames) &&
       h5::write_int_attribute(group, "trajectory_frames", checkpoint.trajectory_frames);
  if (!ok)
    throw IoError(fmt::format("{}: writing the checkpoint of frame {} failed (disk full?)",
                              partial_path(), checkpoint.frame));
}

namespace {

// Appends rows [0, rows) of `path` in `source` to `target`, byte for byte;
// the reason in `why` when the source has no such dataset or another shape or type.
bool copy_rows(hid_t source, const std::string& path, hid_t target, hsize_t rows, std::string& why,
               bool& write_failed) {
  if (H5Lexists(source, path.substr(0, path.find('/')).c_str(), H5P_DEFAULT) <= 0 ||
      H5Lexists(source, path.c_str(), H5P_DEFAULT) <= 0) {
    why = fmt::format("has no /{}", path);
    return false;
  }
  h5::Handle from = h5::dataset(H5Dopen2(source, path.c_str(), H5P_DEFAULT));
  h5::Handle from_space = h5::dataspace(H5Dget_space(from.get()));
  h5::Handle to_space = h5::dataspace(H5Dget_space(target));
  h5::Handle from_type = h5::datatype(H5Dget_type(from.get()));
  h5::Handle type = h5::datatype(H5Dget_type(target));
  const int rank = H5Sget_simple_extent_ndims(to_space.get());
  std::vector<hsize_t> from_dims(std::size_t(std::max(rank, 1))), to_dims = from_dims;
  bool same = from.valid() && H5Sget_simple_extent_ndims(from_space.get()) == rank &&
              H5Tequal(from_type.get(), type.get()) > 0;
  if (same) {
    H5Sget_simple_extent_dims(from_space.get(), from_dims.data(), nullptr);
    H5Sget_simple_extent_dims(to_space.get(), to_dims.data(), nullptr);
    same = std::equal(from_dims.begin() + 1, from_dims.end(), to_dims.begin() + 1) &&
           from_dims[0] >= rows;
  }
  if (!same) {
    why = fmt::format("holds /{} in another shape or type than this run writes", path);
    return false;
  }
  std::size_t row_bytes = H5Tget_size(type.get());
  for (int d = 1; d < rank; ++d) row_bytes *= std::size_t(to_dims[std::size_t(d)]);
  std::vector<unsigned char> row(row_bytes);
  std::vector<hsize_t> start(std::size_t(rank), 0), count = from_dims;
  count[0] = 1;
  h5::Handle memory = h5::dataspace(H5Screate_simple(rank, count.data(), nullptr));
  for (hsize_t r = 0; r < rows; ++r) {
    start[0] = r;
    H5Sselect_hyperslab(from_space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(),
                        nullptr);
    if (H5Dread(from.get(), type.get(), memory.get(), from_space.get(), H5P_DEFAULT, row.data()) <
        0) {
      why = fmt::format("cannot read row {} of /{}", r, path);
      return false;
    }
    if (!append_row(target, r, type.get(), row.data())) {
      write_failed = true;
      return false;
    }
  }
  return true;
}

}  // namespace

void FrameWriter::copy_frames(const std::string& source, int frames, int trajectory_frames) {
  h5::Handle from = h5::file(H5Fopen(source.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
  if (!from.valid()) throw UserError(fmt::format("{}: cannot open to copy its frames", source));
  std::vector<std::pair<hid_t, std::string>> sets = {
      {impl_->time.get(), "frames/time"},
      {impl_->positions.get(), "frames/positions"},
      {impl_->velocity.get(), "frames/velocity"},
      {impl_->strain.get(), "frames/strain"},
      {impl_->coarse_positions.get(), "coarse/positions"},
      {impl_->max_strain.get(), "stats/max_strain"},
      {impl_->mean_strain.get(), "stats/mean_strain"},
      {impl_->stage_count > 0 ? impl_->stage_seconds.get() : -1, "stats/stage_seconds"},
      {impl_->wall_seconds.get(), "stats/wall_seconds"},
      {impl_->kinetic.get(), "stats/kinetic_energy"}};
  for (std::size_t i = 0; i < impl_->series.size(); ++i)
    sets.emplace_back(impl_->series[i].get(), "stats/" + impl_->series_names[i]);
  std::string why;
  bool write_failed = false;
  for (const auto& [set, path] : sets)
    if (set >= 0 && !copy_rows(from.get(), path, set, hsize_t(frames), why, write_failed)) break;
  if (why.empty() && !write_failed && impl_->trajectory.valid())
    copy_rows(from.get(), "coarse/trajectory", impl_->trajectory.get(), hsize_t(trajectory_frames),
              why, write_failed);
  if (why.empty() && !write_failed && impl_->memory.valid())
    copy_rows(from.get(), "coarse/memory", impl_->memory.get(), hsize_t(trajectory_frames), why,
              write_failed);
  if (write_failed)
    throw IoError(
        fmt::format("{}: copying the frames of {} failed (disk full?)", partial_path(), source));
  if (!why.empty()) throw UserError(fmt::format("{}: {}", source, why));
  // What the writer keeps of the frames it wrote itself.
  std::vector<double> values(std::size_t(frames), 0.0);
  const auto read_all = [&](hid_t set) {
    if (frames == 0) return true;
    return H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) >= 0;
  };
  if (!read_all(impl_->time.get()))
    throw IoError(fmt::format("{}: cannot read back /frames/time", partial_path()));
  impl_->times = values;
  if (!read_all(impl_->wall_seconds.get()))
    throw IoError(fmt::format("{}: cannot read back /stats/wall_seconds", partial_path()));
  wall_after_first_s_ = 0.0;
  for (std::size_t i = 1; i < values.size(); ++i) wall_after_first_s_ += values[i];
  frames_ = frames;
  trajectory_frames_ = impl_->trajectory.valid() ? trajectory_frames : 0;
}

void FrameWriter::finish(const RunStatus& status) {
  const hid_t root = impl_->file.get();
  bool ok = h5::write_string_attribute(root, "status", std::string(to_string(status.state)));
  if (!status.reason.empty())
    ok = ok && h5::write_string_attribute(root, "status_reason", status.reason);
  const bool dense = impl_->positions.valid();  // else no frames for ParaView to show
  ok = ok && (!dense || write_xdmf_views(root, lattice_, impl_->times.size(), impl_->fields)) &&
       H5Fflush(root, H5F_SCOPE_GLOBAL) >= 0;
  const std::vector<double> times = std::move(impl_->times);
  const std::vector<std::string> fields = std::move(impl_->fields);
  impl_.reset();  // closes every dataset and the file
  if (!ok) throw IoError(fmt::format("{}: finishing the output file failed", partial_path()));
  std::error_code ec;
  fs::rename(partial_path(), path_, ec);
  if (ec)
    throw IoError(fmt::format("{}: cannot rename to {}: {}", partial_path(), path_, ec.message()));

  fs::path sidecar(path_);
  sidecar.replace_extension(".xdmf");
  if (!dense) {  // a sidecar left by an earlier run of this output would name frames not here
    fs::remove(sidecar, ec);
    return;
  }
  std::ofstream xdmf(sidecar);
  xdmf << xdmf_text(fs::path(path_).filename().string(), lattice_, times, fields);
  if (!xdmf) throw IoError(fmt::format("{}: cannot write the XDMF sidecar", sidecar.string()));
}

}  // namespace flagsim::data
