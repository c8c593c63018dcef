// The study pipeline end to end on the slider-crank: a CSV with the documented columns and one
// row per grid point, errors against the closed form that fall as dt falls, and the Markdown
// table beside it.
#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "study/study_def.h"
#include "study/study_report.h"
#include "study/study_runner.h"

namespace periflex {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ',')) out.push_back(cell);
  return out;
}

TEST(StudyOutputs, CsvHasTheColumnsAndARowPerGridPointWithFallingErrors) {
  const std::string text = std::string(R"(
[study]
name = "slider_crank_test"
scene = ")") + PERIFLEX_SOURCE_ROOT + R"(/scenes/studies/models/slider_crank.toml"
reference = "slider_crank_exact"
end_time = 0.5
compare_interval = 0.01
[[method]]
integrator = "rk4"
dt = [1e-2, 5e-3, 2.5e-3]
correction = "none"
[[method]]
integrator = "verlet"
dt = [2e-3, 1e-3, 5e-4]
correction = "baumgarte"
[[method]]
integrator = "rk4"
dt = 5e-3
correction = "projection"
)";
  const StudyResult result = run_study(parse_study(text, "study_outputs_test.toml"));
  const auto dir = std::filesystem::temp_directory_path() / ("periflex_study_outputs_test_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  const StudyOutputs outputs = write_study_outputs(result, dir.string());

  std::ifstream csv(outputs.csv_path);
  std::string line;
  ASSERT_TRUE(std::getline(csv, line));
  EXPECT_EQ(split(line), study_csv_columns());
  std::vector<std::vector<std::string>> rows;
  while (std::getline(csv, line)) rows.push_back(split(line));
  // 3 + 3 + 1 grid points
  ASSERT_EQ(rows.size(), 7u);
  const auto column = [&](const std::string& name) {
    const auto& c = study_csv_columns();
    return static_cast<size_t>(std::find(c.begin(), c.end(), name) - c.begin());
  };
  for (const auto& r : rows) {
    ASSERT_EQ(r.size(), study_csv_columns().size());
    EXPECT_EQ(r[column("status")], "ok");
    EXPECT_GT(std::stod(r[column("wall_time")]), 0.0);
  }
  // within each series the error falls with dt: rows are written series by series, dt descending
  const size_t err = column("error_max");
  for (size_t first : {size_t(0), size_t(3)})
    for (size_t k = first; k + 1 < first + 3; ++k)
      EXPECT_LT(std::stod(rows[k + 1][err]), std::stod(rows[k][err])) << "row " << k;
  // the mechanism has no free coordinate, so the projection puts it on the closed form itself
  // (to the projection tolerance of the scene, 1e-10)
  EXPECT_LT(std::stod(rows[6][err]), 1e-9);
  EXPECT_LT(std::stod(rows[6][column("violation")]), 1e-9);

  std::ifstream md(outputs.markdown_path);
  std::stringstream md_text;
  md_text << md.rdbuf();
  EXPECT_NE(md_text.str().find("| rk4 | projection |"), std::string::npos);
  EXPECT_NE(md_text.str().find("Observed order"), std::string::npos);
  // with gnuplot installed, a plot (a PNG file); without it, a clear word that there is none
  if (gnuplot_available()) {
    ASSERT_FALSE(outputs.plot_path.empty()) << outputs.plot_message;
    std::ifstream png(outputs.plot_path, std::ios::binary);
    std::string head(8, '\0');
    png.read(head.data(), 8);
    EXPECT_EQ(head, "\x89PNG\r\n\x1a\n") << outputs.plot_path;
  } else {
    EXPECT_NE(outputs.plot_message.find("no plot made"), std::string::npos);
  }
  std::filesystem::remove_all(dir);
}

TEST(StudyOutputs, StepsThatMissTheComparisonTimesAreRefused) {
  const std::string text = std::string(R"(
[study]
scene = ")") + PERIFLEX_SOURCE_ROOT + R"(/scenes/studies/models/pendulum.toml"
reference = "pendulum_exact"
end_time = 0.1
compare_interval = 0.01
[[method]]
integrator = "rk4"
dt = 3e-3
)";
  EXPECT_THROW(run_study(parse_study(text, "bad_study.toml")), InputError);
}

}  // namespace
}  // namespace periflex
