// `periflex sweep` as typed: a grid over two scene keys run locally two at a time and gathered
// into sweep.csv; the job list for GNU parallel (a line run through the shell as parallel
// would) with its Slurm array script and --collect; bad sweep files refused at their line.
#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "child_run.h"
#include "run_program.h"
#include "support/sanitizer_build.h"

namespace periflex::testing {
namespace {

namespace fs = std::filesystem;

// Each run gets an address-space cap (memory_gb, 4 GB by default). A sanitizer build reserves
// terabytes of address space for its shadow memory and dies under that cap, so there the sweeps
// give their runs 100 TB instead; everything else is the same.
#if PERIFLEX_UNDER_SANITIZER
const char* kMemoryLine = "memory_gb = 100000\n";
#else
const char* kMemoryLine = "";
#endif

// A sweep of the pendulum over solver.dt and the bob's mass, 0.05 s each.
// `runs`: the sweep is run (a refused file runs nothing and keeps the line numbers its test names)
// `series`: the columns gathered, as the TOML array's inside
fs::path write_sweep(const fs::path& dir, const std::string& parameters, bool runs = true,
                     const std::string& series = "\"probe.bob.x\"") {
  const fs::path file = dir / "pendulum_sweep.toml";
  std::ofstream(file) << "[sweep]\n"
                      << "scene = \"" << scene("pendulum.toml") << "\"\n"
                      << "set = [\"solver.end_time=0.05\"]\n"
                      << "jobs = 2\n"
                      << "timeout = 60\n"
                      << "series = [" << series << "]\n"
                      << (runs ? kMemoryLine : "") << parameters;
  return file;
}

const char* kGrid =
    "[[parameter]]\nkey = \"solver.dt\"\nvalues = [1e-3, 7e-4]\n"
    "[[parameter]]\nkey = \"body.bob.mass\"\nvalues = [1.0, 2.5]\n";

std::vector<std::string> lines_of(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) lines.push_back(line);
  return lines;
}

TEST(SweepCommand, RunsEveryCombinationAndGathersThemIntoOneCsv) {
  const fs::path dir = fresh_directory("sweep_local");
  const fs::path file = write_sweep(dir, kGrid);
  const ProgramResult run = run_periflex("sweep " + file.string() + " --out " + (dir / "out").string() + " --quiet");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::vector<std::string> csv = lines_of(dir / "out" / "sweep.csv");
  ASSERT_EQ(csv.size(), 5u) << run.output;
  EXPECT_EQ(csv[0].rfind("run,solver.dt,body.bob.mass,status,exit_code,", 0), 0u) << csv[0];
  EXPECT_NE(csv[0].find(",probe.bob.x"), std::string::npos);
  // the last parameter varies fastest; each run ran with its own values and finished
  const std::vector<std::string> expected = {"run_0001,0.001,1.0,ok,0,", "run_0002,0.001,2.5,ok,0,",
                                             "run_0003,0.0007,1.0,ok,0,", "run_0004,0.0007,2.5,ok,0,"};
  for (size_t k = 0; k < expected.size(); ++k) {
    EXPECT_EQ(csv[k + 1].rfind(expected[k], 0), 0u) << csv[k + 1];
    const std::string summary = read_text(dir / "out" / ("run_000" + std::to_string(k + 1)) / "summary.json");
    EXPECT_NE(summary.find(k < 2 ? "\"dt\": 0.001" : "\"dt\": 0.0007"), std::string::npos) << summary;
    // the probe's last x is a number: the series column reached the table
    const std::string last = csv[k + 1].substr(csv[k + 1].rfind(',') + 1);
    EXPECT_FALSE(last.empty());
    EXPECT_NO_THROW((void)std::stod(last));
  }
  // the mass does not change a pendulum's motion, the step does (a little)
  auto x_of = [&](int row) { return std::stod(csv[row].substr(csv[row].rfind(',') + 1)); };
  EXPECT_NEAR(x_of(1), x_of(2), 1e-12);
  EXPECT_NE(x_of(1), x_of(3));
  // the plot: a PNG when gnuplot is installed, else a message saying how to make it
  if (std::system("command -v gnuplot >/dev/null 2>&1") == 0) {
    const std::string png = read_text(dir / "out" / "sweep.png");
    ASSERT_GT(png.size(), 1000u) << run.output;
    EXPECT_EQ(png.substr(1, 3), "PNG");
  } else {
    EXPECT_NE(run.output.find("gnuplot was not found"), std::string::npos) << run.output;
  }
}

TEST(SweepCommand, JobsFileRunsUnderTheShellAndCollectGathersWhatRan) {
  const fs::path dir = fresh_directory("sweep_jobs");
  const fs::path file = write_sweep(dir, kGrid);
  const fs::path out = dir / "out", jobs = dir / "jobs.txt";
  const ProgramResult written = run_periflex("sweep " + file.string() + " --out " + out.string() + " --jobs-file " + jobs.string());
  ASSERT_EQ(written.exit_code, 0) << written.output;
  const std::vector<std::string> lines = lines_of(jobs);
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_NE(lines[2].find("'--set' 'solver.dt=0.0007' '--set' 'body.bob.mass=1.0'"), std::string::npos) << lines[2];
  EXPECT_FALSE(fs::exists(out / "run_0001")) << "a job list runs nothing";
  // the Slurm array: one task per line
  const std::string slurm = read_text(out / "sweep.slurm");
  EXPECT_NE(slurm.find("#SBATCH --array=1-4"), std::string::npos) << slurm;
  EXPECT_NE(slurm.find("SLURM_ARRAY_TASK_ID"), std::string::npos);
  // task 3 as the Slurm script runs it: line 3 of the list through bash
  const std::string task = "cd " + dir.string() + " && SLURM_ARRAY_TASK_ID=3 bash " + (out / "sweep.slurm").string();
  ASSERT_EQ(std::system(task.c_str()), 0);
  EXPECT_TRUE(fs::exists(out / "run_0003" / "summary.json"));
  const ProgramResult collected = run_periflex("sweep --collect " + out.string());
  ASSERT_EQ(collected.exit_code, 0) << collected.output;
  const std::vector<std::string> csv = lines_of(out / "sweep.csv");
  ASSERT_EQ(csv.size(), 5u);
  EXPECT_EQ(csv[1].rfind("run_0001,0.001,1.0,missing,", 0), 0u) << csv[1];
  EXPECT_EQ(csv[3].rfind("run_0003,0.0007,1.0,ok,0,", 0), 0u) << csv[3];
  // another grid written into the same folder: the run left there is of other values, and says
  // so instead of passing for the new grid's run_0003
  const std::string other_grid =
      "[[parameter]]\nkey = \"solver.dt\"\nvalues = [1e-3, 7e-4]\n"
      "[[parameter]]\nkey = \"body.bob.mass\"\nvalues = [1.5, 2.5]\n";
  ASSERT_EQ(run_periflex("sweep " + write_sweep(dir, other_grid).string() + " --out " + out.string() +
                         " --jobs-file " + jobs.string())
                .exit_code,
            0);
  ASSERT_EQ(run_periflex("sweep --collect " + out.string()).exit_code, 0);
  EXPECT_EQ(lines_of(out / "sweep.csv")[3].rfind("run_0003,0.0007,1.5,stale,,", 0), 0u);
  ASSERT_EQ(run_periflex("sweep " + write_sweep(dir, kGrid).string() + " --out " + out.string() + " --jobs-file " +
                         jobs.string())
                .exit_code,
            0);
  // a summary damaged since is told apart from one never written
  std::ofstream(out / "run_0003" / "summary.json") << "{\"status\": \"ok\", \"steps";
  ASSERT_EQ(run_periflex("sweep --collect " + out.string()).exit_code, 0);
  EXPECT_EQ(lines_of(out / "sweep.csv")[3].rfind("run_0003,0.0007,1.0,unreadable,", 0), 0u);
}

// The command lines of the running processes, read from /proc.
std::vector<std::string> process_command_lines() {
  std::vector<std::string> lines;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    std::ifstream in(entry.path() / "cmdline", std::ios::binary);
    std::string line((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::replace(line.begin(), line.end(), '\0', ' ');
    if (!line.empty()) lines.push_back(line);
  }
  return lines;
}

// SIGTERM (or a terminal's Ctrl-C) during a local sweep: the runs under way are told to stop,
// stop cleanly (their summary.json says interrupted), none is left running, no further run
// starts, and sweep.csv says which ran; the sweep exits 143. It used to die at once and leave its
// runs going in the background.
TEST(SweepCommand, SigtermStopsTheRunsUnderWayAndStartsNoMore) {
  const fs::path dir = fresh_directory("sweep_sigterm");
  const fs::path file = dir / "glass_sweep.toml", out = dir / "out";
  std::ofstream(file) << "[sweep]\nscene = \"" << scene("glass_branching.toml") << "\"\njobs = 2\n"
                      << kMemoryLine << "[[parameter]]\nkey = \"flex_body.plate.material.fracture_energy\"\n"
                      << "values = [3.0, 3.8, 4.5, 5.0]\n";
  Child sweep({"sweep", file.string(), "--out", out.string()});
  // both first runs under way: their summary.json is written when they start
  const bool running = sweep.wait_until(
      [&] { return fs::exists(out / "run_0001" / "summary.json") && fs::exists(out / "run_0002" / "summary.json"); },
      120);
  ASSERT_TRUE(running) << "the runs did not start";
  sweep.send(SIGTERM);
  const ChildResult r = sweep.finish(120);
  ASSERT_FALSE(r.timed_out);
  EXPECT_EQ(r.exit_code, 143) << r.output;
  EXPECT_NE(r.output.find("sweep interrupted by SIGTERM"), std::string::npos) << r.output;
  for (const std::string& line : process_command_lines())
    EXPECT_EQ(line.find(out.string()), std::string::npos) << "still running: " << line;
  const std::vector<std::string> csv = lines_of(out / "sweep.csv");
  ASSERT_EQ(csv.size(), 5u) << r.output;
  EXPECT_EQ(csv[1].rfind("run_0001,3.0,interrupted,143,", 0), 0u) << csv[1];
  EXPECT_EQ(csv[2].rfind("run_0002,3.8,interrupted,143,", 0), 0u) << csv[2];
  EXPECT_EQ(csv[3].rfind("run_0003,4.5,missing,", 0), 0u) << csv[3];
  EXPECT_FALSE(fs::exists(out / "run_0004")) << "a run started after the interrupt";
}

struct BadSweep {
  const char* name;
  std::string parameters;
  std::string where;  // file:line:column the message must name
  std::string words;  // and what it must say
  std::string series = "\"probe.bob.x\"";
};

// Four hundred values, 1e-3 to 1.4e-3.
std::string many_values() {
  std::string out = "[";
  for (int k = 0; k < 400; ++k) out += (k ? ", " : "") + std::to_string(1e-3 + 1e-6 * k);
  return out + "]";
}

TEST(SweepCommand, BadSweepFilesExitTwoNamingFileLineAndColumn) {
  const std::vector<BadSweep> cases = {
      {"UnknownSceneKey", "[[parameter]]\nkey = \"body.bob.colour\"\nvalues = [1, 2]\n", ":9:10", "unknown key 'colour'"},
      {"ValuesNotAnArray", "[[parameter]]\nkey = \"solver.dt\"\nvalues = 1e-3\n", ":9:10", "array"},
      {"ValueTheSceneRefuses", "[[parameter]]\nkey = \"solver.dt\"\nvalues = [1e-3, -1.0]\n", ":9:10", "solver.dt"},
      {"NoParameters", "", ":1:1", "[[parameter]]"},
      // a column no run writes (a rigid-body quantity of a pendulum's probe, and a misspelling)
      // 160,000 runs: refused before a scene is read for each
      {"GridTooLarge",
       "[[parameter]]\nkey = \"solver.dt\"\nvalues = " + many_values() +
           "\n[[parameter]]\nkey = \"body.bob.mass\"\nvalues = " + many_values() + "\n",
       ":12:10", "the grid has 160000 runs (400 x 400 values)"},
      // an address-space limit no machine has (its cast to the limit's type killed every run)
      {"MemoryBeyondAnyMachine", "memory_gb = 1e30\n[[parameter]]\nkey = \"solver.dt\"\nvalues = [1e-3]\n", ":7:13",
       "memory_gb"},
      {"SeriesColumnNoRunWrites", "[[parameter]]\nkey = \"solver.dt\"\nvalues = [1e-3]\n", ":6:10",
       "writes no series.csv column 'probe.bob.z'", "\"probe.bob.angle\", \"probe.bob.z\""},
  };
  for (const BadSweep& c : cases) {
    const fs::path dir = fresh_directory(std::string("sweep_bad_") + c.name);
    const fs::path file = write_sweep(dir, c.parameters, false, c.series);
    const ProgramResult r = run_periflex("sweep " + file.string() + " --out " + (dir / "out").string());
    EXPECT_EQ(r.exit_code, 2) << c.name << ": " << r.output;
    EXPECT_NE(r.output.find(file.string() + c.where), std::string::npos) << c.name << ": " << r.output;
    EXPECT_NE(r.output.find(c.words), std::string::npos) << c.name << ": " << r.output;
    EXPECT_FALSE(fs::exists(dir / "out" / "run_0001")) << c.name;
  }
  // --collect of a folder that is no sweep, or whose plan is not one periflex writes: exit 2
  // naming sweep.json (a plan of the wrong shape used to end with a JSON library error, exit 1)
  const fs::path bad = fresh_directory("sweep_bad_collect");
  for (const char* plan : {"", "{\"runs\": 5}", "{\"runs\": [{\"folder\": \"../..\", \"values\": []}]}",
                           "{\"parameters\": [\"a\"], \"runs\": [{\"folder\": \"r\", \"values\": []}]}"}) {
    if (*plan) std::ofstream(bad / "sweep.json") << plan;
    const ProgramResult r = run_periflex("sweep --collect " + bad.string());
    EXPECT_EQ(r.exit_code, 2) << plan << ": " << r.output;
    EXPECT_NE(r.output.find("sweep.json: "), std::string::npos) << plan << ": " << r.output;
  }
}

}  // namespace
}  // namespace periflex::testing
