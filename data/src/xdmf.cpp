// XDMF sidecar: lets ParaView (and VisIt) open /frames/positions as a time
// series of structured 2D meshes, reading the data from the HDF5 file itself.
#include <fmt/format.h>

#include "flagsim/data/frame_writer.hpp"

namespace flagsim::data {

std::string xdmf_text(const std::string& h5_name, const Lattice& lattice,
                      std::span<const double> times_s) {
  const int rows = lattice.rows, cols = lattice.cols;
  const std::size_t frames = times_s.size();
  std::string out =
      "<?xml version=\"1.0\" ?>\n"
      "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
      "<Xdmf Version=\"3.0\">\n <Domain>\n"
      "  <Grid Name=\"flag\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (std::size_t t = 0; t < frames; ++t) {
    out += fmt::format(
        "   <Grid Name=\"frame {0}\" GridType=\"Uniform\">\n"
        "    <Time Value=\"{1:.9g}\"/>\n"
        "    <Topology TopologyType=\"2DSMesh\" Dimensions=\"{2} {3}\"/>\n"
        "    <Geometry GeometryType=\"XYZ\">\n"
        "     <DataItem ItemType=\"HyperSlab\" Dimensions=\"1 {2} {3} 3\" Type=\"HyperSlab\">\n"
        "      <DataItem Dimensions=\"3 4\" Format=\"XML\">{0} 0 0 0 1 1 1 1 1 {2} {3} "
        "3</DataItem>\n"
        "      <DataItem Dimensions=\"{4} {2} {3} 3\" NumberType=\"Float\" Precision=\"4\" "
        "Format=\"HDF\">{5}:/frames/positions</DataItem>\n"
        "     </DataItem>\n"
        "    </Geometry>\n"
        "   </Grid>\n",
        t, times_s[t], rows, cols, frames, h5_name);
  }
  out += "  </Grid>\n </Domain>\n</Xdmf>\n";
  return out;
}

}  // namespace flagsim::data
