#include "cli/sweep_command.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "cli/interrupt.h"
#include "core/error.h"
#include "output/atomic_file.h"
#include "io/child_process.h"
#include "study/sweep_def.h"

namespace periflex {

namespace fs = std::filesystem;

namespace {

// A word for a POSIX shell: single-quoted, inner quotes closed and escaped.
std::string shell_word(const std::string& word) {
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// How each run is started: the program, and the device it is told (empty: the scene's).
struct RunLauncher {
  std::string program, device;
};

// The command line of one run: the program, the scene, every override, its folder.
std::vector<std::string> run_argv(const RunLauncher& launcher, const SweepDef& sweep, const SweepRun& run,
                                  const fs::path& folder) {
  const std::string& program = launcher.program;
  std::vector<std::string> argv = {program, "run", fs::absolute(sweep.scene_path).string()};
  for (const std::string& set : run.overrides) {
    argv.push_back("--set");
    argv.push_back(set);
  }
  argv.insert(argv.end(), {"--out", fs::absolute(folder).string(), "--quiet", "--threads", "1"});
  if (!launcher.device.empty()) argv.insert(argv.end(), {"--device", launcher.device});
  return argv;
}

// The plan of the sweep in its folder: what --collect reads back.
void write_plan(const SweepDef& sweep, const std::vector<SweepRun>& runs, const fs::path& out) {
  nlohmann::json plan;
  plan["name"] = sweep.name;
  plan["scene"] = fs::absolute(sweep.scene_path).string();
  plan["series"] = sweep.series;
  for (const SweepParameter& p : sweep.parameters) plan["parameters"].push_back(p.key);
  for (const SweepRun& run : runs) plan["runs"].push_back({{"folder", run.folder}, {"values", run.values}});
  write_file_atomically((out / "sweep.json").string(), plan.dump(2) + "\n");
}

// The last row of a series.csv as column -> text.
std::vector<std::pair<std::string, std::string>> last_row(const fs::path& csv) {
  std::ifstream in(csv);
  std::string header, line, last;
  if (!std::getline(in, header)) return {};
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  std::vector<std::pair<std::string, std::string>> row;
  std::stringstream names(header), values(last);
  std::string name, value;
  while (std::getline(names, name, ',')) {
    if (!std::getline(values, value, ',')) value.clear();
    row.emplace_back(name, value);
  }
  return row;
}

// A CSV field: quoted when it holds a comma, quote or line break.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

// The plan in a sweep folder's sweep.json, as --collect reads it back.
struct SweepPlan {
  std::vector<std::string> keys, series;
  struct Run {
    std::string folder;
    std::vector<std::string> values;  // one per key
  };
  std::vector<Run> runs;
};

// Reads sweep.json; throws InputError naming it when it is missing or not a plan this program
// writes (run folders are plain names inside the sweep folder).
SweepPlan read_plan(const fs::path& dir) {
  const SourceLocation where{(dir / "sweep.json").string(), 0, 0, ""};
  std::ifstream in(dir / "sweep.json");
  if (!in) throw InputError(where, "not a sweep folder: no sweep.json (written by periflex sweep)");
  SweepPlan plan;
  try {
    nlohmann::json json;
    in >> json;
    plan.keys = json.value("parameters", std::vector<std::string>{});
    plan.series = json.value("series", std::vector<std::string>{});
    for (const auto& run : json.at("runs")) {
      SweepPlan::Run r{run.at("folder").get<std::string>(), run.at("values").get<std::vector<std::string>>()};
      if (r.folder.empty() || r.folder == "." || r.folder == ".." || r.folder.find('/') != std::string::npos)
        throw InputError(where, "run folder '" + r.folder + "' is not a plain folder name inside the sweep folder");
      if (r.values.size() != plan.keys.size())
        throw InputError(where, "run '" + r.folder + "' has " + std::to_string(r.values.size()) + " values for " +
                                    std::to_string(plan.keys.size()) + " parameters");
      plan.runs.push_back(std::move(r));
    }
  } catch (const nlohmann::json::exception& e) {
    throw InputError(where, std::string("not a sweep plan written by periflex sweep (") + e.what() + ")");
  }
  return plan;
}

// sweep.png with gnuplot when it is installed: the first series column against the first
// parameter, one curve per value of the second. Returns what it did, for the user.
std::string plot(const fs::path& dir, const std::vector<std::string>& keys, const std::vector<std::string>& series,
                 const std::vector<SweepPlan::Run>& runs, size_t figures) {
  if (series.empty() || keys.empty()) return "no plot: the sweep names no series column";
  const std::string gnuplot = find_program("gnuplot");
  const fs::path png = fs::absolute(dir / "sweep.png"), csv = fs::absolute(dir / "sweep.csv");
  const size_t y = 1 + keys.size() + figures + 1;  // column of series[0], 1-based
  std::ostringstream gp;
  gp << "set terminal pngcairo size 900,600\nset output '" << png.string() << "'\n"
     << "set datafile separator ','\nset key autotitle columnhead\n"
     << "set xlabel '" << keys[0] << "'\nset ylabel '" << series[0] << "'\nset grid\nset format y '%.10g'\n";
  if (keys.size() == 1) {
    gp << "plot '" << csv.string() << "' using 2:" << y << " with linespoints title '" << series[0] << "'\n";
  } else {
    std::vector<std::string> values;
    for (const auto& run : runs) {
      const std::string& v = run.values[1];
      if (std::find(values.begin(), values.end(), v) == values.end()) values.push_back(v);
    }
    gp << "plot";
    for (size_t k = 0; k < values.size(); ++k)
      gp << (k ? "," : "") << " '" << csv.string() << "' using 2:(strcol(3) eq '" << values[k] << "' ? column(" << y
         << ") : NaN) smooth unique with linespoints title '" << keys[1] << " = " << values[k] << "'";
    gp << "\n";
  }
  const fs::path script = dir / "sweep.gp";
  write_file_atomically(script.string(), gp.str());
  if (gnuplot.empty()) return "no plot made: gnuplot was not found (install gnuplot-nox, then run `gnuplot " + script.string() + "`)";
  ChildLimits limits;
  limits.timeout_seconds = 60.0;
  const ChildResult result = run_child({gnuplot, fs::absolute(script).string()}, limits);
  if (result.exit_code != 0 || !fs::exists(png)) return "no plot made: gnuplot failed: " + result.output;
  return "wrote " + png.string();
}

// Reads a run's summary.json into `summary`; returns "" when it is this run's, or why it is not:
// "missing" (never written), "unreadable" (damaged by hand or by a full disk), "stale" (its --set
// values are not `sets`: the folder holds a run of another sweep written into the same folder).
std::string read_run_summary(const fs::path& file, const std::vector<std::string>& sets, nlohmann::json& summary) {
  std::ifstream in(file);
  if (!in) return "missing";
  try {
    in >> summary;
  } catch (const nlohmann::json::exception&) {
    return "unreadable";
  }
  if (!summary.is_object()) return "unreadable";
  const nlohmann::json& given = summary.contains("set") ? summary["set"] : nlohmann::json::array();
  for (const std::string& set : sets)
    if (!given.is_array() || std::find(given.begin(), given.end(), set) == given.end()) return "stale";
  return "";
}

// Gathers every run of the folder into sweep.csv (and sweep.png); returns what it wrote. Throws InputError when the
// folder holds no sweep.json.
std::string collect(const fs::path& dir) {
  const SweepPlan plan = read_plan(dir);
  const std::vector<std::string>& keys = plan.keys;
  const std::vector<std::string>& series = plan.series;
  const char* figures[] = {"status", "exit_code", "simulated_time", "steps", "wall_time", "solver_cpu_time"};
  std::ostringstream out;
  out << "run";
  for (const std::string& k : keys) out << ',' << csv_field(k);
  for (const char* f : figures) out << ',' << f;
  for (const std::string& s : series) out << ',' << csv_field(s);
  out << '\n';
  for (const SweepPlan::Run& run : plan.runs) {
    const std::string& folder = run.folder;
    out << folder;
    for (const std::string& v : run.values) out << ',' << csv_field(v);
    std::vector<std::string> sets;
    for (size_t k = 0; k < keys.size(); ++k) sets.push_back(keys[k] + "=" + run.values[k]);
    nlohmann::json summary;
    const std::string unread = read_run_summary(dir / folder / "summary.json", sets, summary);
    for (const char* f : figures) {
      out << ',';
      if (!unread.empty()) out << (std::string(f) == "status" ? unread : "");
      else if (summary.contains(f)) out << csv_field(summary[f].is_string() ? summary[f].get<std::string>() : summary[f].dump());
    }
    // a run that says nothing of itself gives no figures
    const auto row = unread.empty() ? last_row(dir / folder / "series.csv")
                                    : std::vector<std::pair<std::string, std::string>>{};
    for (const std::string& name : series) {
      out << ',';
      for (const auto& [column, value] : row)
        if (column == name) out << value;
    }
    out << '\n';
  }
  const std::string path = (dir / "sweep.csv").string();
  write_file_atomically(path, out.str());
  return "wrote " + path + "\n" + plot(dir, keys, series, plan.runs, std::size(figures));
}

// Runs every run a bounded number at once, each a child process with the sweep's limits;
// returns how many failed. Ctrl-C or SIGTERM (cli/interrupt.h) is passed on to the runs under
// way, which stop cleanly as a run does, and no further run starts.
int run_locally(const SweepDef& sweep, const std::vector<SweepRun>& runs, const fs::path& out, int jobs,
                bool quiet, const RunLauncher& launcher) {
  ChildLimits limits;
  limits.timeout_seconds = sweep.timeout_seconds;
  limits.memory_bytes = sweep.memory_bytes;
  limits.interrupt = [] { return pending_interrupt(); };
  std::atomic<size_t> next{0};
  std::atomic<int> failed{0};
  std::mutex print;
  auto worker = [&] {
    for (size_t k = next++; k < runs.size() && pending_interrupt() == 0; k = next++) {
      const fs::path folder = out / runs[k].folder;
      fs::create_directories(folder);
      const ChildResult result = run_child(run_argv(launcher, sweep, runs[k], folder), limits);
      std::ofstream((folder / "log.txt").string()) << result.output;
      const bool ok = result.started && result.signal == 0 && !result.timed_out && result.exit_code == 0;
      if (!ok && !result.interrupted) ++failed;
      std::lock_guard<std::mutex> lock(print);
      if (!quiet || !ok) {
        std::printf("  %s %s (%.1f s)\n", runs[k].folder.c_str(),
                    ok                    ? "ok"
                    : result.interrupted  ? "interrupted"
                    : result.timed_out    ? "timed out"
                    : result.signal       ? "killed by a signal"
                                          : "failed",
                    result.wall_seconds);
        std::fflush(stdout);
      }
    }
  };
  std::vector<std::thread> threads;
  for (int j = 0; j < std::min<int>(jobs, static_cast<int>(runs.size())); ++j) threads.emplace_back(worker);
  for (std::thread& t : threads) t.join();
  return failed;
}

// The command lines for GNU parallel, and a Slurm array script that runs line N as task N.
void write_jobs(const SweepDef& sweep, const std::vector<SweepRun>& runs, const fs::path& out,
                const std::string& jobs_file, const RunLauncher& launcher) {
  std::ostringstream lines;
  for (const SweepRun& run : runs) {
    const std::vector<std::string> argv = run_argv(launcher, sweep, run, out / run.folder);
    for (size_t k = 0; k < argv.size(); ++k) lines << (k ? " " : "") << shell_word(argv[k]);
    lines << '\n';
  }
  write_file_atomically(jobs_file, lines.str());
  const long seconds = static_cast<long>(sweep.timeout_seconds + 0.5);
  char time[32];
  std::snprintf(time, sizeof time, "%ld:%02ld:%02ld", seconds / 3600, seconds / 60 % 60, seconds % 60);
  std::ostringstream slurm;
  slurm << "#!/bin/bash\n"
        << "#SBATCH --job-name=" << sweep.name << "\n"
        << "#SBATCH --array=1-" << runs.size() << "\n"
        << "#SBATCH --time=" << time << "\n"
        << "#SBATCH --mem=" << static_cast<long>(sweep.memory_bytes / 1e6 + 0.5) << "M\n"
        << "#SBATCH --cpus-per-task=1\n"
        << "# task N runs line N of the jobs file\n"
        << "sed -n \"${SLURM_ARRAY_TASK_ID}p\" " << shell_word(fs::absolute(jobs_file).string()) << " | bash\n";
  write_file_atomically((out / "sweep.slurm").string(), slurm.str());
}

}  // namespace

int sweep_command(const SweepOptions& options) {
  try {
    return sweep_or_throw(options);
  } catch (const InputError& error) {
    std::fprintf(stderr, "periflex: error: %s\n", error.what());
    return kExitBadInput;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "periflex: error: %s\n", error.what());
    return kExitOther;
  }
}

int sweep_or_throw(const SweepOptions& options) {
  const RunLauncher launcher{options.program.empty() ? current_executable() : options.program, options.device};
  if (!options.collect_dir.empty()) {
    std::printf("%s\n", collect(options.collect_dir).c_str());
    return kExitOk;
  }
  if (options.sweep_path.empty()) {
    std::fprintf(stderr, "periflex sweep: give a sweep file, or --collect DIR\n");
    return kExitBadInput;
  }
  const SweepDef sweep = load_sweep(options.sweep_path);
  const std::vector<SweepRun> runs = expand_sweep(sweep);
  const fs::path out = options.out_dir.empty() ? fs::path("out") / ("sweep-" + sweep.name) : fs::path(options.out_dir);
  fs::create_directories(out);
  write_plan(sweep, runs, out);
  if (!options.jobs_file.empty()) {
    write_jobs(sweep, runs, out, options.jobs_file, launcher);
    std::printf("wrote %s (%zu runs: parallel --jobs N < %s)\nwrote %s (sbatch)\n", options.jobs_file.c_str(),
                runs.size(), options.jobs_file.c_str(), (out / "sweep.slurm").string().c_str());
    std::printf("then: periflex sweep --collect %s\n", out.string().c_str());
    return kExitOk;
  }
  const int jobs = options.jobs > 0 ? options.jobs : sweep.jobs;
  if (!options.quiet) std::printf("sweep %s: %zu runs, %d at once\n", sweep.name.c_str(), runs.size(), jobs);
  catch_interrupts();
  const int failed = run_locally(sweep, runs, out, jobs, options.quiet, launcher);
  std::printf("%s\n", collect(out).c_str());
  if (const int signal_number = pending_interrupt()) {
    std::fprintf(stderr,
                 "periflex: sweep interrupted by %s: the runs under way stopped where they were (status "
                 "'interrupted'), the rest did not start ('missing'); sweep.csv holds them all\n",
                 interrupt_name(signal_number));
    return interrupt_exit_code(signal_number);
  }
  if (failed > 0) std::printf("%d of %zu runs failed (their log.txt says why)\n", failed, runs.size());
  return failed > 0 ? kExitOther : kExitOk;
}

}  // namespace periflex
