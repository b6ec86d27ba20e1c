// h5_handle.cpp: the HDF5 handles close what they own once, and the
// attribute helpers read back what they wrote (and refuse what is not theirs).
#include "h5_handle.hpp"

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "temp_dir.hpp"

namespace flagsim::data::h5 {
namespace {

Handle new_file(const test::TempDir& dir) {
  return file(H5Fcreate(dir.file("a.h5").c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT));
}

TEST(H5Handle, AMovedHandleOwnsTheIdAndTheEmptyOneClosesNothing) {
  test::TempDir dir;
  Handle first = new_file(dir);
  ASSERT_TRUE(first.valid());
  const hid_t id = first.get();
  Handle second = std::move(first);
  EXPECT_FALSE(
      first.valid());  // NOLINT(bugprone-use-after-move): the moved-from state is the point
  EXPECT_EQ(second.get(), id);
  EXPECT_GT(H5Iis_valid(id), 0);
  second.reset();
  EXPECT_FALSE(second.valid());
  EXPECT_LE(H5Iis_valid(id), 0);  // closed by the handle that owned it, once
  Handle empty;
  EXPECT_FALSE(empty.valid());
}

TEST(H5Handle, AttributesReadBackWhatWasWritten) {
  test::TempDir dir;
  Handle f = new_file(dir);
  ASSERT_TRUE(write_string_attribute(f.get(), "mode", "hybrid"));
  ASSERT_TRUE(write_string_attribute(f.get(), "mode", "xpbd"));  // overwritten, not added
  ASSERT_TRUE(write_string_list_attribute(f.get(), "effects", {"stretch", "wind", "infill"}));
  ASSERT_TRUE(write_int_attribute(f.get(), "seed", -42));
  ASSERT_TRUE(write_double_attribute(f.get(), "fps", 29.97));
  std::string mode;
  std::vector<std::string> effects;
  long long seed = 0;
  double fps = 0.0;
  EXPECT_TRUE(read_string_attribute(f.get(), "mode", mode));
  EXPECT_EQ(mode, "xpbd");
  EXPECT_TRUE(read_string_list_attribute(f.get(), "effects", effects));
  EXPECT_EQ(effects, (std::vector<std::string>{"stretch", "wind", "infill"}));
  EXPECT_TRUE(read_int_attribute(f.get(), "seed", seed));
  EXPECT_EQ(seed, -42);
  EXPECT_TRUE(read_double_attribute(f.get(), "fps", fps));
  EXPECT_EQ(fps, 29.97);
}

TEST(H5Handle, AnAbsentOrForeignAttributeIsNotRead) {
  test::TempDir dir;
  silence_library_errors();
  Handle f = new_file(dir);
  ASSERT_TRUE(write_int_attribute(f.get(), "seed", 7));
  std::string text = "unchanged";
  EXPECT_FALSE(read_string_attribute(f.get(), "absent", text));
  EXPECT_FALSE(read_string_attribute(f.get(), "seed", text));  // an integer is not a string
  EXPECT_EQ(text, "unchanged");
  std::vector<std::string> list;
  EXPECT_FALSE(read_string_list_attribute(f.get(), "seed", list));
  double x = 0.0;
  EXPECT_FALSE(read_double_attribute(f.get(), "absent", x));
}

}  // namespace
}  // namespace flagsim::data::h5
