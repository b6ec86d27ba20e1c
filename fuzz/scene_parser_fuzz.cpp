// libFuzzer target: the scene parser and validator on arbitrary bytes, as a
// scene file and as a --set override of a valid scene. Anything may be
// rejected (UserError, the "error:" line users see); nothing may crash, leak,
// overflow or hang (ASan + UBSan, libFuzzer's timeout).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "flagsim/core/errors.hpp"
#include "flagsim/scene/scene_parser.hpp"

namespace {

constexpr std::string_view kValid = R"([scene]
mode = "hybrid"
[flag]
fine = [17, 25]
coarse = [9, 13]
[wind]
velocity = [10, 0, 0]
)";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    flagsim::parse_scene(text, "fuzz.toml");
  } catch (const flagsim::UserError&) {
  }
  // The first line as KEY=VALUE on a scene that is valid without it.
  const std::string override_text(text.substr(0, text.find('\n')));
  try {
    const std::string overrides[] = {override_text};
    flagsim::parse_scene(kValid, "valid.toml", overrides);
  } catch (const flagsim::UserError&) {
  }
  return 0;
}
