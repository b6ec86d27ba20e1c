#include "flagsim/data/hdf5_library.hpp"

#include <fmt/format.h>
#include <hdf5.h>

namespace flagsim::data {

void skip_hdf5_exit_cleanup() {
  H5dont_atexit();
}

std::string hdf5_version() {
  unsigned major = 0, minor = 0, release = 0;
  H5get_libversion(&major, &minor, &release);
  return fmt::format("{}.{}.{}", major, minor, release);
}

}  // namespace flagsim::data
