#pragma once
#include <string_view>

namespace flagsim {

/// Program version, written to every output file (root attribute `version`).
std::string_view version();

}  // namespace flagsim
