#include "stability/stability_suite.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/resources.h"
#include "solve/simulation.h"
#include "io/child_process.h"
#include "stability/run_outputs.h"

namespace periflex {

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool contains_any(const std::string& text, const std::vector<std::string>& terms, std::string* which = nullptr) {
  const std::string t = lower(text);
  for (const auto& term : terms) {
    if (t.find(lower(term)) != std::string::npos) {
      if (which) *which = term;
      return true;
    }
  }
  return false;
}

// The first output line containing `needle` (case-insensitive), trimmed; empty if none.
std::string line_with(const std::string& output, const std::string& needle) {
  std::stringstream lines(output);
  std::string line;
  const std::string n = lower(needle);
  while (std::getline(lines, line)) {
    if (lower(line).find(n) != std::string::npos) {
      const auto first = line.find_first_not_of(" \t");
      return first == std::string::npos ? std::string() : line.substr(first);
    }
  }
  return {};
}

std::string format_number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

// "critical time step    2.5e-07 s (...)" in the output of `periflex check`; 0 if absent.
double parse_critical_step(const std::string& output) {
  const std::string line = line_with(output, "critical time step");
  if (line.empty()) return 0.0;
  const auto digits = line.find_first_of("0123456789", std::string("critical time step").size());
  if (digits == std::string::npos) return 0.0;
  return std::strtod(line.c_str() + digits, nullptr);
}

std::string describe_child_end(const ChildResult& child) {
  if (child.timed_out) return "killed after the time limit";
  if (child.signal) return "ended by signal " + std::to_string(child.signal);
  return "exit code " + std::to_string(child.exit_code);
}

}  // namespace

const char* expectation_name(Expectation e) {
  switch (e) {
    case Expectation::kStable: return "stable";
    case Expectation::kStopped: return "stopped";
    case Expectation::kStableOrStopped: return "stable or stopped";
    case Expectation::kRefused: return "refused";
    case Expectation::kWarned: return "warned";
  }
  return "?";
}

