#pragma once
// The scene keys as the parser reads them, for people: `flag-sim scene FILE`
// prints a scene with every key its run takes (defaults included, marked), and
// `flag-sim help keys` lists every key with its default, unit, range and
// meaning. Both come from the parser's own reads (SceneKey), so they cannot
// drift from what a run does; the meanings are the one thing written here.
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "flagsim/scene/scene.hpp"
#include "flagsim/scene/scene_parser.hpp"

namespace flagsim {

/// A key and what it means, in one line.
struct KeyMeaning {
  std::string_view key;
  std::string_view meaning;
};

/// Every key of the schema with its meaning, in the order of the contract.
std::span<const KeyMeaning> key_meanings();

/// The scene as TOML: its tables in reading order, every key the run takes,
/// the ones left to their defaults marked "default", values in the shortest
/// form that reads back to the same number. Parses to the same Scene.
/// @param keys  what parse_scene read for `scene`
std::string effective_scene_toml(const Scene& scene, std::span<const SceneKey> keys);

/// `flag-sim help keys`: every key with its default, unit, range and meaning.
std::string keys_reference();

}  // namespace flagsim
