#include "scene/point_file_reader.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>

#include "core/error.h"
#include "scene/toml_reader.h"

namespace periflex {

namespace {

// Longest line accepted: a point is a few numbers; anything longer is not a point file.
constexpr size_t kMaxLineLength = 4096;

[[noreturn]] void fail_at(const std::string& path, long line, const std::string& message) {
  throw InputError(SourceLocation{path, static_cast<int>(line), 0, "shape.file"}, message);
}

// Reads the next line into `text`; false at the end. A line over kMaxLineLength is an error.
bool next_line(std::istream& in, std::string& text, const std::string& path, long line) {
  if (!std::getline(in, text)) {
    if (!in.eof()) fail_at(path, line, "cannot be read (" + std::string(std::strerror(errno)) + ")");
    return false;
  }
  if (text.size() > kMaxLineLength)
    fail_at(path, line, "line is longer than " + std::to_string(kMaxLineLength) + " characters; not a point file?");
  if (!text.empty() && text.back() == '\r') text.pop_back();
  return true;
}

// The line without its comment, trimmed; empty when nothing is left.
std::string_view content(const std::string& text) {
  std::string_view s(text);
  const size_t hash = s.find('#');
  if (hash != std::string_view::npos) s = s.substr(0, hash);
  const size_t first = s.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  const size_t last = s.find_last_not_of(" \t");
  return s.substr(first, last - first + 1);
}

// Splits on commas when there is one, else on blanks.
std::vector<std::string_view> fields(std::string_view s) {
  std::vector<std::string_view> out;
  const bool commas = s.find(',') != std::string_view::npos;
  size_t at = 0;
  while (at <= s.size()) {
    size_t end = commas ? s.find(',', at) : s.find_first_of(" \t", at);
    if (end == std::string_view::npos) end = s.size();
    std::string_view f = s.substr(at, end - at);
    while (!f.empty() && (f.front() == ' ' || f.front() == '\t')) f.remove_prefix(1);
    while (!f.empty() && (f.back() == ' ' || f.back() == '\t')) f.remove_suffix(1);
    if (commas || !f.empty()) out.push_back(f);
    if (!commas) {
      const size_t next = s.find_first_not_of(" \t", end);
      if (next == std::string_view::npos) break;
      at = next;
    } else {
      at = end + 1;
    }
  }
  return out;
}

bool parse_double(std::string_view f, double& value) {
  if (!f.empty() && f.front() == '+') f.remove_prefix(1);
  const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), value);
  return ec == std::errc() && end == f.data() + f.size() && std::isfinite(value);
}

// A header: the first content line whose first field is not a number.
bool is_header(std::string_view s) {
  double value = 0.0;
  const auto f = fields(s);
  return !f.empty() && !parse_double(f.front(), value);
}

}  // namespace

ParticleCloud read_point_file(const std::string& path, const PointFileOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail_at(path, 0, "cannot be opened (" + std::string(std::strerror(errno)) + ")");

  // the data lines counted first, so a file over the budget allocates nothing
  std::string text;
  long line = 0, data_lines = 0;
  bool seen_content = false;
  while (next_line(in, text, path, line + 1)) {
    ++line;
    const std::string_view s = content(text);
    if (s.empty()) continue;
    if (!seen_content && is_header(s)) {
      seen_content = true;
      continue;
    }
    seen_content = true;
    ++data_lines;
  }
  if (static_cast<double>(data_lines) > options.max_points)
    fail_at(path, 0, "holds " + format_count(static_cast<double>(data_lines)) + " points, more than limits.max_particles = " +
                         format_count(options.max_points) + "; raise limits.max_particles or thin the file");

  // then the points themselves
  in.clear();
  in.seekg(0);
  ParticleCloud cloud;
  cloud.source = "points " + path;
  cloud.x.reserve(data_lines);
  cloud.y.reserve(data_lines);
  cloud.volume.reserve(data_lines);
  cloud.no_fail.reserve(data_lines);
  cloud.line.reserve(data_lines);
  const double scale3 = options.scale * options.scale * options.scale;
  line = 0;
  seen_content = false;
  while (next_line(in, text, path, line + 1)) {
    ++line;
    const std::string_view s = content(text);
    if (s.empty()) continue;
    if (!seen_content && is_header(s)) {
      seen_content = true;
      continue;
    }
    seen_content = true;
    const auto f = fields(s);
    if (f.size() < 3 || f.size() > 5)
      fail_at(path, line, "expected 3 to 5 columns (x, y, volume[, block[, no_fail]]), found " + std::to_string(f.size()));
    double v[5] = {0, 0, 0, 0, 0};
    static const char* const kNames[5] = {"x", "y", "volume", "block", "no_fail"};
    for (size_t k = 0; k < f.size(); ++k)
      if (!parse_double(f[k], v[k]))
        fail_at(path, line, "column " + std::to_string(k + 1) + " (" + kNames[k] + ") is not a finite number: '" +
                                std::string(f[k]) + "'");
    if (!(v[2] > 0.0)) fail_at(path, line, "volume must be positive, found " + format_number(v[2]));
    if (f.size() >= 4 && v[3] != std::floor(v[3]))
      fail_at(path, line, "block must be a whole number, found " + format_number(v[3]));
    if (f.size() == 5 && v[4] != 0.0 && v[4] != 1.0)
      fail_at(path, line, "no_fail must be 0 or 1, found " + format_number(v[4]));
    if (options.block >= 0 && (f.size() < 4 || static_cast<long>(v[3]) != options.block)) continue;
    cloud.x.push_back(v[0] * options.scale);
    cloud.y.push_back(v[1] * options.scale);
    cloud.volume.push_back(v[2] * scale3);
    cloud.no_fail.push_back(v[4] != 0.0 ? 1 : 0);
    cloud.line.push_back(line);
    // a block column on some rows only leaves those without it in no block (-1)
    if (f.size() >= 4 && cloud.block.size() + 1 < cloud.x.size()) cloud.block.assign(cloud.x.size() - 1, -1);
    if (f.size() >= 4 || !cloud.block.empty()) cloud.block.push_back(f.size() >= 4 ? static_cast<long>(v[3]) : -1);
  }
  if (cloud.size() == 0)
    fail_at(path, 0, options.block >= 0 ? "has no point in block " + std::to_string(options.block) : std::string("has no point"));
  return cloud;
}

}  // namespace periflex
