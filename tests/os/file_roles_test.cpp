// file_roles.cpp: an output is never an input (or another output), however
// the path is spelt; a failed command leaves no directory it made behind.
#include "flagsim/os/file_roles.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <system_error>

#include "flagsim/core/errors.hpp"
#include "temp_dir.hpp"

namespace flagsim {
namespace {

namespace fs = std::filesystem;

std::string error_of(const FileRoles& roles) {
  try {
    roles.check();
  } catch (const UserError& e) {
    return e.what();
  }
  return "";
}

TEST(FileRoles, AnOutputSpeltDifferentlyFromItsInputIsStillItsInput) {
  test::TempDir dir;
  const std::string scene = dir.write("s.toml", "[scene]\n");
  fs::create_directory(dir.file("sub"));
  for (const std::string& spelling :
       {dir.file("sub/../s.toml"), dir.path() + "//./s.toml", dir.file("s.toml")}) {
    FileRoles roles;
    roles.input(scene, "the scene");
    roles.output(spelling, "-o");
    const std::string message = error_of(roles);
    EXPECT_NE(message.find(spelling), std::string::npos) << spelling << ": " << message;
    EXPECT_NE(message.find("the scene"), std::string::npos) << message;
  }
}

TEST(FileRoles, LinksToAnInputAreThatInput) {
  test::TempDir dir;
  const std::string scene = dir.write("s.toml", "[scene]\n");
  fs::create_symlink(scene, dir.file("soft.toml"));
  fs::create_hard_link(scene, dir.file("hard.toml"));
  fs::create_directory_symlink(dir.path(), dir.file("here"));
  for (const char* link : {"soft.toml", "hard.toml", "here/s.toml"}) {
    FileRoles roles;
    roles.input(scene, "the scene");
    roles.output(dir.file(link), "-o");
    EXPECT_FALSE(error_of(roles).empty()) << link;
    EXPECT_TRUE(same_file(scene, dir.file(link))) << link;
  }
}

TEST(FileRoles, TwoOutputsThatAreOneFileAreRefusedBeforeEitherExists) {
  test::TempDir dir;
  FileRoles roles;
  roles.output(dir.file("run.h5"), "-o");
  roles.output(dir.file("./run.h5"), "--render");
  EXPECT_FALSE(fs::exists(dir.file("run.h5")));
  EXPECT_FALSE(error_of(roles).empty());
}

TEST(FileRoles, DifferentFilesPass) {
  test::TempDir dir;
  const std::string scene = dir.write("s.toml", "[scene]\n");
  FileRoles roles;
  roles.input(scene, "the scene");
  roles.output(dir.file("run.h5"), "-o");
  roles.output(dir.file("run.mp4"), "--render");
  EXPECT_NO_THROW(roles.check());
  EXPECT_FALSE(same_file(scene, dir.file("run.h5")));
}

TEST(FileRoles, AFileNamePartIsOneHarmlessName) {
  EXPECT_NO_THROW(check_file_name_part("default", "scene.name"));
  for (const std::string& bad :
       {std::string(), std::string("a/b"), std::string("."), std::string(".."),
        std::string("tab\there"), std::string(201, 'x'), std::string("nul\0x", 5)})
    EXPECT_THROW(check_file_name_part(bad, "scene.name"), UserError) << bad;
}

TEST(CreatedDirectories, WhatStaysEmptyIsRemovedDeepestFirstWhatHoldsAFileStays) {
  test::TempDir dir;
  std::error_code error;
  {
    CreatedDirectories made;
    ASSERT_TRUE(made.create(dir.file("new/sub"), error)) << error.message();
    EXPECT_TRUE(fs::is_directory(dir.file("new/sub")));
  }
  EXPECT_FALSE(fs::exists(dir.file("new")));  // a failed command leaves nothing
  {
    CreatedDirectories made;
    ASSERT_TRUE(made.create(dir.file("kept/sub"), error));
    dir.write("kept/sub/run.h5", "data");
  }
  EXPECT_TRUE(fs::exists(dir.file("kept/sub/run.h5")));
  fs::create_directory(dir.file("mine"));
  {
    CreatedDirectories made;
    ASSERT_TRUE(made.create(dir.file("mine"), error));  // it was there: not ours
  }
  EXPECT_TRUE(fs::is_directory(dir.file("mine")));
}

}  // namespace
}  // namespace flagsim
