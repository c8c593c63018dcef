// The energy error against time of a time study: one value per comparison time for every run,
// its largest value the row's energy error, written as energy.csv and plotted for the largest
// step of each method.
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include "study/energy_trace.h"
#include "study/study_def.h"
#include "study/study_runner.h"

namespace periflex {
namespace {

StudyResult pendulum_study() {
  const std::string text = std::string("[study]\nscene = \"") + PERIFLEX_SOURCE_ROOT +
                           "/scenes/studies/models/pendulum.toml\"\nreference = \"pendulum_exact\"\n"
                           "end_time = 1.0\ncompare_interval = 0.1\n"
                           "[[method]]\nintegrator = \"symplectic_euler\"\ndt = [4e-3, 2e-3]\ncorrection = \"projection\"\n"
                           "[[method]]\nintegrator = \"rk4\"\ndt = [2e-2, 1e-2]\ncorrection = \"none\"\n";
  return run_study(parse_study(text, "energy.toml"));
}

TEST(EnergyTrace, EveryRunHasItsEnergyErrorAtEveryComparisonTime) {
  const StudyResult result = pendulum_study();
  ASSERT_EQ(result.times.size(), 11u);
  ASSERT_EQ(result.rows.size(), 4u);
  for (const StudyRow& row : result.rows) {
    ASSERT_EQ(row.energy_trace.size(), result.times.size()) << energy_run_label(row);
    EXPECT_EQ(row.energy_trace.front(), 0.0);
    // the row's energy error is the largest of its trace
    EXPECT_DOUBLE_EQ(*std::max_element(row.energy_trace.begin(), row.energy_trace.end()), row.energy_error_rel);
    EXPECT_GT(row.energy_error_rel, 0.0);
  }
  // first order against fourth: symplectic Euler's energy error is far above RK4's
  EXPECT_GT(result.rows[0].energy_error_rel, 100.0 * result.rows[2].energy_error_rel);

  // energy.csv: a header naming every run, then one row per comparison time
  const std::string csv = energy_trace_csv(result);
  std::istringstream in(csv);
  std::string header, line;
  std::getline(in, header);
  EXPECT_EQ(header, "t,symplectic_euler / projection dt 0.004,symplectic_euler / projection dt 0.002,"
                    "rk4 / none dt 0.02,rk4 / none dt 0.01");
  int rows = 0;
  while (std::getline(in, line)) ++rows;
  EXPECT_EQ(rows, 11);

  // the plot draws the largest step of each method: columns 2 (dt 0.004) and 4 (dt 0.02)
  const std::string script = energy_trace_gnuplot_script(result, "energy.csv", "energy.png");
  EXPECT_NE(script.find("column(2)"), std::string::npos) << script;
  EXPECT_NE(script.find("column(4)"), std::string::npos) << script;
  EXPECT_EQ(script.find("column(3)"), std::string::npos) << script;
  EXPECT_EQ(script.find("column(5)"), std::string::npos) << script;
}

}  // namespace
}  // namespace periflex
