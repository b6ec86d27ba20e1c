#include "flagsim/data/output_reader.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "file_walk.hpp"
#include "flagsim/core/errors.hpp"
#include "flagsim/core/limits.hpp"
#include "flagsim/data/frame_writer.hpp"
#include "flagsim/data/isolated_read.hpp"
#include "h5_handle.hpp"

namespace flagsim::data {

struct OutputReader::Impl {
  h5::Handle file;
};

namespace {

// Reads a whole numeric dataset as double; empty if missing. A dataset that
// declares more than `at_most` values is refused before anything is
// allocated: a file's declared shape is not trusted (a 55 KB file can declare
// [1, 2^31, 1, 3]).
std::vector<double> read_all(hid_t file, const std::string& file_path, const char* path,
                             hsize_t at_most, std::vector<hsize_t>* dims_out = nullptr) {
  if (H5Lexists(file, path, H5P_DEFAULT) <= 0) return {};
  h5::Handle set = h5::dataset(H5Dopen2(file, path, H5P_DEFAULT));
  h5::Handle space = h5::dataspace(H5Dget_space(set.get()));
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0 || rank > 4)
    throw UserError(
        fmt::format("{}: {} has rank {}: not an output flag-sim wrote", file_path, path, rank));
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank), 0);
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  hsize_t count = 1;
  for (hsize_t d : dims) count = d != 0 && count > at_most / d ? at_most + 1 : count * d;
  if (count > at_most)
    throw UserError(
        fmt::format("{}: {} declares more than the {} values its /frames/positions "
                    "allows: not an output flag-sim wrote",
                    file_path, path, at_most));
  std::vector<double> values(count);
  if (count > 0 &&
      H5Dread(set.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0)
    throw UserError(
        fmt::format("{}: cannot read {} (truncated or damaged file?)", file_path, path));
  if (dims_out) *dims_out = dims;
  return values;
}

std::vector<Vec3> to_vec3(const std::vector<double>& flat) {
  std::vector<Vec3> result(flat.size() / 3);
  for (std::size_t i = 0; i < result.size(); ++i)
    result[i] = Vec3(flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]);
  return result;
}

}  // namespace

OutputReader::OutputReader(const std::string& path) : impl_(std::make_unique<Impl>()), path_(path) {
  h5::silence_library_errors();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw UserError(fmt::format("{}: no such file", path));
  if (H5Fis_hdf5(path.c_str()) <= 0)
    throw UserError(fmt::format("{}: not an HDF5 file (expected a flag-sim output .h5)", path));
  // The reads below, and those the commands make next, first in a child
  // (isolated_read.hpp): a file that crashes HDF5 is refused, not a crash here.
  if (isolated_reads() && !in_isolated_child())
    run_isolated(path, [&path] {
      const OutputReader reader(path);
      reader.read_what_commands_read();
      walk_hdf5_file(path);
      return std::string();
    });
  impl_->file = h5::file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
  if (!impl_->file.valid())
    throw UserError(
        fmt::format("{}: cannot open the HDF5 file (is it still being written?)", path));
  std::string format;
  if (!h5::read_string_attribute(impl_->file.get(), "format", format) || format != kFormat)
    throw UserError(
        fmt::format("{}: not a flag-sim output (root attribute format is \"{}\", "
                    "expected \"{}\")",
                    path, format, kFormat));
  const hid_t file = impl_->file.get();
  if (H5Lexists(file, "/frames", H5P_DEFAULT) <= 0)
    throw UserError(fmt::format("{}: flag-sim file without /frames", path));
  if (H5Lexists(file, "/frames/positions", H5P_DEFAULT) <= 0) {
    // [output] dense = false: the coarse trajectory in place of the dense frames.
    if (number_attribute("dense", 1.0) != 0.0 || H5Lexists(file, "/coarse", H5P_DEFAULT) <= 0 ||
        H5Lexists(file, "/coarse/trajectory", H5P_DEFAULT) <= 0)
      throw UserError(fmt::format("{}: flag-sim file without /frames/positions", path));
    open_coarse_only();
    return;
  }
  h5::Handle set = h5::dataset(H5Dopen2(file, "/frames/positions", H5P_DEFAULT));
  h5::Handle space = h5::dataspace(H5Dget_space(set.get()));
  hsize_t dims[4] = {0, 0, 0, 0};
  if (H5Sget_simple_extent_ndims(space.get()) != 4 ||
      H5Sget_simple_extent_dims(space.get(), dims, nullptr) < 0 || dims[3] != 3)
    throw UserError(fmt::format("{}: /frames/positions is not [T, J, K, 3]", path));
  // The declared shape against what a scene can make and what the file holds.
  if (dims[1] < 2 || dims[2] < 2 || dims[1] > hsize_t(limits::kLatticeSide) ||
      dims[2] > hsize_t(limits::kLatticeSide) ||
      dims[1] * dims[2] > hsize_t(limits::kLatticeNodes) || dims[0] > hsize_t(limits::kFrames))
    throw UserError(fmt::format(
        "{}: /frames/positions declares {} frames of {} x {} nodes, more than a flag-sim scene "
        "can make (sides 2 to {}, at most {} nodes, {} frames)",
        path, dims[0], dims[1], dims[2], limits::kLatticeSide, limits::kLatticeNodes,
        limits::kFrames));
  h5::Handle type = h5::datatype(H5Dget_type(set.get()));
  const hsize_t declared = dims[0] * dims[1] * dims[2] * 3 * H5Tget_size(type.get());
  // A compressed dataset ([output] compression) stores fewer bytes than it holds.
  h5::Handle layout = h5::plist(H5Dget_create_plist(set.get()));
  const bool filtered = layout.valid() && H5Pget_nfilters(layout.get()) > 0;
  if (!filtered && H5Dget_storage_size(set.get()) < declared)
    throw UserError(fmt::format(
        "{}: /frames/positions declares {} frames of {} x {} nodes ({} bytes) but stores {}: "
        "truncated, or not an output flag-sim wrote",
        path, dims[0], dims[1], dims[2], declared, H5Dget_storage_size(set.get())));
  frames_ = int(dims[0]);
  rows_ = int(dims[1]);
  cols_ = int(dims[2]);
}

