// hdf5_library.cpp: the HDF5 version `flag-sim --version` reports is the
// library's own, and the one these sources were compiled against.
#include "flagsim/data/hdf5_library.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <string>

namespace flagsim::data {
namespace {

TEST(Hdf5Library, TheVersionIsTheLinkedLibrarysAsMajorMinorRelease) {
  EXPECT_EQ(hdf5_version(), std::to_string(H5_VERS_MAJOR) + "." + std::to_string(H5_VERS_MINOR) +
                                "." + std::to_string(H5_VERS_RELEASE));
}

}  // namespace
}  // namespace flagsim::data
