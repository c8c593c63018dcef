// Reading what `periflex run` wrote: series.csv as numbers by column, summary.json, and the
// files of a frames folder.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "support/json_text.h"

namespace periflex::testing {

struct Series {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
  long incomplete_rows = 0;  // rows with another number of fields than the header, or not ending in a newline

  // the index of a column, or -1 when series.csv has none of that name (optional columns)
  int find_column(const std::string& name) const {
    for (size_t k = 0; k < columns.size(); ++k) {
      if (columns[k] == name) return static_cast<int>(k);
    }
    return -1;
  }
  // the index of a column the test requires: a missing one fails the test
  int column(const std::string& name) const {
    const int k = find_column(name);
    if (k >= 0) return k;
    ADD_FAILURE() << "series.csv has no column " << name;
    return 0;
  }
};

inline std::vector<std::string> split_commas(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  std::string field;
  while (std::getline(in, field, ',')) fields.push_back(field);
  return fields;
}

inline Series read_series(const std::filesystem::path& path) {
  Series s;
  std::ifstream in(path, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  size_t start = 0;
  bool header = true;
  while (start < text.size()) {
    const size_t end = text.find('\n', start);
    if (end == std::string::npos) {  // a cut last line
      ++s.incomplete_rows;
      break;
    }
    const auto fields = split_commas(text.substr(start, end - start));
    start = end + 1;
    if (header) {
      s.columns = fields;
      header = false;
      continue;
    }
    if (fields.size() != s.columns.size()) {
      ++s.incomplete_rows;
      continue;
    }
    std::vector<double> row;
    for (const auto& f : fields) row.push_back(std::stod(f));
    s.rows.push_back(std::move(row));
  }
  return s;
}

inline nlohmann::json read_summary(const std::filesystem::path& path) { return read_json_file(path); }

// The files of a folder with that extension (".png"), sorted by name; none for a missing folder.
inline std::vector<std::filesystem::path> files_with_extension(const std::filesystem::path& dir,
                                                               const std::string& extension) {
  std::vector<std::filesystem::path> files;
  if (!std::filesystem::is_directory(dir)) return files;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.path().extension() == extension) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

inline long count_files(const std::filesystem::path& dir, const std::string& extension) {
  long n = 0;
  if (!std::filesystem::is_directory(dir)) return 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() == extension) ++n;
  }
  return n;
}

// Frames of a movie as ffprobe decodes them, or -1 when ffprobe is missing or cannot read it.
inline long movie_frames(const std::filesystem::path& movie) {
  const std::string command = "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                              "stream=nb_read_frames -of csv=p=0 '" + movie.string() + "' 2>/dev/null";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return -1;
  char buffer[64] = {0};
  const bool read = std::fgets(buffer, sizeof buffer, pipe) != nullptr;
  const int status = pclose(pipe);
  if (!read || status != 0) return -1;
  return std::atol(buffer);
}

inline bool have_program(const std::string& name) {
  return std::system(("command -v " + name + " >/dev/null 2>&1").c_str()) == 0;
}

}  // namespace periflex::testing
