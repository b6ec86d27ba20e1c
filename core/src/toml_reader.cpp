#include "toml_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "flagsim/core/errors.hpp"
#include "flagsim/core/near_miss.hpp"

namespace flagsim::detail {
namespace {

std::string describe(const toml::node& node) {
  if (node.is_table()) return "a table";
  if (node.is_floating_point()) return fmt::format("{}", *node.value<double>());  // shortest form
  if (node.is_string()) return fmt::format("\"{}\"", *node.value<std::string>());
  if (const toml::array* array = node.as_array();
      array && array->size() <= 8 &&
      std::all_of(array->begin(), array->end(),
                  [](const toml::node& n) { return n.is_number(); })) {
    std::string text = "[";
    for (const toml::node& item : *array)
      text += fmt::format("{}{}", text.size() > 1 ? ", " : "", *item.value<double>());
    return text + "]";
  }
  std::ostringstream out;
  node.visit([&out](auto&& value) { out << value; });
  // toml++ lays arrays out over several lines; an error is one line.
  std::string text;
  for (const char c : out.str()) {
    const bool space = c == '\n' || c == '\r' || c == '\t' || c == ' ';
    if (!space)
      text += c;
    else if (!text.empty() && text.back() != ' ')
      text += ' ';
  }
  if (text.size() > 60) text = text.substr(0, 57) + "...";
  return text;
}

std::string format_number(double x) {
  return fmt::format("{:g}", x);
}

}  // namespace

std::string where(const toml::source_region& source) {
  std::string path = source.path ? *source.path : std::string("<scene>");
  if (path.starts_with("--")) return path;  // a command-line override, quoted as typed
  if (source.begin.line == 0) return path;
  return fmt::format("{}:{}:{}", path, source.begin.line, source.begin.column);
}

namespace {
thread_local const std::vector<std::pair<std::string, std::string>>* t_override_labels = nullptr;
thread_local std::vector<std::pair<std::string, std::string>> t_override_storage;
}  // namespace

OverrideLabels::OverrideLabels(std::vector<std::pair<std::string, std::string>> key_to_label) {
  t_override_storage = std::move(key_to_label);
  t_override_labels = &t_override_storage;
}

OverrideLabels::~OverrideLabels() {
  t_override_labels = nullptr;
  t_override_storage.clear();
}

std::string where_key(const std::string& key, const toml::source_region& source) {
  if (t_override_labels) {
    // The last override wins, as it does for the value.
    for (auto it = t_override_labels->rbegin(); it != t_override_labels->rend(); ++it) {
      const std::string& overridden = it->first;
      // The key itself, a key inside it, or a table the override reached into
      // (--set flag.fine.x=1 turns flag.fine into a table).
      if (key == overridden || key.starts_with(overridden + ".") ||
          overridden.starts_with(key + "."))
        return it->second;
    }
  }
  return where(source);
}

std::string Bound::describe() const {
  const bool low_set = low > -1e299, high_set = high < 1e299;
  if (low_set && high_set)
    return fmt::format("in {}{}, {}]", low_open ? "(" : "[", format_number(low),
                       format_number(high));
  if (low_set) return fmt::format("{} {}", low_open ? ">" : ">=", format_number(low));
  if (high_set) return fmt::format("<= {}", format_number(high));
  return "finite";
}

TableReader::TableReader(const toml::table& table, std::string prefix, std::string fallback_where)
    : table_(table), prefix_(std::move(prefix)), fallback_where_(std::move(fallback_where)) {}

std::string TableReader::key_name(std::string_view key) const {
  return prefix_.empty() ? std::string(key) : prefix_ + "." + std::string(key);
}

std::string TableReader::where_of(std::string_view key) const {
  if (const toml::node* node = table_.get(key)) return where_key(key_name(key), node->source());
  if (table_.source().begin.line != 0) return where(table_.source());
  return fallback_where_;
}

void TableReader::fail(std::string_view key, const std::string& message) const {
  throw UserError(fmt::format("{}: {}: {}", where_of(key), key_name(key), message));
}

void TableReader::expected(std::string_view key, const toml::node& node,
                           const std::string& what) const {
  throw UserError(fmt::format("{}: {}: expected {}, got {}",
                              where_key(key_name(key), node.source()), key_name(key), what,
                              describe(node)));
}

const toml::node* TableReader::lookup(std::string_view key) {
  known_.emplace_back(key);
  return table_.get(key);
}

std::optional<double> TableReader::optional_real(std::string_view key, Bound bound,
                                                 std::string_view unit) {
  const toml::node* node = lookup(key);
  if (!node) return std::nullopt;
  const std::string what =
      fmt::format("a number {}{}{}", bound.describe(), unit.empty() ? "" : " ", unit);
  if (!node->is_number()) expected(key, *node, what);
  const double x = *node->value<double>();
  if (!std::isfinite(x) || !bound.contains(x)) expected(key, *node, what);
  return x;
}

double TableReader::real(std::string_view key, double fallback, Bound bound,
                         std::string_view unit) {
  return optional_real(key, bound, unit).value_or(fallback);
}

std::optional<long long> TableReader::optional_integer(std::string_view key, long long low,
                                                       long long high) {
  const toml::node* node = lookup(key);
  if (!node) return std::nullopt;
  const std::string what = fmt::format("an integer in [{}, {}]", low, high);
  if (!node->is_integer()) expected(key, *node, what);
  const long long x = *node->value<long long>();
  if (x < low || x > high) expected(key, *node, what);
  return x;
}

long long TableReader::integer(std::string_view key, long long fallback, long long low,
                               long long high) {
  return optional_integer(key, low, high).value_or(fallback);
}

std::string TableReader::string(std::string_view key, std::string fallback) {
  const toml::node* node = lookup(key);
  if (!node) return fallback;
  if (!node->is_string()) expected(key, *node, "a string");
  return *node->value<std::string>();
}

bool TableReader::boolean(std::string_view key, bool fallback) {
  const toml::node* node = lookup(key);
  if (!node) return fallback;
  if (!node->is_boolean()) expected(key, *node, "true or false");
  return *node->value<bool>();
}

std::string TableReader::choice(std::string_view key, std::string fallback,
                                std::vector<std::string_view> choices) {
  const toml::node* node = lookup(key);
  std::string listed;
  for (std::string_view c : choices)
    listed += fmt::format("{}\"{}\"", listed.empty() ? "" : ", ", c);
  const std::string what = "one of " + listed;
  if (!node) return fallback;
  if (!node->is_string()) expected(key, *node, what);
  std::string value = *node->value<std::string>();
  for (std::string_view c : choices)
    if (value == c) return value;
  const std::string guess = closest_name(value, choices);
  throw UserError(fmt::format("{}: {}: expected {}, got \"{}\"{}",
                              where_key(key_name(key), node->source()), key_name(key), what, value,
                              guess.empty() ? "" : fmt::format(" (did you mean \"{}\"?)", guess)));
}

std::vector<std::string> TableReader::choice_set(std::string_view key,
                                                 std::vector<std::string> fallback,
                                                 std::vector<std::string_view> choices) {
  const toml::node* node = lookup(key);
  if (!node) return fallback;
  std::string listed;
  for (std::string_view c : choices)
    listed += fmt::format("{}\"{}\"", listed.empty() ? "" : ", ", c);
  const std::string what = "an array of distinct names, each one of " + listed;
  const toml::array* array = node->as_array();
  if (!array) expected(key, *node, what);
  std::vector<std::string> values;
  for (const toml::node& item : *array) {
    if (!item.is_string()) expected(key, *node, what);
    const std::string value = *item.value<std::string>();
    if (std::find(choices.begin(), choices.end(), value) == choices.end()) {
      const std::string guess = closest_name(value, choices);
      throw UserError(
          fmt::format("{}: {}: expected {}, got \"{}\"{}", where_key(key_name(key), item.source()),
                      key_name(key), what, value,
                      guess.empty() ? "" : fmt::format(" (did you mean \"{}\"?)", guess)));
    }
    if (std::find(values.begin(), values.end(), value) != values.end())
      throw UserError(fmt::format("{}: {}: \"{}\" is listed twice",
                                  where_key(key_name(key), item.source()), key_name(key), value));
    values.push_back(value);
  }
  return values;
}

Vec3 TableReader::vec3(std::string_view key, const Vec3& fallback, std::string_view unit,
                       double max_abs) {
  const toml::node* node = lookup(key);
  return node ? vec3_item(key, *node, unit, max_abs) : fallback;
}

Vec3 TableReader::vec3_item(std::string_view key, const toml::node& node, std::string_view unit,
                            double max_abs) const {
  const std::string what =
      std::isfinite(max_abs)
          ? fmt::format("an array of 3 numbers [x, y, z] in {}, each in [{}, {}]", unit,
                        format_number(-max_abs), format_number(max_abs))
          : fmt::format("an array of 3 finite numbers [x, y, z] in {}", unit);
  const toml::array* array = node.as_array();
  if (!array || array->size() != 3) expected(key, node, what);
  Vec3 v;
  for (int i = 0; i < 3; ++i) {
    const toml::node& item = *array->get(i);
    if (!item.is_number()) expected(key, node, what);
    v[i] = *item.value<double>();
    if (!std::isfinite(v[i]) || std::abs(v[i]) > max_abs) expected(key, node, what);
  }
  return v;
}

std::array<double, 2> TableReader::real_pair(std::string_view key, std::array<double, 2> fallback,
                                             Bound bound, std::string_view what_pair) {
  const toml::node* node = lookup(key);
  if (!node) return fallback;
  const std::string what = fmt::format("{}, two numbers {}", what_pair, bound.describe());
  const toml::array* array = node->as_array();
  if (!array || array->size() != 2) expected(key, *node, what);
  std::array<double, 2> result{};
  for (int i = 0; i < 2; ++i) {
    const toml::node& item = *array->get(i);
    if (!item.is_number()) expected(key, *node, what);
    result[i] = *item.value<double>();
    if (!std::isfinite(result[i]) || !bound.contains(result[i])) expected(key, *node, what);
  }
  return result;
}

std::optional<std::array<int, 2>> TableReader::int_pair(std::string_view key, long long low,
                                                        long long high,
                                                        std::string_view what_pair) {
  const toml::node* node = lookup(key);
  if (!node) return std::nullopt;
  const std::string what = fmt::format("{}, two integers in [{}, {}]", what_pair, low, high);
  const toml::array* array = node->as_array();
  if (!array || array->size() != 2) expected(key, *node, what);
  std::array<int, 2> result{};
  for (int i = 0; i < 2; ++i) {
    const toml::node& item = *array->get(i);
    if (!item.is_integer()) expected(key, *node, what);
    const long long x = *item.value<long long>();
    if (x < low || x > high) expected(key, *node, what);
    result[i] = int(x);
  }
  return result;
}

const toml::table* TableReader::subtable(std::string_view key) {
  const toml::node* node = lookup(key);
  if (!node) return nullptr;
  if (!node->is_table()) expected(key, *node, fmt::format("a table [{}]", key_name(key)));
  return node->as_table();
}

void TableReader::finish(std::span<const std::string_view> elsewhere) const {
  for (auto&& [key, node] : table_) {
    const std::string_view name = key.str();
    bool is_known = false;
    for (const std::string& k : known_) is_known = is_known || k == name;
    if (is_known) continue;
    std::vector<std::string_view> local(known_.begin(), known_.end());
    std::string guess = closest_name(name, local);
    if (!guess.empty()) guess = key_name(guess);
    // A key in the wrong table ("mode" at the root) is found by its last component.
    for (std::string_view full : elsewhere) {
      if (!guess.empty()) break;
      const auto dot = full.rfind('.');
      if (dot != std::string_view::npos && full.substr(dot + 1) == name) guess = full;
    }
    throw UserError(fmt::format("{}: unknown key '{}'{}", where_key(key_name(name), key.source()),
                                key_name(name),
                                guess.empty() ? "" : fmt::format(" (did you mean '{}'?)", guess)));
  }
}

}  // namespace flagsim::detail