OutputReader::~OutputReader() = default;

void OutputReader::open_coarse_only() {
  const hid_t file = impl_->file.get();
  dense_ = false;
  // The dense lattice's shape from its rest positions, the frames from their times.
  const auto shape_of = [&](const char* name, int rank, hsize_t* dims) {
    if (H5Lexists(file, name, H5P_DEFAULT) <= 0) return false;
    h5::Handle set = h5::dataset(H5Dopen2(file, name, H5P_DEFAULT));
    h5::Handle space = h5::dataspace(H5Dget_space(set.get()));
    return H5Sget_simple_extent_ndims(space.get()) == rank &&
           H5Sget_simple_extent_dims(space.get(), dims, nullptr) >= 0;
  };
  hsize_t rest[3] = {0, 0, 0}, time[1] = {0}, trajectory[4] = {0, 0, 0, 0};
  if (!shape_of("/lattice/rest_positions", 3, rest) || rest[2] != 3 ||
      !shape_of("/frames/time", 1, time) || !shape_of("/coarse/trajectory", 4, trajectory) ||
      trajectory[3] != 3)
    throw UserError(fmt::format(
        "{}: a coarse-trajectory file (dense = 0) needs /lattice/rest_positions [J, K, 3], "
        "/frames/time [T] and /coarse/trajectory [S, Jc, Kc, 3]",
        path_));
  if (rest[0] < 2 || rest[1] < 2 || rest[0] > hsize_t(limits::kLatticeSide) ||
      rest[1] > hsize_t(limits::kLatticeSide) ||
      rest[0] * rest[1] > hsize_t(limits::kLatticeNodes) || time[0] > hsize_t(limits::kFrames) ||
      trajectory[0] > hsize_t(limits::kFrames) || trajectory[1] < 2 || trajectory[2] < 2 ||
      trajectory[1] > rest[0] || trajectory[2] > rest[1])
    throw UserError(fmt::format(
        "{}: declares {} frames of {} x {} nodes and a coarse trajectory of {} frames of {} x {}, "
        "more than a flag-sim scene can make",
        path_, time[0], rest[0], rest[1], trajectory[0], trajectory[1], trajectory[2]));
  frames_ = int(time[0]);
  rows_ = int(rest[0]);
  cols_ = int(rest[1]);
  trajectory_frames_ = int(trajectory[0]);
}

