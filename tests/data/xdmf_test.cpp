// xdmf.cpp: the sidecar's text, and the per-frame views it points at, read
// back through HDF5 as any reader would.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <string>
#include <vector>

#include "flagsim/data/frame_writer.hpp"
#include "h5_handle.hpp"
#include "temp_dir.hpp"

namespace flagsim::data {
namespace {

TEST(Xdmf, TheSidecarPointsAtEveryFramesViews) {
  const Lattice lattice = Lattice::rectangle(3, 4, 1, 1, Vec3::Zero());
  const std::vector<double> times = {0.0, 0.5};
  const std::vector<std::string> fields = {"strain", "velocity"};
  const std::string text = xdmf_text("run.h5", lattice, times, fields);
  EXPECT_NE(text.find("CollectionType=\"Temporal\""), std::string::npos);
  EXPECT_NE(text.find("<Time Value=\"0.5\"/>"), std::string::npos);
  EXPECT_NE(text.find("Dimensions=\"3 4 3\" NumberType=\"Float\" Precision=\"4\" "
                      "Format=\"HDF\">run.h5:/xdmf/positions/1<"),
            std::string::npos);
  EXPECT_NE(text.find("<Attribute Name=\"velocity\" AttributeType=\"Vector\" Center=\"Node\">"),
            std::string::npos);
  EXPECT_NE(text.find("Dimensions=\"3 4\" NumberType=\"Float\" Precision=\"4\" "
                      "Format=\"HDF\">run.h5:/xdmf/strain/0<"),
            std::string::npos);
  // ParaView's default reader shows 0 points for a HyperSlab geometry.
  EXPECT_EQ(text.find("HyperSlab"), std::string::npos);
  // Only the fields the run wrote.
  const std::vector<std::string> strain_only = {"strain"};
  const std::string fewer = xdmf_text("run.h5", lattice, times, strain_only);
  EXPECT_EQ(fewer.find("velocity"), std::string::npos);
  EXPECT_NE(fewer.find("/xdmf/strain/1"), std::string::npos);
}

TEST(Xdmf, EachFramesViewReadsThatFrameOfItsField) {
  test::TempDir dir;
  const Lattice lattice = Lattice::rectangle(3, 4, 1.0, 1.0, Vec3::Zero());
  constexpr std::size_t kFrames = 3;
  // /frames/positions [3, 3, 4, 3] and /frames/strain [3, 3, 4], float32, value = its flat index.
  std::vector<float> positions(kFrames * 12 * 3), strain(kFrames * 12);
  for (std::size_t i = 0; i < positions.size(); ++i) positions[i] = float(i);
  for (std::size_t i = 0; i < strain.size(); ++i) strain[i] = float(1000 + i);
  {
    h5::Handle file =
        h5::file(H5Fcreate(dir.file("run.h5").c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT));
    ASSERT_TRUE(file.valid());
    h5::Handle frames =
        h5::group(H5Gcreate2(file.get(), "frames", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
    const hsize_t position_dims[4] = {kFrames, 3, 4, 3}, strain_dims[3] = {kFrames, 3, 4};
    const auto write = [&](const char* name, int rank, const hsize_t* dims, const float* data) {
      h5::Handle space = h5::dataspace(H5Screate_simple(rank, dims, nullptr));
      h5::Handle set = h5::dataset(H5Dcreate2(frames.get(), name, H5T_IEEE_F32LE, space.get(),
                                              H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
      ASSERT_GE(H5Dwrite(set.get(), H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), 0);
    };
    write("positions", 4, position_dims, positions.data());
    write("strain", 3, strain_dims, strain.data());
    const std::vector<std::string> fields = {"strain"};
    ASSERT_TRUE(write_xdmf_views(file.get(), lattice, kFrames, fields));
  }
  h5::Handle file = h5::file(H5Fopen(dir.file("run.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
  ASSERT_TRUE(file.valid());
  const auto read = [&](const std::string& path, std::size_t count) {
    std::vector<float> values(count, -1.0f);
    h5::Handle set = h5::dataset(H5Dopen2(file.get(), path.c_str(), H5P_DEFAULT));
    EXPECT_TRUE(set.valid()) << path;
    if (set.valid()) {
      EXPECT_GE(H5Dread(set.get(), H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
                0);
    }
    return values;
  };
  for (std::size_t t = 0; t < kFrames; ++t) {
    const std::vector<float> p = read(xdmf_view_path("positions", t), 36);
    EXPECT_EQ(p, std::vector<float>(positions.begin() + long(36 * t),
                                    positions.begin() + long(36 * (t + 1))))
        << t;
    const std::vector<float> s = read(xdmf_view_path("strain", t), 12);
    EXPECT_EQ(
        s, std::vector<float>(strain.begin() + long(12 * t), strain.begin() + long(12 * (t + 1))))
        << t;
  }
  // A field the run did not ask for has no views.
  h5::silence_library_errors();
  EXPECT_LT(H5Lexists(file.get(), "/xdmf/velocity", H5P_DEFAULT), 1);
}

}  // namespace
}  // namespace flagsim::data
