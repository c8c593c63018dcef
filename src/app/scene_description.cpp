#include "app/scene_description.h"

#include <fstream>
#include <sstream>

namespace periflex {

std::string leading_comment(const std::string& text) {
  std::istringstream in(text);
  std::string line, out;
  bool indented = false;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const size_t first = line.find_first_not_of(" \t");
    // a blank line inside the block: a paragraph break
    if (first == std::string::npos) {
      if (!out.empty() && out.back() != '\n') out += "\n\n";
      continue;
    }
    if (line[first] != '#') break;
    std::string body = line.substr(first + 1);
    if (!body.empty() && body[0] == ' ') body.erase(0, 1);
    // rulers carry no words
    if (!body.empty() && body.find_first_not_of("-=#") == std::string::npos) continue;
    // an empty comment line: a paragraph break (one, however many)
    if (body.find_first_not_of(" \t") == std::string::npos) {
      if (!out.empty() && out.back() != '\n') out += "\n\n";
      continue;
    }
    // joined to the line before unless either is indented or a paragraph begins
    const bool indent = body[0] == ' ' || body[0] == '\t';
    if (!out.empty() && out.back() != '\n') out += (indent || indented) ? "\n" : " ";
    out += body;
    indented = indent;
  }
  while (!out.empty() && out.back() == '\n') out.pop_back();
  return out;
}

std::string scene_description(const std::string& path, const std::string& description) {
  std::ifstream file(path);
  std::stringstream text;
  if (file) text << file.rdbuf();
  const std::string comment = leading_comment(text.str());
  return comment.empty() ? description : comment;
}

}  // namespace periflex