void OutputReader::read_what_commands_read() const {
  // Each read as a command makes it; one that fails (a field this file lacks
  // or holds in another shape) fails there, in the command, not here.
  const auto quietly = [](const auto& read) {
    try {
      read();
    } catch (const UserError&) {
    }
  };
  for (const char* name : {"status", "status_reason", "mode", "effects", "version", "scene"})
    quietly([&] { attribute(name); });
  for (const char* name : {"fps", "substeps_per_frame", "substep_seconds"})
    quietly([&] { number_attribute(name, 0.0); });
  quietly([&] { seed(); });
  quietly([&] { times_s(); });
  quietly([&] { stage_names(); });
  quietly([&] { stage_seconds(); });
  for (const char* name : {"max_strain", "mean_strain", "wall_seconds", "kinetic_energy",
                           "infill_converged", "infill_iterations", "coarse_offset"})
    quietly([&] { stat(name); });
  quietly([&] { rest_positions(); });
  quietly([&] { coarse_rows(); });
  quietly([&] { coarse_cols(); });
  for (const int frame : {0, frames_ - 1}) {
    if (frame < 0) continue;
    quietly([&] { positions(frame); });
    quietly([&] { velocities(frame); });
    quietly([&] { node_strain(frame); });
    quietly([&] { coarse_positions(frame); });
  }
  for (const int frame : {0, trajectory_frames_ - 1})
    if (frame >= 0) quietly([&] { coarse_trajectory(frame); });
  quietly([&] { checkpoint(); });
}

std::optional<Checkpoint> OutputReader::checkpoint() const {
  const hid_t file = impl_->file.get();
  if (H5Lexists(file, "/checkpoint", H5P_DEFAULT) <= 0) return std::nullopt;
  h5::Handle group = h5::group(H5Gopen2(file, "/checkpoint", H5P_DEFAULT));
  H5G_info_t group_info{};
  long long frame = -1, written = -1, trajectory = -1;
  if (!group.valid() || H5Gget_info(group.get(), &group_info) < 0 ||
      !h5::read_int_attribute(group.get(), "frame", frame) ||
      !h5::read_int_attribute(group.get(), "written_frames", written) ||
      !h5::read_int_attribute(group.get(), "trajectory_frames", trajectory) || frame < 0 ||
      written < 0 || trajectory < 0 || frame >= limits::kFrames || written > frame + 1 ||
      trajectory > frame + 1 || group_info.nlinks > 16)
    throw UserError(fmt::format("{}: /checkpoint is damaged (its counts or parts)", path_));
  Checkpoint checkpoint;
  checkpoint.frame = int(frame);
  checkpoint.written_frames = int(written);
  checkpoint.trajectory_frames = int(trajectory);
  for (hsize_t i = 0; i < group_info.nlinks; ++i) {
    char name[64] = {};
    if (H5Lget_name_by_idx(group.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, name, sizeof name,
                           H5P_DEFAULT) <= 0 ||
        name[sizeof name - 1] != 0)
      throw UserError(fmt::format("{}: /checkpoint is damaged (a part's name)", path_));
    const std::string path = fmt::format("/checkpoint/{}", name);
    // At most positions and velocities of the largest lattice, twice over.
    Checkpoint::Part& part = checkpoint.parts.emplace_back();
    part.name = name;
    part.owned = read_all(file, path_, path.c_str(), 12 * hsize_t(limits::kLatticeNodes));
    h5::Handle set = h5::dataset(H5Dopen2(file, path.c_str(), H5P_DEFAULT));
    h5::read_string_attribute(set.get(), "units", part.units);
    long long checksum = 0;
    if (!h5::read_int_attribute(set.get(), "checksum", checksum) ||
        static_cast<std::uint64_t>(checksum) != checkpoint_checksum(part.owned))
      throw UserError(
          fmt::format("{}: /checkpoint/{} is damaged (its checksum)", path_, part.name));
  }
  return checkpoint;
}

std::string OutputReader::attribute(const char* name) const {
  std::string value;
  h5::read_string_attribute(impl_->file.get(), name, value);
  return value;
}

double OutputReader::number_attribute(const char* name, double fallback) const {
  double value = fallback;
  return h5::read_double_attribute(impl_->file.get(), name, value) ? value : fallback;
}

long long OutputReader::seed() const {
  long long value = 0;
  h5::read_int_attribute(impl_->file.get(), "seed", value);
  return value;
}

std::vector<double> OutputReader::times_s() const {
  return read_all(impl_->file.get(), path_, "/frames/time", hsize_t(frames_));
}

