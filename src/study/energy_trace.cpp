#include "study/energy_trace.h"

#include <map>
#include <sstream>

#include "study/study_def.h"

namespace periflex {

std::string energy_run_label(const StudyRow& row) {
  return row.integrator + " / " + row.correction +
         (row.tol > 0.0 ? " tol " + format_g(row.tol) : " dt " + format_g(row.dt));
}

std::string energy_trace_csv(const StudyResult& result) {
  std::ostringstream out;
  out.precision(6);
  out << "t";
  for (const StudyRow& r : result.rows) out << "," << energy_run_label(r);
  out << "\n";
  for (size_t k = 0; k < result.times.size(); ++k) {
    out << result.times[k];
    // a failed run has no trace: empty cells, which gnuplot skips
    for (const StudyRow& r : result.rows) {
      out << ",";
      if (k < r.energy_trace.size()) out << r.energy_trace[k];
    }
    out << "\n";
  }
  return out.str();
}

std::string energy_trace_gnuplot_script(const StudyResult& result, const std::string& csv_path,
                                        const std::string& png_path) {
  // per series, the run with the largest step (or the loosest tolerance) that succeeded
  std::map<std::pair<std::string, std::string>, size_t> chosen;
  std::vector<std::pair<std::string, std::string>> order;
  for (size_t k = 0; k < result.rows.size(); ++k) {
    const StudyRow& r = result.rows[k];
    if (!r.ok() || r.energy_trace.empty()) continue;
    const auto key = std::make_pair(r.integrator, r.correction);
    const auto it = chosen.find(key);
    if (it == chosen.end()) {
      chosen[key] = k;
      order.push_back(key);
      continue;
    }
    const StudyRow& best = result.rows[it->second];
    if (r.tol > best.tol || (r.tol == best.tol && r.dt > best.dt)) it->second = k;
  }
  std::ostringstream out;
  out << "set terminal pngcairo size 900,640 enhanced font 'sans,11'\n";
  out << "set output '" << png_path << "'\n";
  out << "set datafile separator ','\n";
  out << "set logscale y\nset format y '10^{%L}'\n";
  out << "set grid xtics ytics mytics lc rgb '#dddddd'\n";
  out << "set key outside right top\n";
  out << "set xlabel 'time [s]'\n";
  out << "set ylabel '|energy balance| / max kinetic energy'\n";
  out << "set title '" << result.study.name << ": energy error against time (largest step of each method)' noenhanced\n";
  out << "plot ";
  for (size_t s = 0; s < order.size(); ++s) {
    const size_t column = chosen[order[s]] + 2;  // column 1 is t
    // rows from the second comparison time: at t = 0 the balance is zero by definition
    out << (s ? ", \\\n     " : "") << "'" << csv_path << "' every ::2 using 1:(column(" << column
        << ") > 1e-16 ? column(" << column << ") : 1e-16) with lines lw 2 title '"
        << energy_run_label(result.rows[chosen[order[s]]]) << "' noenhanced";
  }
  if (order.empty()) out << "NaN notitle";
  out << "\n";
  return out.str();
}

}  // namespace periflex
