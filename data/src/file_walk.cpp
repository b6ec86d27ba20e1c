#include "file_walk.hpp"

#include <hdf5.h>

#include <algorithm>
#include <vector>

namespace flagsim::data {
namespace {

constexpr hssize_t kMaxAttributeElements = hssize_t(1) << 20;
constexpr std::size_t kWholeDatasetBytes = std::size_t(16) << 20;

bool is_variable(hid_t type) {
  return H5Tdetect_class(type, H5T_VLEN) > 0 || H5Tis_variable_str(type) > 0;
}

herr_t read_attribute(hid_t location, const char* name, const H5A_info_t*, void*) {
  const hid_t attribute = H5Aopen(location, name, H5P_DEFAULT);
  if (attribute < 0) return 0;
  const hid_t type = H5Aget_type(attribute);
  const hid_t space = H5Aget_space(attribute);
  const hid_t memory = type < 0 ? -1 : H5Tget_native_type(type, H5T_DIR_DEFAULT);
  const hssize_t count = space < 0 ? -1 : H5Sget_simple_extent_npoints(space);
  const std::size_t size = memory < 0 ? 0 : H5Tget_size(memory);
  if (count >= 0 && count <= kMaxAttributeElements && size > 0 && size < (1u << 16)) {
    std::vector<char> buffer(std::size_t(count) * size + 1);
    if (H5Aread(attribute, memory, buffer.data()) >= 0 && is_variable(memory))
      H5Dvlen_reclaim(memory, space, H5P_DEFAULT, buffer.data());
  }
  if (memory >= 0) H5Tclose(memory);
  if (space >= 0) H5Sclose(space);
  if (type >= 0) H5Tclose(type);
  H5Aclose(attribute);
  return 0;
}

// The slice [first, first + 1) along axis 0 (all of it when `whole`).
void read_slice(hid_t set, hid_t file_space, hid_t memory, int rank, const hsize_t* dims,
                hsize_t first, bool whole) {
  std::vector<hsize_t> start(std::size_t(rank), 0), count(dims, dims + rank);
  if (!whole) {
    start[0] = first;
    count[0] = 1;
  }
  std::size_t bytes = H5Tget_size(memory);
  if (bytes == 0) return;
  for (const hsize_t c : count) {  // saturating: declared extents may reach 2^40 each
    if (c == 0) return;
    if (c > kWholeDatasetBytes / bytes) return;
    bytes *= std::size_t(c);
  }
  if (bytes > kWholeDatasetBytes) return;
  if (H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start.data(), nullptr, count.data(),
                          nullptr) < 0)
    return;
  const hid_t memory_space = H5Screate_simple(rank, count.data(), nullptr);
  std::vector<char> buffer(bytes);
  H5Dread(set, memory, memory_space, file_space, H5P_DEFAULT, buffer.data());
  H5Sclose(memory_space);
}

void read_dataset(hid_t set) {
  const hid_t type = H5Dget_type(set);
  const hid_t space = H5Dget_space(set);
  const hid_t memory = type < 0 ? -1 : H5Tget_native_type(type, H5T_DIR_DEFAULT);
  const int rank = space < 0 ? -1 : H5Sget_simple_extent_ndims(space);
  if (memory >= 0 && !is_variable(memory) && rank >= 1 && rank <= 8) {
    hsize_t dims[8] = {};
    H5Sget_simple_extent_dims(space, dims, nullptr);
    std::size_t bytes = H5Tget_size(memory);
    bool small = bytes > 0;
    for (int d = 0; d < rank && small; ++d) {  // saturating, as in read_slice
      small = dims[d] <= kWholeDatasetBytes / std::max<std::size_t>(bytes, 1);
      bytes *= std::size_t(dims[d]);
    }
    if (small && bytes <= kWholeDatasetBytes) {
      read_slice(set, space, memory, rank, dims, 0, true);
    } else if (dims[0] > 0) {
      read_slice(set, space, memory, rank, dims, 0, false);
      read_slice(set, space, memory, rank, dims, dims[0] - 1, false);
    }
  }
  if (memory >= 0) H5Tclose(memory);
  if (space >= 0) H5Sclose(space);
  if (type >= 0) H5Tclose(type);
}

herr_t visit(hid_t root, const char* name, const H5O_info_t* info, void*) {
  const hid_t object = H5Oopen(root, name, H5P_DEFAULT);
  if (object < 0) return 0;
  hsize_t index = 0;
  H5Aiterate2(object, H5_INDEX_NAME, H5_ITER_NATIVE, &index, read_attribute, nullptr);
  if (info->type == H5O_TYPE_DATASET) read_dataset(object);
  H5Oclose(object);
  return 0;
}

}  // namespace

void walk_hdf5_file(const std::string& path) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) return;
  H5Ovisit2(file, H5_INDEX_NAME, H5_ITER_NATIVE, visit, nullptr, H5O_INFO_BASIC);
  H5Fclose(file);  // closing frees what was cached: a damaged heap can fail there too
}

}  // namespace flagsim::data
