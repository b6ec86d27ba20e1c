#pragma once
// A number that describes a run (an HDF5 root attribute of its output): its
// name, value, SI unit, and whether it is a count (written as an integer).
#include <string>

namespace flagsim {

struct NamedNumber {
  std::string name;
  double value = 0.0;
  std::string units;     ///< "s", "1/s", "1" (a count or a ratio)
  bool integer = false;  ///< a count: stored as int64
};

}  // namespace flagsim
