#include "io/series_writer.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "output/series_row.h"

namespace periflex {

SeriesWriter::SeriesWriter(const std::string& path, const std::vector<std::string>& probe_columns,
                           bool with_damage, bool with_contact)
    : path_(path), with_damage_(with_damage), with_contact_(with_contact) {
  columns_ = series_columns(probe_columns, with_damage_, with_contact_);

  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
  std::string header;
  for (size_t k = 0; k < columns_.size(); ++k) header += (k ? "," : "") + columns_[k];
  header += '\n';
  write_all(header);
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
    if (n <= 0) throw std::runtime_error("could not write to " + path_ + " (" + std::strerror(errno) + ")");
    done += static_cast<size_t>(n);
  }
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
