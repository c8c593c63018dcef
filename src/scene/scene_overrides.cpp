#include "scene/scene_overrides.h"

#include <algorithm>
#include <cctype>

namespace periflex {

bool is_array_of_tables_key(std::string_view key) {
  static const char* const kKeys[] = {"body", "joint", "driver", "force", "probe", "flex_body", "attachment", "load"};
  return std::any_of(std::begin(kKeys), std::end(kKeys), [&](const char* k) { return key == k; });
}

namespace {

// Error at the command line, naming the override.
[[noreturn]] void fail_override(const std::string& text, const std::string& key, const std::string& message) {
  SourceLocation where;
  where.file = "--set";
  where.key = key;
  throw InputError(where, "override '" + text + "': " + message);
}

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

std::vector<std::string> split_path(const std::string& path) {
  std::vector<std::string> parts;
  size_t start = 0;
  while (true) {
    const size_t dot = path.find('.', start);
    parts.push_back(path.substr(start, dot == std::string::npos ? std::string::npos : dot - start));
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return parts;
}

bool is_bare_word(const std::string& s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  return std::all_of(s.begin(), s.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
  });
}

// The override value as a TOML node: any TOML value, or a bare word taken as a string.
toml::table parse_value(const std::string& text, const std::string& key, const std::string& value) {
  if (value.empty()) fail_override(text, key, "no value after '='");
  try {
    toml::table holder = toml::parse("value = " + value + "\n", std::string_view("--set"));
    // a value smuggling in more keys ("1\nother = 2") is not one value
    if (holder.size() != 1) fail_override(text, key, "'" + value + "' is not a single TOML value");
    return holder;
  } catch (const toml::parse_error& error) {
    if (is_bare_word(value)) {
      toml::table holder;
      holder.insert("value", value);
      return holder;
    }
    fail_override(text, key, "'" + value + "' is not a TOML value (" + std::string(error.description()) + ")");
  }
}

// Records `node` and everything under it as coming from this override.
void mark(const toml::node& node, const std::string& text, ReadContext& context) {
  context.override_origin[&node] = text;
  if (const auto* table = node.as_table())
    for (const auto& [k, v] : *table) mark(v, text, context);
  if (const auto* array = node.as_array())
    for (const toml::node& element : *array) mark(element, text, context);
}

// Forgets `node` and everything under it (about to be replaced).
void unmark(const toml::node& node, ReadContext& context) {
  context.override_origin.erase(&node);
  if (const auto* table = node.as_table())
    for (const auto& [k, v] : *table) unmark(v, context);
  if (const auto* array = node.as_array())
    for (const toml::node& element : *array) unmark(element, context);
}

// Element of `array` named `selector` (a table with name = selector) or at index `selector`.
toml::node* select_element(toml::array& array, const std::string& selector, const std::string& text,
                           const std::string& key, const std::string& array_key) {
  for (toml::node& element : array)
    if (const auto* table = element.as_table())
      if (const auto* name = table->get_as<std::string>("name"); name != nullptr && name->get() == selector)
        return &element;
  // a plain 0-based index
  if (!selector.empty() && std::all_of(selector.begin(), selector.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); })) {
    const size_t index = selector.size() > 9 ? array.size() : std::stoul(selector);
    if (index < array.size()) return array.get(index);
    fail_override(text, key, "index " + selector + " is beyond the " + std::to_string(array.size()) + " elements of '" +
                  array_key + "'");
  }
  std::string names;
  for (toml::node& element : array)
    if (const auto* table = element.as_table())
      if (const auto* name = table->get_as<std::string>("name")) names += (names.empty() ? "" : ", ") + name->get();
  fail_override(text, key, "no element named '" + selector + "' in '" + array_key + "'" +
                (names.empty() ? std::string() : " (names: " + names + ")"));
}

void apply_one(toml::table& root, const std::string& text, ReadContext& context) {
  // split "path=value"
  const size_t equals = text.find('=');
  if (equals == std::string::npos) fail_override(text, "", "expected key.path=value");
  const std::string key = trim(text.substr(0, equals));
  const std::string value_text = trim(text.substr(equals + 1));
  if (key.empty()) fail_override(text, key, "empty key path before '='");
  const std::vector<std::string> parts = split_path(key);
  for (const std::string& part : parts)
    if (part.empty()) fail_override(text, key, "empty segment in key path '" + key + "'");
  const toml::table holder = parse_value(text, key, value_text);
  const toml::node& value = *holder.get("value");

  // walk down to the container of the last segment, creating plain tables that do not exist yet
  toml::node* cursor = &root;
  std::string walked;
  for (size_t k = 0; k + 1 < parts.size(); ++k) {
    const std::string& part = parts[k];
    walked += (walked.empty() ? "" : ".") + part;
    if (auto* table = cursor->as_table()) {
      toml::node* child = table->get(part);
      if (child == nullptr) {
        if (is_array_of_tables_key(part)) fail_override(text, key, "the scene declares no [[" + part + "]]");
        auto [it, inserted] = table->insert(part, toml::table{});
        mark(it->second, text, context);
        child = &it->second;
      }
      cursor = child;
    } else if (auto* array = cursor->as_array()) {
      cursor = select_element(*array, part, text, key, walked.substr(0, walked.rfind('.')));
    }
    if (!cursor->is_table() && !cursor->is_array())
      fail_override(text, key, "'" + walked + "' is " + describe_type(*cursor) + ", not a table");
  }

  // set the last segment
  const std::string& last = parts.back();
  if (auto* table = cursor->as_table()) {
    if (const toml::node* old = table->get(last)) {
      if (old->is_array_of_tables() || is_array_of_tables_key(last))
        fail_override(text, key, "cannot replace the whole '" + last + "' array; set keys of its elements");
      unmark(*old, context);
    }
    auto [it, inserted] = table->insert_or_assign(last, value);
    mark(it->second, text, context);
  } else if (auto* array = cursor->as_array()) {
    toml::node* element = select_element(*array, last, text, key, walked);
    unmark(*element, context);
    // find the element's position to replace it in place
    auto position = array->cbegin();
    for (auto it = array->begin(); it != array->end(); ++it, ++position)
      if (&*it == element) break;
    auto replaced = array->replace(position, value);
    mark(*replaced, text, context);
  }
}

}  // namespace

void apply_overrides(toml::table& root, const std::vector<std::string>& overrides, ReadContext& context) {
  for (const std::string& text : overrides) apply_one(root, text, context);
}

}  // namespace periflex
