#include "flagsim/data/disk_room.hpp"

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <string>

#include "temp_dir.hpp"

namespace flagsim::data {
namespace {

TEST(DiskRoom, AFewBytesFitAndMoreThanAnyDiskDoesNot) {
  test::TempDir dir;
  EXPECT_EQ(no_room_for(dir.file("new.h5.partial"), 4096), std::nullopt);
  const auto full = no_room_for(dir.file("new.h5.partial"), UINTMAX_MAX / 2);
  ASSERT_TRUE(full.has_value());
  EXPECT_EQ(full->rfind("no room for more frames: ", 0), 0u) << *full;
  EXPECT_NE(full->find("MB"), std::string::npos) << *full;
}

TEST(DiskRoom, TheFileSizeLimitCountsWhatTheFileHoldsAlready) {
  test::TempDir dir;
  const std::string file = dir.write("run.h5.partial", std::string(6000, 'x'));
  rlimit before{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &before), 0);
  rlimit lowered = before;
  lowered.rlim_cur = 10000;  // bytes; only checked here, nothing is written past it
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &lowered), 0);
  const auto fits = no_room_for(file, 3000);  // 6000 + 3000 <= 10000
  const auto over = no_room_for(file, 5000);  // 6000 + 5000 > 10000
  const auto fresh = no_room_for(dir.file("other.h5.partial"), 5000);
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &before), 0);
  EXPECT_EQ(fits, std::nullopt);
  ASSERT_TRUE(over.has_value());
  EXPECT_NE(over->find("0.0 MB left"), std::string::npos) << *over;
  EXPECT_EQ(fresh, std::nullopt);
}

}  // namespace
}  // namespace flagsim::data
