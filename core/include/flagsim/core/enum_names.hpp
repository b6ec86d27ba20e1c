#pragma once
// The names of an enum the scene file spells out (scene.mode = "hybrid",
// solver.backend = "xpbd", ...): one table per enum, in the order users are
// told them. Parsing, printing and the list of choices an error message gives
// all read that table, so a name is written once.
#include <array>
#include <cstddef>
#include <optional>
#include <string_view>
#include <vector>

namespace flagsim {

template <typename E>
struct NamedValue {
  E value;
  std::string_view name;  ///< a string literal: null-terminated
};

template <typename E, std::size_t N>
using NameTable = std::array<NamedValue<E>, N>;

/// The name of `value` ("?" for a value the table lacks).
template <typename E, std::size_t N>
constexpr std::string_view name_in(const NameTable<E, N>& table, E value) {
  for (const NamedValue<E>& entry : table)
    if (entry.value == value) return entry.name;
  return "?";
}

/// The value named `name`, or nullopt.
template <typename E, std::size_t N>
constexpr std::optional<E> value_in(const NameTable<E, N>& table, std::string_view name) {
  for (const NamedValue<E>& entry : table)
    if (entry.name == name) return entry.value;
  return std::nullopt;
}

/// Every name, in the table's order.
template <typename E, std::size_t N>
std::vector<std::string_view> names_in(const NameTable<E, N>& table) {
  std::vector<std::string_view> names;
  names.reserve(N);
  for (const NamedValue<E>& entry : table) names.push_back(entry.name);
  return names;
}

}  // namespace flagsim
