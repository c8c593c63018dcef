// A reference trajectory from a CSV file, so any benchmark's published (or independently
// computed) motion can be studied: a time column and named value columns, e.g.
//
//   t,probe.bob.x,probe.bob.y
//   0,1,0
//   0.01,0.99999951,-0.00049050
//
//   ReferenceCsv ref = load_reference_csv("a01.csv", "t", {"probe.bob.x", "probe.bob.y"}, where);
//   ref.require_span(0.0, 20.0, where);
//   std::vector<double> v = ref.values(1.234);   // the named columns, in the order asked
//
// Between samples the values are interpolated by the Lagrange polynomial of degree 5 through the
// six nearest samples (fewer at the ends of a short file): its error is
// |x^(6)(xi)| / 720 * prod |t - t_k| <= |x^(6)| h^6 * 3.52 / 720 in the middle interval of six
// equally spaced samples, so about (omega h)^6 / 200 of the amplitude for a motion of angular
// frequency omega sampled every h (4e-12 of it at omega h = 0.03); at the samples themselves the
// values are the file's. Exit-2 errors name file:line:column and the column.
#pragma once

#include <string>
#include <vector>

#include "core/error.h"

namespace periflex {

class ReferenceCsv {
 public:
  // Values of the selected columns at time t (t within the file's span).
  std::vector<double> values(double t) const;
  // Throws InputError at `where` unless the samples cover [start, end].
  void require_span(double start, double end, const SourceLocation& where) const;
  double first_time() const { return times_.front(); }
  double last_time() const { return times_.back(); }
  size_t samples() const { return times_.size(); }
  const std::vector<std::string>& columns() const { return names_; }
  const std::string& path() const { return path_; }

 private:
  friend ReferenceCsv parse_reference_csv(const std::string&, const std::string&, const std::string&,
                                          const std::vector<std::string>&, const SourceLocation&);
  std::string path_;
  std::vector<std::string> names_;
  std::vector<double> times_;
  std::vector<std::vector<double>> columns_;  // per selected column, one value per sample
};

// Reads `path` (a regular file of at most 256 MB): a header line of comma-separated names, then
// one row of numbers per sample; blank lines and lines starting with '#' are skipped. Only the
// time column and `columns` are kept. Throws InputError for a missing file or column (at
// `where`, the study key that named it), a cell that is not a finite number, a row of the wrong
// length, times that do not increase strictly, or fewer than two samples.
ReferenceCsv load_reference_csv(const std::string& path, const std::string& time_column,
                                const std::vector<std::string>& columns, const SourceLocation& where);
// As load_reference_csv, from text; `path` names it in messages.
ReferenceCsv parse_reference_csv(const std::string& text, const std::string& path, const std::string& time_column,
                                 const std::vector<std::string>& columns, const SourceLocation& where);

}  // namespace periflex
