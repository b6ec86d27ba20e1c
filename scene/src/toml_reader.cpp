#include "toml_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "flagsim/core/errors.hpp"
#include "flagsim/core/near_miss.hpp"
#include "flagsim/scene/scene_parser.hpp"

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

thread_local KeyLog* t_key_log = nullptr;

}  // namespace

std::string toml_real(double x) {
  std::string text = fmt::format("{}", x);  // the shortest round trip
  if (text.find_first_of(".eEn") == std::string::npos) text += ".0";
  return text;
}

std::string toml_vec3(const Vec3& v) {
  return fmt::format("[{}, {}, {}]", toml_real(v.x()), toml_real(v.y()), toml_real(v.z()));
}

KeyLog::KeyLog() {
  t_key_log = this;
}
KeyLog::~KeyLog() {
  t_key_log = nullptr;
}

void TableReader::note(std::string_view key, std::string value, std::string_view unit,
                       std::string range) const {
  if (!t_key_log) return;
  t_key_log->records_.push_back(
      {key_name(key), std::move(value), std::string(unit), std::move(range), table_.contains(key)});
}

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
  const std::optional<double> x = read_real(key, bound, unit);
  note(key, x ? toml_real(*x) : std::string(), unit, bound.describe());
  return x;
}

std::optional<double> TableReader::read_real(std::string_view key, Bound bound,
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
  const double x = read_real(key, bound, unit).value_or(fallback);
  note(key, toml_real(x), unit, bound.describe());
  return x;
}

std::optional<long long> TableReader::optional_integer(std::string_view key, long long low,
                                                       long long high) {
  const std::optional<long long> x = read_integer(key, low, high);
  note(key, x ? std::to_string(*x) : std::string(), "",
       fmt::format("an integer in [{}, {}]", low, high));
  return x;
}

std::optional<long long> TableReader::read_integer(std::string_view key, long long low,
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
  const long long x = read_integer(key, low, high).value_or(fallback);
  note(key, std::to_string(x), "", fmt::format("an integer in [{}, {}]", low, high));
  return x;
}

std::string TableReader::string(std::string_view key, std::string fallback) {
  const toml::node* node = lookup(key);
  if (node && !node->is_string()) expected(key, *node, "a string");
  std::string value = node ? *node->value<std::string>() : std::move(fallback);
  // An empty default is "not set": the reader's caller decides what it means.
  note(key, value.empty() && !node ? std::string() : toml_string(value), "", "a string");
  return value;
}

bool TableReader::boolean(std::string_view key, bool fallback) {
  const toml::node* node = lookup(key);
  if (node && !node->is_boolean()) expected(key, *node, "true or false");
  const bool value = node ? *node->value<bool>() : fallback;
  note(key, value ? "true" : "false", "", "true or false");
  return value;
}

std::string TableReader::choice(std::string_view key, std::string fallback,
                                std::vector<std::string_view> choices) {
  const toml::node* node = lookup(key);
  std::string listed;
  for (std::string_view c : choices)
    listed += fmt::format("{}\"{}\"", listed.empty() ? "" : ", ", c);
  const std::string what = "one of " + listed;
  if (!node) {
    note(key, toml_string(fallback), "", what);
    return fallback;
  }
  if (!node->is_string()) expected(key, *node, what);
  std::string value = *node->value<std::string>();
  for (std::string_view c : choices)
    if (value == c) {
      note(key, toml_string(value), "", what);
      return value;
    }
  const std::string guess = closest_name(value, choices);
  throw UserError(fmt::format("{}: {}: expected {}, got \"{}\"{}",
                              where_key(key_name(key), node->source()), key_name(key), what, value,
                              guess.empty() ? "" : fmt::format(" (did you mean \"{}\"?)", guess)));
}

std::vector<std::string> TableReader::choice_set(std::string_view key,
                                                 std::vector<std::string> fallback,
                                                 const std::vector<std::string_view>& choices) {
  std::vector<std::string> values = read_choice_set(key, std::move(fallback), choices);
  std::string text;
  for (const std::string& value : values)
    text += fmt::format("{}{}", text.empty() ? "" : ", ", toml_string(value));
  std::string listed;
  for (std::string_view c : choices)
    listed += fmt::format("{}\"{}\"", listed.empty() ? "" : ", ", c);
  note(key, "[" + text + "]", "", "distinct names, each one of " + listed);
  return values;
}

std::vector<std::string> TableReader::read_choice_set(
    std::string_view key, std::vector<std::string> fallback,
    const std::vector<std::string_view>& choices) {
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
  Vec3 v = node ? vec3_item(key, *node, unit, max_abs) : fallback;
  note(key, toml_vec3(v), unit,
       std::isfinite(max_abs) ? fmt::format("[x, y, z], each in [{}, {}]", format_number(-max_abs),
                                            format_number(max_abs))
                              : "[x, y, z] of finite numbers");
  return v;
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
  const std::array<double, 2> pair = read_real_pair(key, fallback, bound, what_pair);
  note(key, fmt::format("[{}, {}]", toml_real(pair[0]), toml_real(pair[1])), what_pair,
       "two numbers " + bound.describe());
  return pair;
}

std::array<double, 2> TableReader::read_real_pair(std::string_view key,
                                                  std::array<double, 2> fallback, Bound bound,
                                                  std::string_view what_pair) {
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
                                                        long long high, std::string_view what_pair,
                                                        std::optional<std::array<int, 2>> shown) {
  const std::optional<std::array<int, 2>> pair = read_int_pair(key, low, high, what_pair);
  const std::optional<std::array<int, 2>> taken = pair ? pair : shown;
  note(key, taken ? fmt::format("[{}, {}]", (*taken)[0], (*taken)[1]) : std::string(), what_pair,
       fmt::format("two integers in [{}, {}]", low, high));
  return pair;
}

std::optional<std::array<int, 2>> TableReader::read_int_pair(std::string_view key, long long low,
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
  // The unknown key that comes first in the file (the table iterates in key
  // order: "two bad keys reported line 21 before line 19", issue 33 item 8).
  const toml::key* first = nullptr;
  const auto before = [](const toml::source_position& a, const toml::source_position& b) {
    return a.line < b.line || (a.line == b.line && a.column < b.column);
  };
  for (auto&& [key, node] : table_) {
    bool is_known = false;
    for (const std::string& k : known_) is_known = is_known || k == key.str();
    if (!is_known && (!first || before(key.source().begin, first->source().begin))) first = &key;
  }
  if (first) {
    const toml::key& key = *first;
    const std::string_view name = key.str();
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
