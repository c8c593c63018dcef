#include "stability/run_outputs.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace periflex {

namespace {

std::string read_file(const std::filesystem::path& path, bool& found) {
  std::ifstream in(path, std::ios::binary);
  found = static_cast<bool>(in);
  std::stringstream text;
  if (found) text << in.rdbuf();
  return text.str();
}

// The whole cell must be one finite number.
bool parse_number(const std::string& cell, double& value) {
  if (cell.empty()) return false;
  char* end = nullptr;
  value = std::strtod(cell.c_str(), &end);
  return end == cell.c_str() + cell.size() && std::isfinite(value);
}

// Least-squares slope of y over x; 0 with fewer than two distinct x.
double slope(const std::vector<double>& x, const std::vector<double>& y) {
  const size_t n = x.size();
  if (n < 2) return 0.0;
  double mx = 0, my = 0;
  for (size_t k = 0; k < n; ++k) {
    mx += x[k];
    my += y[k];
  }
  mx /= n;
  my /= n;
  double sxy = 0, sxx = 0;
  for (size_t k = 0; k < n; ++k) {
    sxy += (x[k] - mx) * (y[k] - my);
    sxx += (x[k] - mx) * (x[k] - mx);
  }
  return sxx > 0 ? sxy / sxx : 0.0;
}

}  // namespace

int Series::column(const std::string& name) const {
  const auto it = std::find(columns.begin(), columns.end(), name);
  return it == columns.end() ? -1 : static_cast<int>(it - columns.begin());
}

double RunOutputs::relative_energy_error() const {
  // a scene in which no energy moves has nothing to compare against: report the absolute value
  return energy_scale > 0 ? energy_error / energy_scale : energy_error;
}

Series parse_series(const std::string& text, std::vector<std::string>& problems) {
  Series series;
  std::stringstream lines(text);
  std::string line;
  long line_number = 0;
  while (std::getline(lines, line)) {
    ++line_number;
    std::vector<std::string> cells;
    std::stringstream split(line);
    std::string cell;
    while (std::getline(split, cell, ',')) cells.push_back(cell);
    if (line_number == 1) {
      series.columns = cells;
      continue;
    }
    if (cells.size() != series.columns.size()) {
      problems.push_back("series.csv line " + std::to_string(line_number) + " has " + std::to_string(cells.size()) +
                         " cells, the header " + std::to_string(series.columns.size()));
      continue;
    }
    std::vector<double> row(cells.size());
    bool ok = true;
    for (size_t k = 0; k < cells.size() && ok; ++k) {
      if (!parse_number(cells[k], row[k])) {
        problems.push_back("series.csv line " + std::to_string(line_number) + " column " + series.columns[k] +
                           " is not a finite number: '" + cells[k] + "'");
        ok = false;
      }
    }
    if (ok) series.rows.push_back(std::move(row));
  }
  // a file cut in the middle of a row has no final newline
  if (!text.empty() && text.back() != '\n') problems.push_back("series.csv does not end with a complete row");
  if (series.columns.empty()) problems.push_back("series.csv has no header");
  return series;
}

RunOutputs read_run_outputs(const std::string& dir, int exit_code) {
  RunOutputs out;
  auto problem = [&](const std::string& what) {
    out.valid = false;
    out.problems.push_back(what);
  };

  // summary.json: valid JSON whose status and exit code agree with the process
  bool found = false;
  const std::string summary_text = read_file(std::filesystem::path(dir) / "summary.json", found);
  if (!found) {
    problem("summary.json is missing");
  } else {
    try {
      const auto j = nlohmann::json::parse(summary_text);
      out.has_summary = true;
      out.status = j.value("status", std::string());
      out.summary_exit_code = j.value("exit_code", -1);
      out.message = j.value("message", std::string());
      out.steps = j.value("steps", 0L);
      if (j.contains("simulated_time") && j["simulated_time"].is_number()) out.simulated_time = j["simulated_time"];
      if (j.contains("model")) {
        const auto& m = j["model"];
        if (m.contains("critical_time_step") && m["critical_time_step"].is_number())
          out.critical_time_step = m["critical_time_step"];
        if (m.contains("warnings") && m["warnings"].is_array())
          for (const auto& w : m["warnings"]) out.warnings.push_back(w.get<std::string>());
      }
    } catch (const std::exception& e) {
      problem(std::string("summary.json is not valid JSON: ") + e.what());
    }
    if (out.has_summary) {
      const char* expected = exit_code == 0 ? "ok" : exit_code == 3 ? "numerical_failure" : nullptr;
      if (expected && out.status != expected)
        problem("summary.json status is '" + out.status + "', expected '" + expected + "' for exit code " +
                std::to_string(exit_code));
      if (out.summary_exit_code != exit_code)
        problem("summary.json exit_code is " + std::to_string(out.summary_exit_code) + ", the process exited with " +
                std::to_string(exit_code));
      if (exit_code == 3 && out.message.empty()) problem("summary.json has no message for a numerical failure");
    }
  }

  // series.csv: complete rows of finite numbers, times increasing
  const std::string series_text = read_file(std::filesystem::path(dir) / "series.csv", found);
  if (!found) {
    problem("series.csv is missing");
    return out;
  }
  std::vector<std::string> csv_problems;
  const Series series = parse_series(series_text, csv_problems);
  for (const auto& p : csv_problems) problem(p);
  out.rows = static_cast<long>(series.rows.size());
  if (exit_code == 0 && out.rows == 0) problem("series.csv has no rows after a successful run");

  const int t = series.column("t");
  const int balance = series.column("energy_balance");
  const int violation = series.column("violation_position");
  if (t < 0 || balance < 0 || violation < 0) {
    if (!series.columns.empty()) problem("series.csv lacks one of the columns t, energy_balance, violation_position");
    return out;
  }
  std::vector<double> times, balances, violations;
  double previous = -INFINITY;
  for (const auto& row : series.rows) {
    if (row[t] < previous) problem("series.csv time goes backwards at t = " + std::to_string(row[t]));
    previous = row[t];
    times.push_back(row[t]);
    balances.push_back(row[balance]);
    violations.push_back(row[violation]);
    out.energy_error = std::max(out.energy_error, std::abs(row[balance]));
    out.max_violation = std::max(out.max_violation, std::abs(row[violation]));
  }
  if (!series.rows.empty()) {
    out.last_time = times.back();
    out.final_violation = violations.back();
    // every account has a natural zero except the gravity potential, which counts from its
    // initial value (its zero is wherever the scene's origin happens to be)
    const auto& first = series.rows.front();
    for (const auto& row : series.rows) {
      for (const char* name : {"kinetic", "potential_elastic", "dissipated", "fracture", "external_work", "driver_work"}) {
        const int c = series.column(name);
        if (c >= 0) out.energy_scale = std::max(out.energy_scale, std::abs(row[c]));
      }
      const int g = series.column("potential_gravity");
      if (g >= 0) out.energy_scale = std::max(out.energy_scale, std::abs(row[g] - first[g]));
    }
  }
  out.energy_drift_rate = slope(times, balances);
  out.violation_drift_rate = slope(times, violations);
  return out;
}

}  // namespace periflex
