#include "scene/toml_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace periflex {

// ---------------------------------------------------------------------------
// Context

SourceLocation ReadContext::locate(const toml::node* node, const std::string& key) const {
  SourceLocation where;
  where.file = file;
  where.key = key;
  if (node == nullptr) return where;
  // an override has no position in the file: it is located on the command line
  if (override_origin.count(node) != 0) {
    where.file = "--set";
    return where;
  }
  where.line = static_cast<int>(node->source().begin.line);
  where.column = static_cast<int>(node->source().begin.column);
  return where;
}

void ReadContext::fail(const toml::node* node, const std::string& key, const std::string& message) const {
  const auto origin = node != nullptr ? override_origin.find(node) : override_origin.end();
  if (origin != override_origin.end()) throw InputError(locate(node, key), "override '" + origin->second + "': " + message);
  throw InputError(locate(node, key), message);
}

std::string describe_type(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a floating-point number";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    case toml::node_type::date: return "a date";
    case toml::node_type::time: return "a time";
    case toml::node_type::date_time: return "a date-time";
    case toml::node_type::none: break;
  }
  return "nothing";
}

toml::table parse_toml_located(std::string_view text, const std::string& display_path) {
  try {
    return toml::parse(text, display_path);
  } catch (const toml::parse_error& e) {
    SourceLocation where;
    where.file = display_path;
    where.line = static_cast<int>(e.source().begin.line);
    where.column = static_cast<int>(e.source().begin.column);
    throw InputError(where, "TOML syntax error: " + std::string(e.description()));
  }
}

std::string format_number(double value) {
  std::ostringstream out;
  out.precision(10);
  out << value;
  return out.str();
}

std::string format_count(double value) {
  // doubles hold every whole number exactly up to 2^53; beyond it the digits are still the
  // value's own
  if (!std::isfinite(value) || value != std::floor(value) || std::abs(value) >= 1e30) return format_number(value);
  char text[64];
  std::snprintf(text, sizeof text, "%.0f", value);
  return text;
}

// ---------------------------------------------------------------------------
// Free readers

double read_number(const ReadContext& context, const toml::node& node, const std::string& key, Sign sign,
                   bool geometric) {
  // ints are accepted where floats are expected
  double value = 0.0;
  if (const auto* i = node.as_integer()) {
    value = static_cast<double>(i->get());
  } else if (const auto* f = node.as_floating_point()) {
    value = f->get();
  } else {
    context.fail(&node, key, "expected a number, found " + describe_type(node));
  }
  // numbers must be finite and, where they measure space or time, of sane size
  if (!std::isfinite(value)) context.fail(&node, key, "expected a finite number, found " + format_number(value));
  if (geometric && std::abs(value) > kMaxGeometricMagnitude)
    context.fail(&node, key, "value " + format_number(value) + " is absurdly large (the limit for lengths, "
                 "coordinates, times and function values is " + format_number(kMaxGeometricMagnitude) + ")");
  if (sign == Sign::kPositive && !(value > 0.0))
    context.fail(&node, key, "must be positive, found " + format_number(value));
  if (sign == Sign::kNonNegative && value < 0.0)
    context.fail(&node, key, "must not be negative, found " + format_number(value));
  return value;
}

Vec2 read_vec2(const ReadContext& context, const toml::node& node, const std::string& key) {
  // an [x, y] pair of numbers
  const auto* array = node.as_array();
  if (array == nullptr) context.fail(&node, key, "expected an [x, y] array, found " + describe_type(node));
  if (array->size() != 2)
    context.fail(&node, key, "expected an [x, y] array of 2 numbers, found " + std::to_string(array->size()) +
                 " elements");
  return Vec2(read_number(context, *array->get(0), key, Sign::kAny, true),
              read_number(context, *array->get(1), key, Sign::kAny, true));
}

std::vector<double> read_number_list(const ReadContext& context, const toml::node& node, const std::string& key,
                                     bool geometric) {
  const auto* array = node.as_array();
  if (array == nullptr) context.fail(&node, key, "expected an array of numbers, found " + describe_type(node));
  std::vector<double> out;
  out.reserve(array->size());
  for (const toml::node& element : *array) out.push_back(read_number(context, element, key, Sign::kAny, geometric));
  return out;
}

// ---------------------------------------------------------------------------
// TableReader

TableReader::TableReader(const ReadContext& context, const toml::table& table, std::string path, std::string label)
    : context_(context), table_(table), path_(std::move(path)), label_(std::move(label)) {}

