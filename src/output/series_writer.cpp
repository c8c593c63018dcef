#include "output/series_writer.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace periflex {

SeriesWriter::SeriesWriter(const std::string& path, const std::vector<std::string>& probe_columns,
                           bool with_damage, bool with_contact)
    : path_(path), with_damage_(with_damage), with_contact_(with_contact) {
  columns_ = {"t",           "kinetic",     "potential_gravity", "potential_elastic", "dissipated",
              "fracture",    "external_work", "driver_work",     "energy_balance",    "violation_position",
              "violation_velocity"};
  if (with_damage_) {
    for (const char* c : {"broken_bonds", "mean_damage", "max_damage"}) columns_.push_back(c);
  }
  if (with_contact_) {
    for (const char* c : {"contact_force_total", "contact_count"}) columns_.push_back(c);
  }
  columns_.insert(columns_.end(), probe_columns.begin(), probe_columns.end());

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
  const Energies& e = s.energies;
  std::vector<double> values = {s.time,       e.kinetic,     e.potential_gravity, e.potential_elastic,
                                e.dissipated, e.fracture,    e.external_work,     e.driver_work,
                                e.balance,    s.violation_position, s.violation_velocity};
  if (with_damage_) {
    values.push_back(static_cast<double>(s.broken_bonds));
    values.push_back(s.mean_damage);
    values.push_back(s.max_damage);
  }
  if (with_contact_) {
    values.push_back(s.contact_force_total);
    values.push_back(static_cast<double>(s.contact_count));
  }
  values.insert(values.end(), s.probe_values.begin(), s.probe_values.end());
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
