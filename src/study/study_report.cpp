#include "study/study_report.h"

#include "io/child_process.h"
#include "study/energy_trace.h"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <set>
#include <sstream>
#include <stdexcept>

namespace periflex {

namespace {

std::string num(double v) {
  if (std::isnan(v)) return "nan";
  std::ostringstream out;
  out << std::setprecision(6) << v;
  return out.str();
}

std::string short_num(double v) {
  if (std::isnan(v)) return "-";
  std::ostringstream out;
  out << std::setprecision(3) << v;
  return out.str();
}

void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

// A free-text field without the separator.
std::string csv_safe(std::string text) {
  for (char& c : text)
    if (c == ',' || c == '\n') c = ';';
  return text;
}

std::string series_label(const std::string& integrator, const std::string& correction) {
  return integrator + " / " + correction;
}

}  // namespace

const std::vector<std::string>& study_csv_columns() {
  static const std::vector<std::string> columns = {
      "integrator", "correction", "dt", "tol", "error_max", "error_rms", "error_max_rel", "error_rms_rel",
      "energy_error", "energy_error_rel", "violation", "crack_tip_error", "broken_bond_error", "wall_time",
      "steps", "status"};
  return columns;
}

const std::vector<std::string>& refine_csv_columns() {
  static const std::vector<std::string> columns = {
      "grid_spacing", "horizon_ratio", "particles", "dt", "measured", "expected", "error_rel", "wall_time",
      "steps", "status"};
  return columns;
}

namespace {

bool is_refine(const StudyResult& result) { return result.study.mode == StudyDef::Mode::kRefine; }

std::string refine_csv(const StudyResult& result) {
  std::ostringstream out;
  const auto& columns = refine_csv_columns();
  for (size_t c = 0; c < columns.size(); ++c) out << (c ? "," : "") << columns[c];
  out << "\n";
  for (const StudyRow& r : result.rows)
    out << num(r.grid_spacing) << "," << num(r.horizon_ratio) << "," << r.particles << "," << num(r.dt) << ","
        << num(r.ok() ? r.measured : NAN) << "," << num(r.expected) << "," << num(r.ok() ? r.error_max_rel : NAN)
        << "," << num(r.wall_time) << "," << r.steps << "," << csv_safe(r.status) << "\n";
  return out.str();
}

// A study stopped by the user says so above its table: the table is not the whole grid.
std::string stopped_note(const StudyResult& result) {
  if (!result.stopped) return "";
  return "**Stopped before the end** (interrupted): " + std::to_string(result.rows.size()) +
         " runs finished and are below; the rest of the grid did not run.\n\n";
}

std::string refine_markdown(const StudyResult& result) {
  std::ostringstream out;
  out << "### " << result.study.name << " (scene " << result.scene_name << ")\n\n";
  out << "Known answer: " << result.reference_description << ".\n\n";
  out << stopped_note(result);
  out << "| grid spacing [m] | horizon ratio m | particles | dt [s] | " << result.quantity << " ["
      << result.quantity_unit << "] | relative error | steps | wall time [s] |\n";
  out << "|---|---|---|---|---|---|---|---|\n";
  for (const StudyRow& r : result.rows) {
    out << "| " << short_num(r.grid_spacing) << " | " << short_num(r.horizon_ratio) << " | " << r.particles
        << " | " << short_num(r.dt) << " | ";
    if (r.ok()) out << short_num(r.measured) << " | " << short_num(r.error_max_rel);
    else out << r.status << " | -";
    out << " | " << r.steps << " | " << short_num(r.wall_time) << " |\n";
  }
  return out.str();
}

std::string refine_gnuplot_script(const StudyResult& result, const std::string& csv_path,
                                  const std::string& png_path) {
  std::ostringstream out;
  out << "set terminal pngcairo size 900,640 enhanced font 'sans,11'\n";
  out << "set output '" << png_path << "'\n";
  out << "set datafile separator ','\nset logscale xy\n";
  out << "set format x '10^{%L}'\nset format y '10^{%L}'\n";
  out << "set grid xtics ytics mxtics mytics lc rgb '#dddddd'\nset key outside right top\n";
  out << "set xlabel 'wall time [s]'\nset ylabel 'relative error of " << result.quantity << "' noenhanced\n";
  out << "set title '" << result.study.name << ": error against run time as the grid is refined' noenhanced\n";
  std::vector<double> ratios;
  for (const StudyRow& r : result.rows)
    if (std::find(ratios.begin(), ratios.end(), r.horizon_ratio) == ratios.end()) ratios.push_back(r.horizon_ratio);
  out << "plot ";
  for (size_t s = 0; s < ratios.size(); ++s)
    out << (s ? ", \\\n     " : "") << "'" << csv_path << "' every ::1 using (abs($2 - " << num(ratios[s])
        << ") < 1e-9 && strcol(10) eq 'ok' ? $8 : NaN):7 with linespoints lw 2 pt " << (5 + s % 9)
        << " title 'm = " << short_num(ratios[s]) << "' noenhanced";
  out << "\n";
  return out.str();
}

}  // namespace

std::string study_csv(const StudyResult& result) {
  if (is_refine(result)) return refine_csv(result);
  std::ostringstream out;
  const auto& columns = study_csv_columns();
  for (size_t c = 0; c < columns.size(); ++c) out << (c ? "," : "") << columns[c];
  out << "\n";
  for (const StudyRow& r : result.rows) {
    out << r.integrator << "," << r.correction << "," << num(r.dt) << "," << num(r.tol) << ","
        << num(r.error_max) << "," << num(r.error_rms) << "," << num(r.error_max_rel) << ","
        << num(r.error_rms_rel) << "," << num(r.energy_error) << "," << num(r.energy_error_rel) << ","
        << num(r.violation) << "," << num(r.crack_tip_error) << "," << num(r.broken_bond_error) << ","
        << num(r.wall_time) << "," << r.steps << "," << csv_safe(r.status) << "\n";
  }
  return out.str();
}

std::string study_markdown(const StudyResult& result) {
  if (is_refine(result)) return refine_markdown(result);
  std::ostringstream out;
  out << "### " << result.study.name << " (scene " << result.scene_name << ")\n\n";
  out << "Reference: " << result.reference_description << ".  \n";
  out << "Relative errors are divided by the largest excursion of the compared probes, "
      << short_num(result.excursion) << " m.\n\n";
  out << stopped_note(result);
  out << "| integrator | correction | dt | tol | max error (rel) | RMS error (rel) | energy error (rel) "
         "| max violation |";
  if (result.has_fracture) out << " crack-tip error [m] | broken-bond error |";
  out << " steps | wall time [s] |\n";
  out << "|---|---|---|---|---|---|---|---|";
  if (result.has_fracture) out << "---|---|";
  out << "---|---|\n";
  for (const StudyRow& r : result.rows) {
    out << "| " << r.integrator << " | " << r.correction << " | " << short_num(r.dt) << " | "
        << (r.tol > 0 ? short_num(r.tol) : "-") << " | ";
    if (!r.ok()) {
      out << r.status << " | | | |";
      if (result.has_fracture) out << " | |";
      out << " " << r.steps << " | - |\n";
      continue;
    }
    out << short_num(r.error_max_rel) << " | " << short_num(r.error_rms_rel) << " | "
        << short_num(r.energy_error_rel) << " | " << short_num(r.violation) << " |";
    if (result.has_fracture) out << " " << short_num(r.crack_tip_error) << " | " << short_num(r.broken_bond_error) << " |";
    out << " " << r.steps << " | " << short_num(r.wall_time) << " |\n";
  }
  out << "\nFastest run to reach a relative error of 1e-3 and of 1e-6:\n\n"
      << "| study | 1e-3 | 1e-6 |\n|---|---|---|\n" << study_guidance_row(result);
  out << "\nObserved order (least-squares slope of log max error against log dt, or log tol for "
         "adaptive runs):\n\n";
  out << "| integrator | correction | observed | theory | points |\n|---|---|---|---|---|\n";
  for (const ObservedOrder& o : result.orders) {
    out << "| " << o.integrator << " | " << o.correction << " | " << short_num(o.slope)
        << (o.against_tolerance ? " (in tol)" : "") << " | " << (o.theory ? std::to_string(o.theory) : "-")
        << " | " << o.points << " |\n";
  }
  return out.str();
}

std::string study_guidance_row(const StudyResult& result) {
  // the fastest successful run whose relative error reaches each target
  const auto fastest = [&](double target) -> std::string {
    const StudyRow* best = nullptr;
    for (const StudyRow& r : result.rows)
      if (r.ok() && r.error_max_rel <= target && (!best || r.wall_time < best->wall_time)) best = &r;
    if (!best) return "none of the runs";
    std::ostringstream out;
    if (is_refine(result)) {
      out << "dx = " << short_num(best->grid_spacing) << ", m = " << short_num(best->horizon_ratio);
    } else {
      out << best->integrator << " / " << best->correction;
      if (best->tol > 0) out << ", tol " << short_num(best->tol);
      else out << ", dt " << short_num(best->dt);
    }
    out << " (" << short_num(best->wall_time) << " s)";
    return out.str();
  };
  return "| " + result.study.name + " | " + fastest(1e-3) + " | " + fastest(1e-6) + " |\n";
}

std::string study_gnuplot_script(const StudyResult& result, const std::string& csv_path,
                                 const std::string& png_path) {
  if (is_refine(result)) return refine_gnuplot_script(result, csv_path, png_path);
  std::ostringstream out;
  out << "set terminal pngcairo size 900,640 enhanced font 'sans,11'\n";
  out << "set output '" << png_path << "'\n";
  out << "set datafile separator ','\n";
  out << "set logscale xy\n";
  out << "set format x '10^{%L}'\nset format y '10^{%L}'\n";
  out << "set grid xtics ytics mxtics mytics lc rgb '#dddddd'\n";
  out << "set key outside right top\n";
  out << "set xlabel 'wall time [s] (solver only, median of " << result.study.repeats << ")'\n";
  out << "set ylabel 'max probe position error / excursion'\n";
  out << "set title '" << result.study.name << ": error against run time' noenhanced\n";
  // one line per (integrator, correction) series, read from the CSV by column match
  std::vector<std::pair<std::string, std::string>> series;
  std::set<std::pair<std::string, std::string>> seen;
  for (const StudyRow& r : result.rows)
    if (seen.insert({r.integrator, r.correction}).second) series.push_back({r.integrator, r.correction});
  out << "plot ";
  for (size_t s = 0; s < series.size(); ++s) {
    const auto& [integrator, correction] = series[s];
    out << (s ? ", \\\n     " : "") << "'" << csv_path << "' every ::1 using "
        << "((strcol(1) eq '" << integrator << "' && strcol(2) eq '" << correction
        << "' && strcol(16) eq 'ok') ? $14 : NaN):7 with linespoints lw 2 pt " << (5 + s % 9) << " title '"
        << series_label(integrator, correction) << "' noenhanced";
  }
  out << "\n";
  return out.str();
}

bool gnuplot_available() { return !find_program("gnuplot").empty(); }

// Runs gnuplot on a script in the output folder (so its relative paths hold); true when it
// succeeded. Its messages go to gnuplot.log there.
bool run_gnuplot(const std::filesystem::path& dir, const std::string& script) {
  ChildLimits limits;
  limits.timeout_seconds = 120.0;
  limits.memory_bytes = 0.0;
  limits.working_directory = dir.string();
  const ChildResult result = run_child({find_program("gnuplot"), script}, limits);
  std::ofstream((dir / "gnuplot.log").string()) << result.output;
  return result.started && !result.timed_out && result.signal == 0 && result.exit_code == 0;
}

StudyOutputs write_study_outputs(const StudyResult& result, const std::string& out_dir) {
  namespace fs = std::filesystem;
  const fs::path dir(out_dir);
  fs::create_directories(dir);
  StudyOutputs outputs;
  outputs.csv_path = (dir / "study.csv").string();
  outputs.markdown_path = (dir / "study.md").string();
  write_text(outputs.csv_path, study_csv(result));
  write_text(outputs.markdown_path, study_markdown(result));
  write_text(dir / "guidance.md", study_guidance_row(result));

  const fs::path script = dir / "study.gp";
  const fs::path png = dir / "study.png";
  write_text(script, study_gnuplot_script(result, "study.csv", "study.png"));
  // time studies: the energy error against time beside the error against run time
  const bool energy = !is_refine(result) && !result.times.empty();
  if (energy) {
    write_text(dir / "energy.csv", energy_trace_csv(result));
    write_text(dir / "energy.gp", energy_trace_gnuplot_script(result, "energy.csv", "energy.png"));
  }
  // a plot of nothing is no plot: gnuplot would only fail on the empty ranges
  if (std::none_of(result.rows.begin(), result.rows.end(), [](const StudyRow& r) { return r.ok(); })) {
    outputs.plot_message = "no plot made: no run of the study finished";
    return outputs;
  }
  if (!gnuplot_available()) {
    outputs.plot_message = "no plot made: gnuplot was not found (install gnuplot-nox, then run "
                           "`gnuplot study.gp` in " + dir.string() + ")";
    return outputs;
  }
  if (!run_gnuplot(dir, "study.gp") || !fs::exists(png)) {
    outputs.plot_message = "no plot made: gnuplot failed (see " + (dir / "gnuplot.log").string() + ")";
    return outputs;
  }
  std::error_code ignored;
  fs::remove(dir / "gnuplot.log", ignored);
  outputs.plot_path = png.string();
  if (energy) {
    if (run_gnuplot(dir, "energy.gp") && fs::exists(dir / "energy.png")) {
      fs::remove(dir / "gnuplot.log", ignored);
      outputs.energy_plot_path = (dir / "energy.png").string();
    }
  }
  return outputs;
}

}  // namespace periflex
