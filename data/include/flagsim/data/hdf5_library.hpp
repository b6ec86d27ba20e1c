#pragma once
// The HDF5 library as this process uses it: its version and its exit handler.
#include <string>

namespace flagsim::data {

/// To be called first thing in main, before any HDF5 call: no HDF5 clean-up
/// at process exit. HDF5 1.10's exit handler crashes (SIGSEGV in H5F__close_cb)
/// on a file whose flush failed (disk full); every file is closed by its owner
/// before exit anyway.
void skip_hdf5_exit_cleanup();

/// The HDF5 library this program runs with ("1.10.8"), for --version.
std::string hdf5_version();

}  // namespace flagsim::data