CaseResult run_stability_case(const StabilityCase& c, const SuiteOptions& options) {
  CaseResult r;
  r.name = c.name;
  r.group = c.group;
  r.description = c.description;
  r.expected = expectation_name(c.expect);

  // an integrator someone else adds may not exist yet: the case is then skipped, and says so
  if (!c.requires_integrator.empty()) {
    if (find_integrator(c.requires_integrator) == nullptr) {
      r.outcome = "skipped";
      r.as_expected = true;
      r.verdict = "integrator '" + c.requires_integrator + "' is not offered by this build";
      return r;
    }
  }

  const std::string root = options.resource_root.empty() ? find_resource_root() : options.resource_root;
  const std::string scene = root + "/" + c.scene;
  const std::string dir = options.out_dir + "/" + c.name;
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
  std::filesystem::create_directories(dir, ec);

  ChildLimits limits;
  limits.timeout_seconds = c.timeout_seconds;
  limits.memory_bytes = options.memory_bytes;
  limits.environment = {"OMP_NUM_THREADS=" + std::to_string(std::max(1, options.threads))};
  limits.interrupt = options.interrupt;

  std::vector<std::string> argv = {options.program, c.command, scene};
  for (const auto& s : c.sets) {
    argv.push_back("--set");
    argv.push_back(s);
  }

  // a step given relative to the critical step: ask `periflex check` for that step first
  if (c.dt_over_critical > 0) {
    std::vector<std::string> check = {options.program, "check", scene};
    check.insert(check.end(), argv.begin() + 3, argv.end());
    const ChildResult probe = run_child(check, limits);
    r.critical_time_step = parse_critical_step(probe.output);
    if (r.critical_time_step <= 0 || !std::isfinite(r.critical_time_step)) {
      r.outcome = "error";
      r.verdict = "`periflex check` reported no critical time step (" + describe_child_end(probe) + ")";
      r.message = line_with(probe.output, "periflex:");
      return r;
    }
    r.dt = c.dt_over_critical * r.critical_time_step;
    if (c.command == "run") {
      argv.push_back("--dt");
      argv.push_back(format_number(r.dt));
    } else {
      argv.push_back("--set");
      argv.push_back("solver.dt=" + format_number(r.dt));
    }
  }
  if (c.dt > 0) {
    r.dt = c.dt;
    argv.push_back("--dt");
    argv.push_back(format_number(r.dt));
  }
  // a long run: a number of steps, and about a thousand rows of output whatever their count
  if (c.run_steps > 0 && r.dt > 0) {
    const double until = static_cast<double>(c.run_steps) * r.dt;
    argv.insert(argv.end(), {"--until", format_number(until), "--set",
                             "solver.output_interval=" + format_number(until / 1000.0)});
  }
  for (std::string option : c.options) {
    const auto at = option.find("{out}");
    if (at != std::string::npos) option.replace(at, 5, dir);
    argv.push_back(option);
  }
  if (c.command == "run") {
    argv.insert(argv.end(), {"--out", dir, "--quiet"});
  }

  const ChildResult child = run_child(argv, limits);
  r.exit_code = child.exit_code;
  r.signal = child.signal;
  r.run_seconds = child.wall_seconds;
  {
    std::ofstream log(dir + "/output.txt");
    for (const auto& a : argv) log << a << ' ';
    log << "\n" << child.output;
  }

  // what happened, before judging it
  if (!child.started) {
    r.outcome = "error";
    r.verdict = "could not start " + options.program + ": " + child.output;
    return r;
  }
  if (child.timed_out) {
    r.outcome = "hung";
  } else if (child.signal) {
    r.outcome = "crashed";
  } else if (c.command == "check") {
    std::string term;
    r.outcome = contains_any(child.output, c.message_terms, &term) ? "warned" : "checked";
    if (!term.empty()) r.message = line_with(child.output, term);
    if (child.exit_code == 1) r.outcome = "error";
  } else if (child.exit_code == 0) {
    r.outcome = "stable";
  } else if (child.exit_code == 3) {
    r.outcome = "stopped";
  } else if (child.exit_code == 2) {
    r.outcome = "refused";
  } else {
    r.outcome = "error";
  }
  // a build without the off-screen renderer refuses --render / --screenshot: nothing to judge
  if (c.requires_rendering && r.outcome == "refused" && contains_any(child.output, {"off-screen renderer", "egl"})) {
    r.outcome = "skipped";
    r.as_expected = true;
    r.verdict = "this build of periflex has no off-screen renderer";
    r.message = line_with(child.output, "periflex: ");
    return r;
  }
  if (r.outcome == "stopped") {
    r.message = line_with(child.output, "numerical failure");
  } else if (r.outcome == "refused" || r.outcome == "error") {
    r.message = line_with(child.output, "periflex: ");
  } else if (r.outcome == "crashed" || r.outcome == "hung") {
    r.message = describe_child_end(child);
  }

  // a run leaves series.csv and summary.json, which must be intact whatever the outcome
  bool outputs_ok = true;
  if (c.command == "run" && (r.outcome == "stable" || r.outcome == "stopped")) {
    const RunOutputs out = read_run_outputs(dir, child.exit_code);
    outputs_ok = out.valid;
    r.output_problems = out.problems;
    r.steps = out.steps;
    r.rows = out.rows;
    r.simulated_time = out.last_time;
    r.energy_error = out.energy_error;
    r.relative_energy_error = out.relative_energy_error();
    r.max_violation = out.max_violation;
    r.energy_drift_rate = out.energy_drift_rate;
    r.violation_drift_rate = out.violation_drift_rate;
    if (r.critical_time_step == 0) r.critical_time_step = out.critical_time_step;
    if (r.message.empty() && r.outcome == "stopped") r.message = out.message;
  }

  // judge it against the expectation
  std::ostringstream why;
  const bool stable_ok = r.outcome == "stable" && r.relative_energy_error <= c.max_relative_energy_error &&
                         r.max_violation <= c.max_violation;
  // a diagnostic must name the expected quantity (in what went wrong, not in the advice that
  // follows "Try:") and say what to change
  const auto remedy_at = lower(r.message).find("try:");
  const std::string remedy = remedy_at == std::string::npos ? std::string() : r.message.substr(remedy_at);
  const bool names_quantity = contains_any(r.message.substr(0, remedy_at), c.message_terms);
  const bool has_remedy = !remedy.empty() && (c.remedy_terms.empty() || contains_any(remedy, c.remedy_terms));
  const bool stopped_ok = r.outcome == "stopped" && names_quantity && has_remedy;
  switch (c.expect) {
    case Expectation::kStable:
      r.as_expected = stable_ok;
      break;
    case Expectation::kStopped:
      r.as_expected = stopped_ok;
      break;
    case Expectation::kStableOrStopped:
      r.as_expected = stable_ok || stopped_ok;
      break;
    case Expectation::kRefused:
      r.as_expected = r.outcome == "refused" && names_quantity;
      break;
    case Expectation::kWarned:
      r.as_expected = r.outcome == "warned";
      break;
  }
  if (!outputs_ok) r.as_expected = false;

  if (r.outcome == "stable" && c.expect != Expectation::kStopped && c.expect != Expectation::kRefused &&
      c.expect != Expectation::kWarned && !stable_ok) {
    why << "energy error " << r.relative_energy_error << " (bound " << c.max_relative_energy_error
        << "), max violation " << r.max_violation << " (bound " << c.max_violation << ")";
  } else if (r.outcome == "stopped" && !stopped_ok && c.expect != Expectation::kStable) {
    if (!names_quantity) {
      why << "the diagnostic does not name the expected quantity";
    } else {
      why << "the diagnostic's remedy does not name the parameter to change";
      if (!c.remedy_terms.empty()) why << " (" << c.remedy_terms.front() << ")";
    }
  } else if (!r.as_expected && outputs_ok) {
    why << "expected " << r.expected << ", got " << r.outcome;
  }
  if (!outputs_ok) {
    why << (why.tellp() > 0 ? "; " : "") << "invalid outputs: " << r.output_problems.front();
  }
  r.verdict = why.str();
  return r;
}

