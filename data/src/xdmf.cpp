// XDMF sidecar: lets ParaView (and VisIt) open the run as a time series of
// structured 2D meshes with per-node point arrays, reading the data from the
// HDF5 file itself.
//
// Why per-frame views: each time step's geometry has to name one frame of
// /frames/positions [T, J, K, 3]. An XDMF HyperSlab item says that in the
// XML, but ParaView's default reader (Xdmf3ReaderS, ParaView 5.11) reads a
// HyperSlab geometry as an untyped array and shows 0 points ("Skipping
// unrecognized array type [None]"); only the legacy XDMFReader follows it.
// Every reader opens a dataset that is one frame, so the file gets one for
// each frame and field, as an HDF5 virtual dataset: a view of that frame's
// slab of the frames' dataset, no data copied (a few hundred bytes of
// metadata per view). The views name their source file ".", the file
// itself, so they survive the rename from .partial and moving the file.
#include <fmt/format.h>

#include <algorithm>

#include "flagsim/data/frame_writer.hpp"
#include "h5_handle.hpp"

namespace flagsim::data {
namespace {

// The per-node fields a time step carries: dataset, components, XDMF attribute type.
struct Field {
  const char* name;  ///< under /frames and /xdmf
  int components;    ///< 1: [T, J, K], 3: [T, J, K, 3]
  const char* attribute_type;
};
constexpr Field kFields[] = {
    {"positions", 3, nullptr},  // the geometry
    {"velocity", 3, "Vector"},
    {"strain", 1, "Scalar"},
};

std::string data_item(const std::string& h5_name, const Lattice& lattice, const Field& field,
                      std::size_t frame) {
  const std::string dims = field.components == 1
                               ? fmt::format("{} {}", lattice.rows, lattice.cols)
                               : fmt::format("{} {} {}", lattice.rows, lattice.cols, 3);
  return fmt::format(
      "<DataItem Dimensions=\"{}\" NumberType=\"Float\" Precision=\"4\" "
      "Format=\"HDF\">{}:{}</DataItem>",
      dims, h5_name, xdmf_view_path(field.name, frame));
}

bool wanted(const Field& field, std::span<const std::string> fields) {
  return !field.attribute_type ||
         std::find(fields.begin(), fields.end(), field.name) != fields.end();
}

}  // namespace

std::string xdmf_view_path(const char* field, std::size_t frame) {
  return fmt::format("/xdmf/{}/{}", field, frame);
}

bool write_xdmf_views(std::int64_t file_id, const Lattice& lattice, std::size_t frames,
                      std::span<const std::string> fields) {
  const hid_t file = file_id;
  h5::Handle props = h5::plist(H5Pcreate(H5P_GROUP_CREATE));
  H5Pset_obj_track_times(props.get(), false);
  h5::Handle root = h5::group(H5Gcreate2(file, "xdmf", H5P_DEFAULT, props.get(), H5P_DEFAULT));
  if (!root.valid()) return false;
  const hsize_t rows = hsize_t(lattice.rows), cols = hsize_t(lattice.cols);
  for (const Field& field : kFields) {
    if (!wanted(field, fields)) continue;
    h5::Handle group =
        h5::group(H5Gcreate2(root.get(), field.name, H5P_DEFAULT, props.get(), H5P_DEFAULT));
    if (!group.valid()) return false;
    const int rank = field.components == 1 ? 2 : 3;
    const hsize_t view_dims[3] = {rows, cols, 3};
    const hsize_t source_dims[4] = {hsize_t(frames), rows, cols, 3};
    h5::Handle view_space = h5::dataspace(H5Screate_simple(rank, view_dims, nullptr));
    h5::Handle source_space = h5::dataspace(H5Screate_simple(rank + 1, source_dims, nullptr));
    const std::string source = fmt::format("/frames/{}", field.name);
    for (std::size_t t = 0; t < frames; ++t) {
      const hsize_t start[4] = {hsize_t(t), 0, 0, 0};
      const hsize_t count[4] = {1, rows, cols, 3};
      h5::Handle create = h5::plist(H5Pcreate(H5P_DATASET_CREATE));
      H5Pset_obj_track_times(create.get(), false);
      if (H5Sselect_hyperslab(source_space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr) <
              0 ||
          H5Pset_virtual(create.get(), view_space.get(), ".", source.c_str(), source_space.get()) <
              0)
        return false;
      h5::Handle view =
          h5::dataset(H5Dcreate2(group.get(), std::to_string(t).c_str(), H5T_IEEE_F32LE,
                                 view_space.get(), H5P_DEFAULT, create.get(), H5P_DEFAULT));
      if (!view.valid()) return false;
    }
  }
  return true;
}

std::string xdmf_text(const std::string& h5_name, const Lattice& lattice,
                      std::span<const double> times_s, std::span<const std::string> fields) {
  const std::size_t frames = times_s.size();
  std::string out =
      "<?xml version=\"1.0\" ?>\n"
      "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
      "<Xdmf Version=\"3.0\">\n <Domain>\n"
      "  <Grid Name=\"flag\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (std::size_t t = 0; t < frames; ++t) {
    out += fmt::format(
        "   <Grid Name=\"frame {}\" GridType=\"Uniform\">\n"
        "    <Time Value=\"{:.9g}\"/>\n"
        "    <Topology TopologyType=\"2DSMesh\" Dimensions=\"{} {}\"/>\n"
        "    <Geometry GeometryType=\"XYZ\">\n"
        "     {}\n"
        "    </Geometry>\n",
        t, times_s[t], lattice.rows, lattice.cols, data_item(h5_name, lattice, kFields[0], t));
    for (const Field& field : kFields)
      if (field.attribute_type && wanted(field, fields))
        out += fmt::format(
            "    <Attribute Name=\"{}\" AttributeType=\"{}\" Center=\"Node\">\n"
            "     {}\n"
            "    </Attribute>\n",
            field.name, field.attribute_type, data_item(h5_name, lattice, field, t));
    out += "   </Grid>\n";
  }
  out += "  </Grid>\n </Domain>\n</Xdmf>\n";
  return out;
}

}  // namespace flagsim::data
