// `periflex study` against a reference trajectory the user supplies as CSV, as typed: the
// IFToMM A01 pendulum studied against a file written from its closed form (Jacobi elliptic
// functions) at uneven times, and the files and study keys a careless user gets wrong.
#include <unistd.h>

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "core/vec2.h"
#include "study/elliptic.h"

namespace periflex {
namespace {

namespace fs = std::filesystem;

struct ProgramRun {
  int exit_code = -1;
  std::string output;
};

ProgramRun run_program(const std::string& arguments) {
  ProgramRun run;
  const std::string command = std::string("'") + PERIFLEX_BINARY + "' " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return run;
  std::array<char, 4096> buffer{};
  while (fgets(buffer.data(), buffer.size(), pipe)) run.output += buffer.data();
  const int status = pclose(pipe);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return run;
}

fs::path fresh(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("periflex_csv_reference_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// The A01 bob from its closed form, every ~0.005 s at uneven times from 0 to `end`, with an
// unrelated column between the ones compared.
void write_a01_csv(const fs::path& path, double end) {
  std::ofstream out(path);
  out.precision(17);
  out << "t,energy,probe.bob.x,probe.bob.y\n";
  const double k = std::sin(kPi / 4), omega0 = std::sqrt(9.81), h = 0.005;
  for (int i = 0;; ++i) {
    const double t = i == 0 ? 0.0 : i * h + 0.25 * h * std::sin(3.0 * i);
    const JacobiValues j = jacobi_elliptic(omega0 * t, k * k);
    const double theta = 2.0 * std::asin(k * j.cn / j.dn);
    out << t << ",0," << std::sin(theta) << "," << -std::cos(theta) << "\n";
    if (t > end) break;
  }
}

std::string a01_study(const std::string& scene, const std::string& reference_lines) {
  return "[study]\nscene = \"" + scene + "\"\n" + reference_lines +
         "end_time = 10.0\ncompare_interval = 0.1\n"
         "[[method]]\nintegrator = \"rk4\"\ndt = [1e-2, 5e-3, 2.5e-3]\ncorrection = \"projection\"\n";
}

// error_max of each row of a study.csv, by dt.
std::map<double, double> errors_by_dt(const fs::path& csv) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  std::map<double, double> out;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string c; std::getline(s, c, ',');) cells.push_back(c);
    out[std::stod(cells[2])] = std::stod(cells[4]);
  }
  return out;
}

TEST(StudyCsvReference, A01AgainstItsClosedFormFromAFileMatchesTheBuiltInReference) {
  const fs::path dir = fresh("a01");
  write_a01_csv(dir / "a01.csv", 10.0);
  const std::string shipped = std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/benchmarks/a01_pendulum.toml";
  std::ofstream(dir / "csv.toml") << a01_study(shipped, "reference = \"csv\"\nreference_file = \"a01.csv\"\n"
                                                        "columns = [\"probe.bob.x\", \"probe.bob.y\"]\n");
  std::ofstream(dir / "exact.toml") << a01_study(shipped, "reference = \"pendulum_exact\"\n");
  const ProgramRun csv = run_program("study '" + (dir / "csv.toml").string() + "' --out '" + (dir / "csv").string() + "' --quiet");
  ASSERT_EQ(csv.exit_code, 0) << csv.output;
  const ProgramRun exact =
      run_program("study '" + (dir / "exact.toml").string() + "' --out '" + (dir / "exact").string() + "' --quiet");
  ASSERT_EQ(exact.exit_code, 0) << exact.output;
  const auto from_file = errors_by_dt(dir / "csv" / "study.csv");
  const auto built_in = errors_by_dt(dir / "exact" / "study.csv");
  ASSERT_EQ(from_file.size(), 3u);
  for (const auto& [dt, error] : from_file) {
    std::printf("rk4 dt %g: max error %.4g m against the file, %.4g m against the closed form\n", dt, error,
                built_in.at(dt));
    // the interpolation between the samples adds at most 1e-10 m (the motion has components up
    // to about 6 rad/s: (6 * 1.25 h)^6 / 200 = 4e-11 m at h = 0.005)
    EXPECT_NEAR(error, built_in.at(dt), 1e-10 + 1e-3 * built_in.at(dt)) << "dt " << dt;
  }
  // fourth order seen through the file: halving dt divides the error by about 16
  EXPECT_GT(from_file.at(1e-2) / from_file.at(5e-3), 10.0);
  EXPECT_LT(from_file.at(2.5e-3), 1e-6);
  fs::remove_all(dir);
}

TEST(StudyCsvReference, PointMassOnAMasslessRodIsStudiedAgainstTheFile) {
  // the model the closed-form reference in the code cannot describe: any benchmark can be studied
  const fs::path dir = fresh("rod");
  write_a01_csv(dir / "a01.csv", 10.0);
  std::ofstream(dir / "rod.toml") << a01_study(std::string(PERIFLEX_SOURCE_ROOT) + "/tests/data/scenes/a01_point_mass_rod.toml",
                                               "reference = \"csv\"\nreference_file = \"a01.csv\"\n");
  const ProgramRun run = run_program("study '" + (dir / "rod.toml").string() + "' --out '" + (dir / "out").string() + "' --quiet");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto errors = errors_by_dt(dir / "out" / "study.csv");
  EXPECT_LT(errors.at(2.5e-3), 1e-6);
  fs::remove_all(dir);
}

// Runs a study of the A01 scene against `csv_text` with extra study lines; exit code and output.
ProgramRun hostile(const std::string& name, const std::string& csv_text, const std::string& extra = "",
                   bool write_csv = true) {
  const fs::path dir = fresh(name);
  if (write_csv) std::ofstream(dir / "ref.csv") << csv_text;
  std::ofstream(dir / "s.toml") << a01_study(std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/benchmarks/a01_pendulum.toml",
                                             "reference = \"csv\"\n" + extra);
  ProgramRun run = run_program("study '" + (dir / "s.toml").string() + "' --out '" + (dir / "out").string() + "' --quiet");
  // nothing is written for a refused study
  EXPECT_FALSE(fs::exists(dir / "out" / "study.csv")) << name;
  fs::remove_all(dir);
  return run;
}

TEST(StudyCsvReference, HostileFilesExitTwoWithALocatedMessage) {
  const std::string file = "reference_file = \"ref.csv\"\n";
  const std::string good_header = "t,probe.bob.x,probe.bob.y\n";
  struct Case {
    std::string name, csv, extra, expect;
  };
  const std::vector<Case> cases = {
      {"missing_column", "t,probe.bob.x\n0,1\n10,1\n", file, "ref.csv:1:1: key 'probe.bob.y': the reference file has no column 'probe.bob.y' (its columns: t, probe.bob.x)"},
      {"word", good_header + "0,1,0\n5,one,0\n10,1,0\n", file, "ref.csv:3:3: key 'probe.bob.x': expected a finite number, found 'one'"},
      {"nan", good_header + "0,1,0\n5,1,nan\n10,1,0\n", file, "ref.csv:3:5: key 'probe.bob.y'"},
      {"backwards", good_header + "0,1,0\n5,1,0\n4,1,0\n10,1,0\n", file, "ref.csv:4:1: key 't': time 4 does not increase"},
      {"short", good_header + "0,1,0\n5,1,0\n9.5,1,0\n", file, "covers t = 0 to 9.5 s, not the study's 0 to 10 s"},
      {"late_start", good_header + "0.5,1,0\n10,1,0\n", file, "covers t = 0.5 to 10 s"},
      {"ragged", good_header + "0,1,0\n5,1\n10,1,0\n", file, "ref.csv:3:1: this row has 2 cells, the header 3"},
      {"empty", "", file, "the reference file is empty"},
      {"no_time", "time,probe.bob.x,probe.bob.y\n0,1,0\n10,1,0\n", file, "has no column 't'"},
      {"no_file", "", "", "reference = \"csv\" needs the file of the reference trajectory"},
      {"unknown_run_column", good_header + "0,1,0\n10,1,0\n", file + "columns = [\"probe.tip.x\"]\n",
       "key 'study.columns': the scene has no column 'probe.tip.x' to compare (its probe columns: probe.bob.x"},
  };
  for (const Case& c : cases) {
    const ProgramRun run = hostile(c.name, c.csv, c.extra);
    EXPECT_EQ(run.exit_code, 2) << c.name << ": " << run.output;
    EXPECT_NE(run.output.find(c.expect), std::string::npos) << c.name << ": " << run.output;
  }
  // a file named but absent: located at the study key that names it
  const ProgramRun absent = hostile("absent", "", file, false);
  EXPECT_EQ(absent.exit_code, 2) << absent.output;
  EXPECT_NE(absent.output.find("s.toml:4:18: key 'study.reference_file': cannot read the reference file"),
            std::string::npos) << absent.output;
}

}  // namespace
}  // namespace periflex
