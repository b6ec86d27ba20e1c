#pragma once
// Reading a scene: TOML text -> validated Scene, or a UserError that names the
// file, line, column and key, says what was expected and suggests near-miss names.
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "flagsim/scene/scene.hpp"

namespace flagsim {

/// A scene key set on the command line: `assignment` is KEY=VALUE (VALUE in
/// TOML syntax); `typed` is how the user wrote it ("--set flag.fine=[65,97]",
/// "--mode foo"), which is what an error about it quotes.
struct Override {
  std::string assignment;
  std::string typed;
};

/// `text` as a TOML basic string, quoted and escaped ("a\"b" for a"b).
std::string toml_string(std::string_view text);

/// `--set KEY=VALUE` arguments as overrides, each quoted as typed.
std::vector<Override> set_overrides(std::span<const std::string> assignments);

/// A scene key as the parser read it for one scene (`flag-sim scene`, `help keys`).
struct SceneKey {
  std::string key;     ///< dotted, e.g. "flag.fine"
  std::string value;   ///< TOML text of the value the scene takes; "" for an absent optional key
  std::string unit;    ///< as the parser states it ("" for none)
  std::string range;   ///< what the parser accepts
  bool given = false;  ///< in the file or an override; else the default
};

/// Parses and validates a scene.
/// @param toml_text    the scene file's contents
/// @param source_path  name used in error messages (the file path)
/// @param overrides    "KEY=VALUE" strings (from --set), VALUE in TOML syntax; applied
///                     on top of the file and checked exactly like it
/// @param keys         if given: every key the parser read, in reading order
/// @throws UserError on any malformed, unknown, out-of-range or inconsistent key
Scene parse_scene(std::string_view toml_text, std::string_view source_path,
                  std::span<const Override> overrides, std::vector<SceneKey>* keys = nullptr);
Scene parse_scene(std::string_view toml_text, std::string_view source_path,
                  std::span<const std::string> overrides = {});

/// Reads the file at `path` and parses it as above; an unreadable file is a UserError.
Scene load_scene_file(const std::string& path, std::span<const Override> overrides,
                      std::vector<SceneKey>* keys = nullptr);
Scene load_scene_file(const std::string& path, std::span<const std::string> overrides = {});

/// The embedded default scene (scenes/default.toml, compiled into the binary).
std::string_view default_scene_toml();

/// The name error messages use for the embedded default scene.
inline constexpr std::string_view kDefaultSceneName = "<default scene>";

}  // namespace flagsim
