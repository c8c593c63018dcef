// Typed, located access to a parsed TOML tree for the scene loader.
//
// Every value read goes through a TableReader, which knows the dotted key path of its table
// ("body.crank"), a human label ("[[body]] 'crank'") and the file. A read of the wrong type,
// a non-finite number, a value out of range, or (at finish()) a key nobody asked for throws
// InputError naming the file, line, column and dotted key. Nodes that came from a --set override
// are reported as "--set" with the override text instead of a file position.
//
// Sections:
//   ReadContext   file name, override origins, error construction
//   Sign          sign rules for numbers
//   TableReader   typed reads from one table, unknown-key detection
#pragma once

#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <toml++/toml.h>

#include "core/error.h"
#include "core/vec2.h"

namespace periflex {

// Largest magnitude accepted where a length, coordinate or time is expected.
constexpr double kMaxGeometricMagnitude = 1e12;

// ---------------------------------------------------------------------------
// What every reader of one scene shares.
struct ReadContext {
  std::string file;  // display path of the scene file
  // Nodes inserted by --set overrides, with the override text that produced them.
  std::unordered_map<const toml::node*, std::string> override_origin;

  // Location of `node` (file, line, column) with `key` as the dotted key; a node from an
  // override is located at "--set". A null node gives the file alone.
  SourceLocation locate(const toml::node* node, const std::string& key) const;
  // Throws InputError at `node`; the message gains "override '...': " when the node came from --set.
  [[noreturn]] void fail(const toml::node* node, const std::string& key, const std::string& message) const;
};

// Parses TOML text; a syntax error becomes an InputError at its line and column in display_path.
toml::table parse_toml_located(std::string_view text, const std::string& display_path);

// "a string", "an integer", ... for messages.
std::string describe_type(const toml::node& node);
// Shortest faithful text of a number for messages.
std::string format_number(double value);
// A count for messages, every digit of it ("1000001", never "1e+06"): a limit or a number of
// rows, frames, steps or particles compared with one reads exactly. A value that is not a whole
// number (a limit given as 2.5) is written as format_number writes it.
std::string format_count(double value);

// ---------------------------------------------------------------------------
// Sign rule for a number.
enum class Sign { kAny, kPositive, kNonNegative };

// Reads typed values out of one TOML table and remembers which keys were asked for.
class TableReader {
 public:
  // path: dotted key of the table ("solver.correction"); label: how messages name it ("[solver.correction]").
  TableReader(const ReadContext& context, const toml::table& table, std::string path, std::string label);

  const ReadContext& context() const { return context_; }
  const toml::table& table() const { return table_; }
  const std::string& path() const { return path_; }
  const std::string& label() const { return label_; }
  // Dotted key of `key` inside this table.
  std::string key_path(std::string_view key) const;
  // Location of the table itself (its header or first line).
  SourceLocation where() const;

  // The node under `key`, or null; marks the key as known.
  const toml::node* node(std::string_view key);
  bool has(std::string_view key) const { return table_.contains(key); }

  // Throws at `key` (or at the table when the key is absent).
  [[noreturn]] void fail(std::string_view key, const std::string& message) const;
  // Throws "missing required key" at the table.
  [[noreturn]] void fail_missing(std::string_view key, const std::string& why = "") const;

  // Numbers: ints are accepted where floats are expected; always finite. A geometric number
  // (length, coordinate, time) must also satisfy |x| <= kMaxGeometricMagnitude.
  std::optional<double> optional_number(std::string_view key, Sign sign = Sign::kAny, bool geometric = false);
  double number(std::string_view key, double fallback, Sign sign = Sign::kAny, bool geometric = false);
  double required_number(std::string_view key, Sign sign = Sign::kAny, bool geometric = false);

  // Integers (no floats) not below `minimum`.
  long integer(std::string_view key, long fallback, long minimum);

  // [x, y] arrays of two numbers; always geometric.
  std::optional<Vec2> optional_vec2(std::string_view key);
  Vec2 vec2(std::string_view key, const Vec2& fallback);
  Vec2 required_vec2(std::string_view key);
  // A direction: non-zero, returned normalised.
  Vec2 axis(std::string_view key, const Vec2& fallback);

  bool boolean(std::string_view key, bool fallback);

  std::optional<std::string> optional_string(std::string_view key);
  std::string string(std::string_view key, const std::string& fallback);
  std::string required_string(std::string_view key);
  // A string or an array of strings; empty when absent.
  std::vector<std::string> strings(std::string_view key);
  // A string that must be one of `choices`; names them when it is not.
  std::string choice(std::string_view key, const std::vector<std::string>& choices, const std::string& fallback);
  std::string required_choice(std::string_view key, const std::vector<std::string>& choices);

  // Sub-table or array under `key`, type-checked; null when absent.
  const toml::table* optional_table(std::string_view key);
  const toml::array* optional_array(std::string_view key);

  // Throws on the first key of the table nobody asked for. `other_keys` are keys valid for
  // other variants of this table (other joint types, ...): they get "does not apply to <variant>".
  void finish(const std::set<std::string>& other_keys = {}, const std::string& variant = "") const;

 private:
  const ReadContext& context_;
  const toml::table& table_;
  std::string path_;
  std::string label_;
  std::vector<std::string> asked_;  // keys asked for, in order, for "expected one of"
};

// Reads a number node: int or float, finite, sign and geometric rules. `key` is dotted.
double read_number(const ReadContext& context, const toml::node& node, const std::string& key,
                   Sign sign = Sign::kAny, bool geometric = false);
// Reads an [x, y] node.
Vec2 read_vec2(const ReadContext& context, const toml::node& node, const std::string& key);
// Reads an array of numbers (any length, geometric when asked).
std::vector<double> read_number_list(const ReadContext& context, const toml::node& node,
                                     const std::string& key, bool geometric = false);

}  // namespace periflex