std::string TableReader::key_path(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

SourceLocation TableReader::where() const { return context_.locate(&table_, path_); }

const toml::node* TableReader::node(std::string_view key) {
  if (std::find(asked_.begin(), asked_.end(), key) == asked_.end()) asked_.emplace_back(key);
  return table_.get(key);
}

void TableReader::fail(std::string_view key, const std::string& message) const {
  const toml::node* at = table_.get(key);
  context_.fail(at != nullptr ? at : &table_, key_path(key), message);
}

void TableReader::fail_missing(std::string_view key, const std::string& why) const {
  context_.fail(&table_, key_path(key),
                "missing required key '" + std::string(key) + "' in " + label_ + (why.empty() ? "" : " (" + why + ")"));
}

std::optional<double> TableReader::optional_number(std::string_view key, Sign sign, bool geometric) {
  const toml::node* at = node(key);
  if (at == nullptr) return std::nullopt;
  return read_number(context_, *at, key_path(key), sign, geometric);
}

double TableReader::number(std::string_view key, double fallback, Sign sign, bool geometric) {
  return optional_number(key, sign, geometric).value_or(fallback);
}

double TableReader::required_number(std::string_view key, Sign sign, bool geometric) {
  const auto value = optional_number(key, sign, geometric);
  if (!value) fail_missing(key);
  return *value;
}

long TableReader::integer(std::string_view key, long fallback, long minimum) {
  const toml::node* at = node(key);
  if (at == nullptr) return fallback;
  const auto* i = at->as_integer();
  if (i == nullptr) fail(key, "expected an integer, found " + describe_type(*at));
  if (i->get() < minimum) fail(key, "must be at least " + std::to_string(minimum) + ", found " + std::to_string(i->get()));
  // the caller stores these in int; refuse what does not fit
  if (i->get() > 1'000'000'000) fail(key, "value " + std::to_string(i->get()) + " is absurdly large");
  return static_cast<long>(i->get());
}

std::optional<Vec2> TableReader::optional_vec2(std::string_view key) {
  const toml::node* at = node(key);
  if (at == nullptr) return std::nullopt;
  return read_vec2(context_, *at, key_path(key));
}

Vec2 TableReader::vec2(std::string_view key, const Vec2& fallback) { return optional_vec2(key).value_or(fallback); }

Vec2 TableReader::required_vec2(std::string_view key) {
  const auto value = optional_vec2(key);
  if (!value) fail_missing(key);
  return *value;
}

Vec2 TableReader::axis(std::string_view key, const Vec2& fallback) {
  const Vec2 value = vec2(key, fallback);
  // a direction needs a length to be normalised
  if (!(value.norm() > 1e-12)) fail(key, "a zero-length axis has no direction");
  return value.normalized();
}

bool TableReader::boolean(std::string_view key, bool fallback) {
  const toml::node* at = node(key);
  if (at == nullptr) return fallback;
  const auto* b = at->as_boolean();
  if (b == nullptr) fail(key, "expected a boolean (true or false), found " + describe_type(*at));
  return b->get();
}

std::optional<std::string> TableReader::optional_string(std::string_view key) {
  const toml::node* at = node(key);
  if (at == nullptr) return std::nullopt;
  const auto* s = at->as_string();
  if (s == nullptr) fail(key, "expected a string, found " + describe_type(*at));
  return s->get();
}

std::string TableReader::string(std::string_view key, const std::string& fallback) {
  return optional_string(key).value_or(fallback);
}

std::string TableReader::required_string(std::string_view key) {
  const auto value = optional_string(key);
  if (!value) fail_missing(key);
  return *value;
}

std::vector<std::string> TableReader::strings(std::string_view key) {
  const toml::node* value = node(key);
  if (!value) return {};
  if (const auto* s = value->as_string()) return {s->get()};
  const toml::array* array = value->as_array();
  if (!array) fail(key, "expected a string or an array of strings, found " + describe_type(*value));
  std::vector<std::string> out;
  for (const toml::node& item : *array) {
    const auto* s = item.as_string();
    if (!s) fail(key, "expected strings only, found " + describe_type(item));
    out.push_back(s->get());
  }
  return out;
}

static std::string join(const std::vector<std::string>& words, const std::string& separator) {
  std::string out;
  for (size_t k = 0; k < words.size(); ++k) out += (k ? separator : "") + words[k];
  return out;
}

std::string TableReader::choice(std::string_view key, const std::vector<std::string>& choices,
                                const std::string& fallback) {
  const std::string value = string(key, fallback);
  if (std::find(choices.begin(), choices.end(), value) == choices.end())
    fail(key, "unknown " + std::string(key) + " '" + value + "'; expected one of: " + join(choices, ", "));
  return value;
}

std::string TableReader::required_choice(std::string_view key, const std::vector<std::string>& choices) {
  if (!has(key)) {
    node(key);
    fail_missing(key, "one of: " + join(choices, ", "));
  }
  return choice(key, choices, "");
}

const toml::table* TableReader::optional_table(std::string_view key) {
  const toml::node* at = node(key);
  if (at == nullptr) return nullptr;
  const auto* t = at->as_table();
  if (t == nullptr) fail(key, "expected a table, found " + describe_type(*at));
  return t;
}

const toml::array* TableReader::optional_array(std::string_view key) {
  const toml::node* at = node(key);
  if (at == nullptr) return nullptr;
  const auto* a = at->as_array();
  if (a == nullptr) fail(key, "expected an array, found " + describe_type(*at));
  return a;
}

void TableReader::finish(const std::set<std::string>& other_keys, const std::string& variant) const {
  // the first key in file order that nobody asked for is the one to report
  const toml::key* first = nullptr;
  const toml::node* first_node = nullptr;
  for (const auto& [k, v] : table_) {
    if (std::find(asked_.begin(), asked_.end(), k.str()) != asked_.end()) continue;
    const bool earlier = first == nullptr || k.source().begin.line < first->source().begin.line ||
                         (k.source().begin.line == first->source().begin.line &&
                          k.source().begin.column < first->source().begin.column);
    if (earlier) {
      first = &k;
      first_node = &v;
    }
  }
  if (first == nullptr) return;
  const std::string name(first->str());
  // report at the key itself; an override-inserted value is located at --set
  SourceLocation where = context_.locate(first_node, key_path(name));
  if (where.file != "--set" && first->source().begin.line > 0) {
    where.line = static_cast<int>(first->source().begin.line);
    where.column = static_cast<int>(first->source().begin.column);
  }
  std::string message;
  if (other_keys.count(name) != 0)
    message = "key '" + name + "' does not apply to " + variant + " in " + label_ + "; expected one of: " +
              join(asked_, ", ");
  else
    message = "unknown key '" + name + "' in " + label_ + "; expected one of: " + join(asked_, ", ");
  const auto origin = context_.override_origin.find(first_node);
  if (origin != context_.override_origin.end()) message = "override '" + origin->second + "': " + message;
  throw InputError(where, message);
}

}  // namespace periflex
