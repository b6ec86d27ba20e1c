#pragma once
// Typed, range-checked reads from one TOML table, each marking its key as known,
// so that finish() can reject the keys nobody read (unknown or misspelt).
// Every failure throws UserError "FILE:LINE:COL: KEY: expected ..., got ...".
#include <toml++/toml.h>

#include <array>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "flagsim/core/enum_names.hpp"
#include "flagsim/core/vec3.hpp"

namespace flagsim::detail {

/// "FILE:LINE:COL" of a node read from the scene file.
std::string where(const toml::source_region& source);

/// While alive, errors about the given dotted keys (or keys under them) name
/// the --set override they came from: toml++ drops the source of a node copied
/// into the scene table, so the overrides are remembered here. One per parse.
class OverrideLabels {
 public:
  explicit OverrideLabels(std::vector<std::pair<std::string, std::string>> key_to_label);
  ~OverrideLabels();
  OverrideLabels(const OverrideLabels&) = delete;
  OverrideLabels& operator=(const OverrideLabels&) = delete;
};

/// Where dotted key `key` (written at `source`) came from: its --set override,
/// or FILE:LINE:COL.
std::string where_key(const std::string& key, const toml::source_region& source);

/// One key as a parse read it (for `flag-sim scene` and `help keys`).
struct KeyRecord {
  std::string key;     ///< dotted
  std::string value;   ///< TOML text of the value the scene takes; "" for an absent optional key
  std::string unit;    ///< as the read states it
  std::string range;   ///< what the read accepts
  bool given = false;  ///< in the table (the file or an override); else the default
};

/// While alive, every TableReader read of this thread is recorded here, in
/// reading order. One per parse.
class KeyLog {
 public:
  KeyLog();
  ~KeyLog();
  KeyLog(const KeyLog&) = delete;
  KeyLog& operator=(const KeyLog&) = delete;
  const std::vector<KeyRecord>& records() const { return records_; }

 private:
  friend class TableReader;
  std::vector<KeyRecord> records_;
};

/// A double as TOML writes it back: the shortest text that reads back to the
/// same double, with a decimal point ("0.2", "20000.0", "1e-06").
std::string toml_real(double x);
/// [x, y, z] as TOML, each as toml_real.
std::string toml_vec3(const Vec3& v);

/// An allowed interval for a number, with its description for messages.
struct Bound {
  double low = -1e300;
  double high = 1e300;
  bool low_open = false;  ///< true: value must be > low (else >= low)
  static Bound positive() { return {0.0, 1e300, true}; }
  static Bound non_negative() { return {0.0, 1e300, false}; }
  static Bound any() { return {}; }
  static Bound between(double lo, double hi) { return {lo, hi, false}; }
  bool contains(double x) const { return (low_open ? x > low : x >= low) && x <= high; }
  std::string describe() const;
};

class TableReader {
 public:
  /// @param table   the table to read
  /// @param prefix  its dotted name ("flag", "wind.gusts"); "" for the root
  /// @param fallback_where  location used when the table has no source (it was absent)
  TableReader(const toml::table& table, std::string prefix, std::string fallback_where);

  const toml::table& table() const { return table_; }
  std::string key_name(std::string_view key) const;
  /// Location of the key's value (or of the table when the key is absent).
  std::string where_of(std::string_view key) const;

  bool has(std::string_view key) const { return table_.contains(key); }
  double real(std::string_view key, double fallback, Bound bound, std::string_view unit);
  std::optional<double> optional_real(std::string_view key, Bound bound, std::string_view unit);
  long long integer(std::string_view key, long long fallback, long long low, long long high);
  std::optional<long long> optional_integer(std::string_view key, long long low, long long high);
  std::string string(std::string_view key, std::string fallback);
  bool boolean(std::string_view key, bool fallback);
  /// One of `choices`; the message lists them and suggests the closest.
  std::string choice(std::string_view key, std::string fallback,
                     std::vector<std::string_view> choices);
  /// One of the names in `table`, as its value (choice() with the table's names).
  template <typename E, std::size_t N>
  E choice_of(std::string_view key, E fallback, const NameTable<E, N>& table) {
    return *value_in(table, choice(key, std::string(name_in(table, fallback)), names_in(table)));
  }
  /// An array of distinct strings, each one of `choices` (in the order given).
  std::vector<std::string> choice_set(std::string_view key, std::vector<std::string> fallback,
                                      const std::vector<std::string_view>& choices);
  /// [x, y, z] of finite numbers, each of magnitude at most `max_abs`.
  Vec3 vec3(std::string_view key, const Vec3& fallback, std::string_view unit,
            double max_abs = std::numeric_limits<double>::infinity());
  /// `node` (an item of the array at `key`) as such an [x, y, z]; errors
  /// point at the item itself.
  Vec3 vec3_item(std::string_view key, const toml::node& node, std::string_view unit,
                 double max_abs = std::numeric_limits<double>::infinity()) const;
  /// [a, b] of numbers inside `bound`.
  std::array<double, 2> real_pair(std::string_view key, std::array<double, 2> fallback, Bound bound,
                                  std::string_view what);
  /// [a, b] of integers in [low, high]; `shown` is the default the caller
  /// keeps when the key is absent (for the KeyLog only).
  std::optional<std::array<int, 2>> int_pair(std::string_view key, long long low, long long high,
                                             std::string_view what,
                                             std::optional<std::array<int, 2>> shown = {});
  /// The sub-table at `key`, if present (must be a table).
  const toml::table* subtable(std::string_view key);
  /// Marks a key as known without reading it (it is read elsewhere).
  void allow(std::string_view key) { known_.emplace_back(key); }
  /// Throws for the first key that no read asked for, with a suggestion.
  /// `elsewhere` are dotted names of all keys in the schema, for "did you mean flag.pin?".
  void finish(std::span<const std::string_view> elsewhere = {}) const;

  [[noreturn]] void fail(std::string_view key, const std::string& message) const;
  /// Appends the read of `key` to the live KeyLog, if any (the typed reads
  /// do; a key read by hand, as keyframe.corners, says it here).
  void note(std::string_view key, std::string value, std::string_view unit,
            std::string range) const;

 private:
  const toml::node* lookup(std::string_view key);
  // The reads themselves, before note().
  std::optional<double> read_real(std::string_view key, Bound bound, std::string_view unit);
  std::optional<long long> read_integer(std::string_view key, long long low, long long high);
  std::vector<std::string> read_choice_set(std::string_view key, std::vector<std::string> fallback,
                                           const std::vector<std::string_view>& choices);
  std::array<double, 2> read_real_pair(std::string_view key, std::array<double, 2> fallback,
                                       Bound bound, std::string_view what_pair);
  std::optional<std::array<int, 2>> read_int_pair(std::string_view key, long long low,
                                                  long long high, std::string_view what_pair);
  [[noreturn]] void expected(std::string_view key, const toml::node& node,
                             const std::string& what) const;

  const toml::table& table_;
  std::string prefix_;
  std::string fallback_where_;
  std::vector<std::string> known_;
};

}  // namespace flagsim::detail
