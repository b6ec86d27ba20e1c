#pragma once
// Every object of an HDF5 file visited, as a test read (isolated_read.hpp):
// every attribute read whole (variable-length strings too), every dataset's
// first and last slice along its first axis (the two ends of its chunk index)
// and, up to 16 MiB, the whole of it. Errors are ignored: this only has to
// touch what a reader could touch.
#include <string>

namespace flagsim::data {

void walk_hdf5_file(const std::string& path);

}  // namespace flagsim::data