std::string stability_table_markdown(const std::vector<CaseResult>& results) {
  auto num = [](double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.2e", v);
    return std::string(buffer);
  };
  auto cell = [](std::string s) {
    std::replace(s.begin(), s.end(), '|', '/');
    std::replace(s.begin(), s.end(), '\n', ' ');
    return s;
  };
  std::ostringstream md;
  md << "| case | group | expected | outcome | as expected | energy error (rel.) | max constraint violation"
        " | run time [s] | steps | message |\n";
  md << "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : results) {
    const bool measured = r.outcome == "stable" || r.outcome == "stopped";
    // why a case is not as expected comes first, so a shortened cell still says it
    std::string message = r.message;
    if (!r.verdict.empty()) message = "**" + r.verdict + "**" + (message.empty() ? "" : ": " + message);
    if (message.size() > 400) message = message.substr(0, 397) + "...";
    md << "| " << r.name << " | " << r.group << " | " << r.expected << " | " << r.outcome << " | "
       << (r.as_expected ? "yes" : "**NO**") << " | " << (measured ? num(r.relative_energy_error) : "-") << " | "
       << (measured ? num(r.max_violation) : "-") << " | " << (r.outcome == "skipped" ? "-" : num(r.run_seconds))
       << " | " << (measured ? std::to_string(r.steps) : "-") << " | " << cell(message) << " |\n";
  }
  return md.str();
}

void write_stability_table(const std::vector<CaseResult>& results, const std::string& dir, const std::string& title) {
  std::filesystem::create_directories(dir);
  int expected = 0;
  for (const auto& r : results) expected += r.as_expected ? 1 : 0;

  std::ofstream md(dir + "/stability.md");
  md << "# " << title << "\n\n";
  md << expected << " of " << results.size() << " cases behaved as expected.\n\n";
  md << stability_table_markdown(results);
  // long runs: drift per unit time
  bool any_long = false;
  for (const auto& r : results) any_long |= r.group == "long_run" && r.outcome == "stable";
  if (any_long) {
    md << "\n| long run | simulated time [s] | steps | energy drift [J/s] | relative energy error"
          " | constraint drift [1/s] | max constraint violation |\n|---|---|---|---|---|---|---|\n";
    for (const auto& r : results) {
      if (r.group != "long_run" || r.outcome != "stable") continue;
      char line[512];
      std::snprintf(line, sizeof line, "| %s | %.6g | %ld | %.3e | %.3e | %.3e | %.3e |\n", r.name.c_str(),
                    r.simulated_time, r.steps, r.energy_drift_rate, r.relative_energy_error, r.violation_drift_rate,
                    r.max_violation);
      md << line;
    }
  }

  std::ofstream csv(dir + "/stability.csv");
  csv << "case,group,expected,outcome,as_expected,exit_code,signal,relative_energy_error,energy_error,"
         "max_violation,run_seconds,steps,rows,simulated_time,dt,critical_time_step,energy_drift_rate,"
         "violation_drift_rate,message\n";
  for (const auto& r : results) {
    std::string message = r.message + (r.verdict.empty() ? "" : " -- note: " + r.verdict);
    std::string quoted;
    for (char ch : message) quoted += ch == '"' ? std::string("\"\"") : std::string(1, ch == '\n' ? ' ' : ch);
    char numbers[512];
    std::snprintf(numbers, sizeof numbers, "%d,%d,%.6e,%.6e,%.6e,%.3f,%ld,%ld,%.9g,%.6e,%.6e,%.6e,%.6e",
                  r.exit_code, r.signal, r.relative_energy_error, r.energy_error, r.max_violation, r.run_seconds,
                  r.steps, r.rows, r.simulated_time, r.dt, r.critical_time_step, r.energy_drift_rate,
                  r.violation_drift_rate);
    csv << r.name << ',' << r.group << ',' << r.expected << ',' << r.outcome << ',' << (r.as_expected ? 1 : 0) << ','
        << numbers << ",\"" << quoted << "\"\n";
  }
}

}  // namespace periflex
