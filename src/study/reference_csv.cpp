#include "study/reference_csv.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "study/study_def.h"

namespace periflex {

namespace {

constexpr std::uintmax_t kMaxCsvBytes = 256u << 20;

// One cell of a line: its text and 1-based column.
struct Cell {
  std::string text;
  int column = 1;
};

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return {};
  const size_t b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}

std::vector<Cell> split(const std::string& line) {
  std::vector<Cell> cells;
  size_t start = 0;
  while (true) {
    const size_t comma = line.find(',', start);
    const std::string raw = line.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    // the column of the cell's first non-blank character
    const size_t lead = raw.find_first_not_of(" \t");
    cells.push_back({trim(raw), static_cast<int>(start + (lead == std::string::npos ? 0 : lead)) + 1});
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return cells;
}

SourceLocation at(const std::string& path, int line, int column, const std::string& key) {
  SourceLocation where;
  where.file = path;
  where.line = line;
  where.column = column;
  where.key = key;
  return where;
}

}  // namespace

ReferenceCsv parse_reference_csv(const std::string& text, const std::string& path, const std::string& time_column,
                                 const std::vector<std::string>& columns, const SourceLocation& where) {
  ReferenceCsv ref;
  ref.path_ = path;
  ref.names_ = columns;
  ref.columns_.assign(columns.size(), {});
  std::istringstream in(text);
  std::string line;
  int line_number = 0;
  std::vector<int> pick;  // file column of the time, then of each selected column
  size_t width = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const std::string content = trim(line);
    if (content.empty() || content[0] == '#') continue;
    const std::vector<Cell> cells = split(line);
    // the header: every name the study asks for must be there
    if (pick.empty()) {
      width = cells.size();
      std::string available;
      for (const Cell& c : cells) available += (available.empty() ? "" : ", ") + c.text;
      for (const std::string& wanted : [&] {
             std::vector<std::string> all{time_column};
             all.insert(all.end(), columns.begin(), columns.end());
             return all;
           }()) {
        int found = -1;
        for (size_t k = 0; k < cells.size(); ++k)
          if (cells[k].text == wanted) found = static_cast<int>(k);
        if (found < 0)
          throw InputError(at(path, line_number, 1, wanted),
                           "the reference file has no column '" + wanted + "' (its columns: " + available +
                               "); named by " + where.key + " in " + where.file);
        pick.push_back(found);
      }
      continue;
    }
    // a sample: as many cells as the header, the picked ones finite numbers
    if (cells.size() != width)
      throw InputError(at(path, line_number, 1, ""),
                       "this row has " + std::to_string(cells.size()) + " cells, the header " + std::to_string(width));
    std::vector<double> row;
    for (size_t k = 0; k < pick.size(); ++k) {
      const Cell& cell = cells[pick[k]];
      const std::string& name = k == 0 ? time_column : columns[k - 1];
      char* end = nullptr;
      errno = 0;
      const double v = cell.text.empty() ? 0.0 : std::strtod(cell.text.c_str(), &end);
      if (cell.text.empty() || *end != '\0' || !std::isfinite(v) || errno == ERANGE)
        throw InputError(at(path, line_number, cell.column, name),
                         "expected a finite number, found '" + cell.text + "'");
      row.push_back(v);
    }
    // times increase strictly, so each instant has one value to interpolate
    if (!ref.times_.empty() && !(row[0] > ref.times_.back()))
      throw InputError(at(path, line_number, cells[pick[0]].column, time_column),
                       "time " + format_g(row[0]) + " does not increase (the row before has " +
                           format_g(ref.times_.back()) + "): times must increase strictly");
    ref.times_.push_back(row[0]);
    for (size_t k = 1; k < row.size(); ++k) ref.columns_[k - 1].push_back(row[k]);
  }
  if (pick.empty()) throw InputError(at(path, 0, 0, ""), "the reference file is empty (no header line)");
  if (ref.times_.size() < 2)
    throw InputError(at(path, line_number, 0, ""), "the reference file needs at least two samples, found " +
                                                       std::to_string(ref.times_.size()));
  return ref;
}

ReferenceCsv load_reference_csv(const std::string& path, const std::string& time_column,
                                const std::vector<std::string>& columns, const SourceLocation& where) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status))
    throw InputError(where, "cannot read the reference file '" + path + "': it does not exist");
  if (!std::filesystem::is_regular_file(status))
    throw InputError(where, "the reference file '" + path + "' is not a regular file");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec || size > kMaxCsvBytes)
    throw InputError(where, "the reference file '" + path + "' has " + std::to_string(size) +
                                " bytes, more than the limit of " + std::to_string(kMaxCsvBytes));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(where, "cannot read the reference file '" + path + "'");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_reference_csv(text.str(), path, time_column, columns, where);
}

void ReferenceCsv::require_span(double start, double end, const SourceLocation& where) const {
  // a sample may miss the end by round-off in how it was written (a relative 1e-9)
  const double slack = 1e-9 * std::max(1.0, std::abs(end));
  if (times_.front() > start + slack || times_.back() < end - slack)
    throw InputError(where, "the reference file '" + path_ + "' covers t = " + format_g(times_.front()) + " to " +
                                format_g(times_.back()) + " s, not the study's " + format_g(start) + " to " +
                                format_g(end) + " s");
}

std::vector<double> ReferenceCsv::values(double t) const {
  // the six samples nearest t: from two below the interval holding t, shifted inside the file
  const long n = static_cast<long>(times_.size());
  const long above = std::upper_bound(times_.begin(), times_.end(), t) - times_.begin();
  const long points = std::min<long>(6, n);
  const long first = std::clamp<long>(above - 3, 0, n - points);
  std::vector<double> out(columns_.size(), 0.0);
  for (long a = first; a < first + points; ++a) {
    // Lagrange basis polynomial of sample a at t (exactly 1 or 0 at the samples)
    double weight = 1.0;
    for (long b = first; b < first + points; ++b)
      if (b != a) weight *= (t - times_[b]) / (times_[a] - times_[b]);
    for (size_t c = 0; c < columns_.size(); ++c) out[c] += weight * columns_[c][a];
  }
  return out;
}

}  // namespace periflex
