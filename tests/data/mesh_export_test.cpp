#include "flagsim/data/mesh_export.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <sstream>

#include "flagsim/core/errors.hpp"
#include "flagsim/core/lattice.hpp"
#include "temp_dir.hpp"

namespace flagsim::data {
namespace {

TEST(Pc2Writer, HeaderThenSamplesAsFloat32) {
  test::TempDir dir;
  const std::string path = dir.file("a.pc2");
  const std::vector<Vec3> sample = {Vec3(1, 2, 3), Vec3(-0.5, 0.25, 1e-3)};
  {
    Pc2Writer cache(path, 2, 2, 5.0f, 1.0f);
    cache.write_sample(sample);
    cache.write_sample(sample);
    cache.finish();
  }
  const std::string bytes = test::file_bytes(path);
  ASSERT_EQ(bytes.size(), kPc2HeaderBytes + sizeof(float) * 2 * 2 * 3);
  EXPECT_EQ(bytes.substr(0, 12), std::string("POINTCACHE2\0", 12));
  std::int32_t version = 0, points = 0, samples = 0;
  float start = 0, rate = 0, z = 0;
  std::memcpy(&version, bytes.data() + 12, 4);
  std::memcpy(&points, bytes.data() + 16, 4);
  std::memcpy(&start, bytes.data() + 20, 4);
  std::memcpy(&rate, bytes.data() + 24, 4);
  std::memcpy(&samples, bytes.data() + 28, 4);
  std::memcpy(&z, bytes.data() + kPc2HeaderBytes + 5 * sizeof(float), 4);
  EXPECT_EQ(version, 1);
  EXPECT_EQ(points, 2);
  EXPECT_EQ(start, 5.0f);
  EXPECT_EQ(rate, 1.0f);
  EXPECT_EQ(samples, 2);
  EXPECT_EQ(z, 1e-3f);
}

TEST(Pc2Writer, ASampleOfTheWrongSizeOrTooFewSamplesFail) {
  test::TempDir dir;
  Pc2Writer wrong(dir.file("a.pc2"), 3, 1, 0.0f, 1.0f);
  EXPECT_THROW(wrong.write_sample(std::vector<Vec3>(2)), IoError);
  Pc2Writer short_cache(dir.file("b.pc2"), 1, 2, 0.0f, 1.0f);
  short_cache.write_sample(std::vector<Vec3>(1));
  EXPECT_THROW(short_cache.finish(), IoError);
}

TEST(ObjText, QuadsUvsAndNormalsOfAFlatLattice) {
  // 2 rows x 3 columns at rest: rows run down -y, columns along +x, normals +z.
  const Lattice lattice = Lattice::rectangle(2, 3, 2.0, 1.0, Vec3(0, 2, 0));
  const std::string text = obj_text(2, 3, lattice.rest_positions(), "test");
  std::istringstream in(text);
  std::string line;
  int v = 0, vt = 0, vn = 0, f = 0;
  std::vector<std::string> faces, uvs;
  while (std::getline(in, line)) {
    if (line.rfind("v ", 0) == 0) ++v;
    if (line.rfind("vt ", 0) == 0) uvs.push_back(line), ++vt;
    if (line.rfind("vn ", 0) == 0) {
      ++vn;
      EXPECT_EQ(line, "vn 0.000000 0.000000 1.000000");
    }
    if (line.rfind("f ", 0) == 0) faces.push_back(line), ++f;
  }
  EXPECT_EQ(text.rfind("# test\n", 0), 0u);
  EXPECT_EQ(v, 6);
  EXPECT_EQ(vt, 6);
  EXPECT_EQ(vn, 6);
  ASSERT_EQ(f, 2);
  EXPECT_EQ(faces[0], "f 1/1/1 4/4/4 5/5/5 2/2/2");
  EXPECT_EQ(uvs[0], "vt 0 1");
  EXPECT_EQ(uvs[5], "vt 1 0");
  EXPECT_NE(text.find("v 2 1 0\n"), std::string::npos);  // the bottom fly corner
}

}  // namespace
}  // namespace flagsim::data
