#include "text_match.h"

#include <regex>

namespace periflex::testing {

bool contains_match(const std::string& text, const std::string& pattern) {
  return std::regex_search(text, std::regex(pattern));
}

std::vector<std::string> first_match(const std::string& text, const std::string& pattern) {
  std::smatch m;
  std::vector<std::string> parts;
  if (!std::regex_search(text, m, std::regex(pattern))) return parts;
  for (const auto& part : m) parts.push_back(part.str());
  return parts;
}

std::vector<std::string> all_matches(const std::string& text, const std::string& pattern) {
  const std::regex re(pattern);
  std::vector<std::string> found;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator(); ++it)
    found.push_back(it->str());
  return found;
}

}  // namespace periflex::testing