std::vector<double> OutputReader::frame_field(const char* name, int frame, int components) const {
  const hid_t file = impl_->file.get();
  if (frame < 0 || frame >= frames_) throw UserError(fmt::format("{}: no frame {}", path_, frame));
  if (H5Lexists(file, "/frames", H5P_DEFAULT) <= 0 || H5Lexists(file, name, H5P_DEFAULT) <= 0)
    return {};
  h5::Handle set = h5::dataset(H5Dopen2(file, name, H5P_DEFAULT));
  h5::Handle file_space = h5::dataspace(H5Dget_space(set.get()));
  // [T, J, K] or [T, J, K, components], T at least this frame: the shape of
  // /frames/positions, checked before anything is read.
  const int rank = components == 1 ? 3 : 4;
  hsize_t dims[4] = {0, 0, 0, 0};
  if (H5Sget_simple_extent_ndims(file_space.get()) != rank ||
      H5Sget_simple_extent_dims(file_space.get(), dims, nullptr) < 0 || dims[0] <= hsize_t(frame) ||
      dims[1] != hsize_t(rows_) || dims[2] != hsize_t(cols_) ||
      (rank == 4 && dims[3] != hsize_t(components)))
    throw UserError(fmt::format("{}: {} is not [T, {}, {}{}] with T > {}", path_, name, rows_,
                                cols_, rank == 4 ? fmt::format(", {}", components) : "", frame));
  const hsize_t start[4] = {hsize_t(frame), 0, 0, 0};
  const hsize_t count[4] = {1, hsize_t(rows_), hsize_t(cols_), hsize_t(components)};
  H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr);
  h5::Handle memory = h5::dataspace(H5Screate_simple(rank, count, nullptr));
  std::vector<double> flat(std::size_t(rows_) * std::size_t(cols_) * std::size_t(components));
  if (H5Dread(set.get(), H5T_NATIVE_DOUBLE, memory.get(), file_space.get(), H5P_DEFAULT,
              flat.data()) < 0)
    throw UserError(fmt::format("{}: cannot read {} of frame {}", path_, name, frame));
  return flat;
}

std::vector<Vec3> OutputReader::positions(int frame) const {
  if (!dense_)
    throw UserError(fmt::format(
        "{}: holds the coarse trajectory only (output.dense = false); `flag-sim refine {} -o "
        "DENSE.h5` recomputes the dense frames",
        path_, path_));
  return to_vec3(frame_field("/frames/positions", frame, 3));
}

std::vector<Vec3> OutputReader::velocities(int frame) const {
  return to_vec3(frame_field("/frames/velocity", frame, 3));
}

std::vector<double> OutputReader::node_strain(int frame) const {
  return frame_field("/frames/strain", frame, 1);
}

std::vector<Vec3> OutputReader::rest_positions() const {
  return to_vec3(read_all(impl_->file.get(), path_, "/lattice/rest_positions",
                          hsize_t(rows_) * hsize_t(cols_) * 3));
}

std::vector<Vec3> OutputReader::coarse_positions(int frame) const {
  if (frame < 0 || frame >= frames_) return {};
  return coarse_frame("/coarse/positions", frame);
}

std::vector<Vec3> OutputReader::coarse_trajectory(int frame) const {
  if (frame < 0 || frame >= trajectory_frames_) return {};
  return coarse_frame("/coarse/trajectory", frame);
}

std::vector<double> OutputReader::coarse_memory(int frame) const {
  const hid_t file = impl_->file.get();
  const char* const name = "/coarse/memory";
  if (frame < 0 || frame >= trajectory_frames_ || H5Lexists(file, "/coarse", H5P_DEFAULT) <= 0 ||
      H5Lexists(file, name, H5P_DEFAULT) <= 0)
    return {};
  h5::Handle set = h5::dataset(H5Dopen2(file, name, H5P_DEFAULT));
  h5::Handle file_space = h5::dataspace(H5Dget_space(set.get()));
  hsize_t dims[2] = {0, 0};
  // Two angles a bending triple, at most two triples a node.
  const hsize_t most = 4 * hsize_t(rows_) * hsize_t(cols_);
  if (H5Sget_simple_extent_ndims(file_space.get()) != 2 ||
      H5Sget_simple_extent_dims(file_space.get(), dims, nullptr) < 0 ||
      dims[0] != hsize_t(trajectory_frames_) || dims[1] == 0 || dims[1] > most)
    throw UserError(fmt::format("{}: {} is not [{}, M] with 0 < M <= {}", path_, name,
                                trajectory_frames_, most));
  const hsize_t start[2] = {hsize_t(frame), 0};
  const hsize_t count[2] = {1, dims[1]};
  H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr);
  h5::Handle memory = h5::dataspace(H5Screate_simple(2, count, nullptr));
  std::vector<double> values(static_cast<std::size_t>(dims[1]));
  if (H5Dread(set.get(), H5T_NATIVE_DOUBLE, memory.get(), file_space.get(), H5P_DEFAULT,
              values.data()) < 0)
    throw UserError(fmt::format("{}: cannot read {} of frame {}", path_, name, frame));
  return values;
}

