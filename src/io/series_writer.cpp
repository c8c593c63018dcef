#include "io/series_writer.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include "output/series_row.h"

namespace periflex {

namespace {

// The header line of series.csv: the column names, comma-separated.
std::string header_line(const std::vector<std::string>& columns) {
  std::string header;
  for (size_t k = 0; k < columns.size(); ++k) header += (k ? "," : "") + columns[k];
  return header;
}

}  // namespace

SeriesWriter::SeriesWriter(const std::string& path, const std::vector<std::string>& probe_columns,
                           bool with_damage, bool with_contact, const std::string& earlier_rows)
    : path_(path), with_damage_(with_damage), with_contact_(with_contact) {
  columns_ = series_columns(probe_columns, with_damage_, with_contact_);

  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
  write_all(header_line(columns_) + '\n' + earlier_rows);
}

std::string series_rows_before(const std::string& path, const std::vector<std::string>& columns, double time) {
  std::ifstream in(path, std::ios::binary);
  std::string header;
  if (!in || !std::getline(in, header)) return "";
  if (header != header_line(columns)) return "";
  // a whole row: as many numbers as the header has columns, ended by a line break
  const auto whole_row = [&columns](const std::string& line, double& t) {
    const char* at = line.data();
    const char* end = line.data() + line.size();
    for (size_t k = 0; k < columns.size(); ++k) {
      double value = 0.0;
      const auto parsed = std::from_chars(at, end, value);
      if (parsed.ec != std::errc() || parsed.ptr != (k + 1 < columns.size() ? std::find(at, end, ',') : end))
        return false;
      if (k == 0) t = value;
      at = parsed.ptr + 1;
    }
    return true;
  };
  std::string kept, line;
  double t = 0.0;
  while (std::getline(in, line) && !in.eof() && whole_row(line, t) && t < time) {
    kept += line;
    kept += '\n';
  }
  return kept;
}

SeriesWriter::~SeriesWriter() {
  if (fd_ >= 0) ::close(fd_);
}

void SeriesWriter::write_all(const std::string& text) {
  // one write() call hands the whole line to the kernel, so a kill leaves whole rows; the loop
  // only continues after a signal or a short write (a full disk)
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd_, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int error = errno;
      // a full disk took part of the line: the file keeps its whole lines only
      if (done > 0 && ::ftruncate(fd_, size_) == 0) ::lseek(fd_, size_, SEEK_SET);
      throw std::runtime_error("could not write to " + path_ + " (" + std::strerror(error) + ")");
    }
    done += static_cast<size_t>(n);
  }
  size_ += static_cast<off_t>(text.size());
}

bool SeriesWriter::write(const Sample& s) {
  series_values(s, with_damage_, with_contact_, values_);
  const std::vector<double>& values = values_;
  for (double v : values) {
    if (!std::isfinite(v)) return false;
  }

  // Format the whole row first, then hand it to the file in one write and flush.
  line_.clear();
  // the shortest text that reads back as the same double: a value taken from the file is the
  // solver's, bit for bit (at most 24 characters: sign, 17 digits, point, exponent)
  char buffer[32];
  for (size_t k = 0; k < values.size(); ++k) {
    const auto written = std::to_chars(buffer, buffer + sizeof buffer, values[k]);
    if (k) line_ += ',';
    line_.append(buffer, written.ptr);
  }
  line_ += '\n';
  write_all(line_);
  ++rows_;
  return true;
}

}  // namespace periflex
