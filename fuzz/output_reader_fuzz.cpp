// libFuzzer target: the output reader (`info`, `render`, compare's inputs) on
// HDF5 files whose every declared shape, type, attribute and value comes from
// the fuzzer. The bytes do not mutate the HDF5 container itself (libhdf5's
// own parser is not ours to harden); they build a well-formed HDF5 file that
// lies about being a flag-sim output in every way a file can: ranks, extents
// up to 2^40 with nothing stored, float or integer types, NaN, stage lists
// longer or shorter than their columns. Anything may be refused (UserError);
// nothing may crash, overflow, allocate past the declared limits (libFuzzer's
// -rss_limit_mb) or hang.
#include <fuzzer/FuzzedDataProvider.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "file_walk.hpp"
#include "flagsim/core/errors.hpp"
#include "flagsim/data/frame_writer.hpp"
#include "flagsim/data/isolated_read.hpp"
#include "flagsim/data/output_reader.hpp"
#include "h5_handle.hpp"

namespace {

namespace h5 = flagsim::data::h5;

// A dataset at `path` of fuzzed rank, extents and element type; its values are
// written only when it is small, so huge extents are declared, not stored.
void add_dataset(FuzzedDataProvider& in, hid_t file, const char* path) {
  if (!in.ConsumeBool()) return;
  const int rank = in.ConsumeIntegralInRange(0, 5);
  const std::size_t n = static_cast<std::size_t>(rank);
  std::vector<hsize_t> dims(n, 0), max_dims(n, H5S_UNLIMITED), chunk(n, 1);
  hsize_t count = 1;
  for (int d = 0; d < rank; ++d) {
    dims[d] = in.ConsumeBool() ? in.ConsumeIntegralInRange<hsize_t>(0, 40)
                               : hsize_t(1) << in.ConsumeIntegralInRange(0, 40);
    count =
        dims[d] != 0 && count > (hsize_t(1) << 62) / dims[d] ? hsize_t(1) << 62 : count * dims[d];
  }
  const bool integer = in.ConsumeBool();
  h5::Handle space = h5::dataspace(
      rank == 0 ? H5Screate(H5S_SCALAR) : H5Screate_simple(rank, dims.data(), max_dims.data()));
  h5::Handle props = h5::plist(H5Pcreate(H5P_DATASET_CREATE));
  if (rank > 0) H5Pset_chunk(props.get(), rank, chunk.data());
  h5::Handle set = h5::dataset(H5Dcreate2(file, path, integer ? H5T_STD_I32LE : H5T_IEEE_F32LE,
                                          space.get(), H5P_DEFAULT, props.get(), H5P_DEFAULT));
  if (!set.valid() || count > 4096 || !in.ConsumeBool()) return;
  std::vector<double> values(count);
  for (double& v : values) v = in.ConsumeFloatingPoint<double>();
  H5Dwrite(set.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
}

std::string write_file(FuzzedDataProvider& in) {
  const std::string path = "/tmp/flagsim_reader_fuzz_" + std::to_string(getpid()) + ".h5";
  h5::Handle file = h5::file(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT));
  if (!file.valid()) return path;
  const hid_t root = file.get();
  h5::write_string_attribute(
      root, "format",
      in.ConsumeBool() ? std::string(flagsim::data::kFormat) : in.ConsumeRandomLengthString(16));
  h5::write_double_attribute(root, "fps", in.ConsumeFloatingPoint<double>());
  h5::write_int_attribute(root, "seed", in.ConsumeIntegral<long long>());
  h5::write_string_attribute(root, "scene", in.ConsumeRandomLengthString(256));
  // A coarse-trajectory file ([output] dense = false) when dense is 0 and there is no
  // /frames/positions.
  if (in.ConsumeBool()) h5::write_double_attribute(root, "dense", in.ConsumeBool() ? 0.0 : 1.0);
  for (const char* group : {"/frames", "/lattice", "/coarse", "/stats"})
    if (in.ConsumeBool())
      h5::Handle(H5Gcreate2(root, group, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  for (const char* set :
       {"/frames/positions", "/frames/time", "/frames/velocity", "/frames/strain",
        "/lattice/rest_positions", "/coarse/positions", "/coarse/rows", "/coarse/cols",
        "/coarse/trajectory", "/coarse/memory", "/stats/max_strain", "/stats/stage_seconds"})
    add_dataset(in, root, set);
  if (H5Lexists(root, "/stats", H5P_DEFAULT) > 0 &&
      H5Lexists(root, "/stats/stage_seconds", H5P_DEFAULT) > 0) {
    h5::Handle set = h5::dataset(H5Dopen2(root, "/stats/stage_seconds", H5P_DEFAULT));
    std::vector<std::string> names(in.ConsumeIntegralInRange<std::size_t>(0, 70), "stage");
    h5::write_string_list_attribute(set.get(), "stages", names);
  }
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  h5::silence_library_errors();
  // The test read in-process (isolated_read.hpp): a crash in it, or in the
  // reads below, is one this fuzzer must see, not a file refused as damaged.
  flagsim::data::set_isolated_reads(false);
  const std::string path = write_file(in);
  flagsim::data::walk_hdf5_file(path);
  try {
    const flagsim::data::OutputReader reader(path);
    reader.read_what_commands_read();
    reader.attribute("scene");
    reader.number_attribute("fps", 30.0);
    reader.seed();
    reader.times_s();
    reader.rest_positions();
    reader.coarse_rows();
    reader.coarse_cols();
    reader.stat("max_strain");
    reader.stage_names();
    reader.stage_seconds();
    for (int t : {-1, 0, 1, reader.frame_count() - 1, reader.frame_count()}) {
      for (auto read : {+[](const flagsim::data::OutputReader&r, int f) { r.positions(f); },
                        +[](const flagsim::data::OutputReader&r, int f) { r.velocities(f); },
                        +[](const flagsim::data::OutputReader&r, int f) { r.node_strain(f); }}) {
        try {
          read(reader, t);
        } catch (const flagsim::UserError&) {
        }
      }
      reader.coarse_positions(t);
    }
    for (int t : {-1, 0, 1, reader.trajectory_frames() - 1, reader.trajectory_frames()}) {
      try {
        reader.coarse_trajectory(t);
      } catch (const flagsim::UserError&) {
      }
      try {
        reader.coarse_memory(t);
      } catch (const flagsim::UserError&) {
      }
    }
  } catch (const flagsim::UserError&) {
  }
  unlink(path.c_str());
  return 0;
}