std::vector<Vec3> OutputReader::coarse_frame(const char* name, int frame) const {
  const hid_t file = impl_->file.get();
  if (H5Lexists(file, "/coarse", H5P_DEFAULT) <= 0 || H5Lexists(file, name, H5P_DEFAULT) <= 0)
    return {};
  h5::Handle set = h5::dataset(H5Dopen2(file, name, H5P_DEFAULT));
  h5::Handle file_space = h5::dataspace(H5Dget_space(set.get()));
  hsize_t dims[4] = {0, 0, 0, 0};
  if (H5Sget_simple_extent_ndims(file_space.get()) != 4 ||
      H5Sget_simple_extent_dims(file_space.get(), dims, nullptr) < 0 || dims[3] != 3 ||
      dims[1] > hsize_t(rows_) || dims[2] > hsize_t(cols_))
    throw UserError(fmt::format("{}: {} is not [T, Jc, Kc, 3] with Jc <= {}, Kc <= {}", path_, name,
                                rows_, cols_));
  if (hsize_t(frame) >= dims[0]) return {};
  // One frame, as positions() reads: not the whole run for every frame.
  const hsize_t start[4] = {hsize_t(frame), 0, 0, 0};
  const hsize_t count[4] = {1, dims[1], dims[2], 3};
  H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr);
  h5::Handle memory = h5::dataspace(H5Screate_simple(4, count, nullptr));
  std::vector<double> flat(std::size_t(dims[1] * dims[2] * 3));
  if (H5Dread(set.get(), H5T_NATIVE_DOUBLE, memory.get(), file_space.get(), H5P_DEFAULT,
              flat.data()) < 0)
    throw UserError(fmt::format("{}: cannot read {} of frame {}", path_, name, frame));
  return to_vec3(flat);
}

std::vector<int> OutputReader::coarse_rows() const {
  const std::vector<double> values =
      read_all(impl_->file.get(), path_, "/coarse/rows", hsize_t(rows_));
  return std::vector<int>(values.begin(), values.end());
}

std::vector<int> OutputReader::coarse_cols() const {
  const std::vector<double> values =
      read_all(impl_->file.get(), path_, "/coarse/cols", hsize_t(cols_));
  return std::vector<int>(values.begin(), values.end());
}

std::vector<double> OutputReader::stat(const char* name) const {
  return read_all(impl_->file.get(), path_, fmt::format("/stats/{}", name).c_str(),
                  hsize_t(frames_));
}

std::vector<std::vector<double>> OutputReader::stage_seconds() const {
  std::vector<hsize_t> dims;
  // At most 64 stages a frame (flag-sim writes under 16).
  const std::vector<double> flat =
      read_all(impl_->file.get(), path_, "/stats/stage_seconds", hsize_t(frames_) * 64, &dims);
  std::vector<std::vector<double>> rows;
  if (dims.size() != 2 || dims[1] == 0) return rows;
  // Each column is the stage its `stages` attribute names: a file where the
  // two disagree was not written by flag-sim, and reading on would go past a row.
  if (const std::size_t names = stage_names().size(); names != dims[1])
    throw UserError(fmt::format(
        "{}: /stats/stage_seconds has {} columns but its attribute `stages` names {}: not an "
        "output flag-sim wrote",
        path_, dims[1], names));
  for (hsize_t t = 0; t < dims[0]; ++t)
    rows.emplace_back(flat.begin() + long(t * dims[1]), flat.begin() + long((t + 1) * dims[1]));
  return rows;
}

std::vector<std::string> OutputReader::stage_names() const {
  std::vector<std::string> names;
  if (H5Lexists(impl_->file.get(), "/stats/stage_seconds", H5P_DEFAULT) <= 0) return names;
  h5::Handle set = h5::dataset(H5Dopen2(impl_->file.get(), "/stats/stage_seconds", H5P_DEFAULT));
  h5::read_string_list_attribute(set.get(), "stages", names);
  return names;
}

}  // namespace flagsim::data
