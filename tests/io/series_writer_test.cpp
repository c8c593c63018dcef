// series.csv rows reach the file whole: one write() system call per row however wide the row,
// so a run killed at any instant leaves complete rows (README: outputs survive a kill).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "io/series_writer.h"

namespace periflex {
namespace {

// Write system calls this process has made so far (/proc/self/io, field syscw).
long write_calls() {
  std::ifstream in("/proc/self/io");
  for (std::string key; in >> key;) {
    long value = 0;
    in >> value;
    if (key == "syscw:") return value;
  }
  return -1;
}

TEST(SeriesWriter, EachRowOfHundredsOfProbesIsOneWriteCall) {
  if (write_calls() < 0) GTEST_SKIP() << "no /proc/self/io on this system";
  const std::filesystem::path path = ::testing::TempDir() + "series_writer_test.csv";
  // 300 probes of 3 columns: rows of about 10 kB, more than any stdio buffer
  std::vector<std::string> columns;
  for (int k = 0; k < 900; ++k) columns.push_back("probe.p" + std::to_string(k) + ".x");
  SeriesWriter writer(path.string(), columns, true);
  Sample sample;
  sample.probe_values.assign(columns.size(), 0.0);
  for (size_t k = 0; k < sample.probe_values.size(); ++k) sample.probe_values[k] = 1.0 / 3.0 + static_cast<double>(k);

  for (int row = 0; row < 5; ++row) {
    sample.time = row * 1e-3;
    const long before = write_calls();
    ASSERT_TRUE(writer.write(sample));
    EXPECT_EQ(write_calls() - before, 1) << "row " << row << " took several write calls";
  }

  // every row whole and as wide as the header
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  const auto header_commas = std::count(line.begin(), line.end(), ',');
  int rows = 0;
  while (std::getline(in, line)) {
    EXPECT_GT(line.size(), 8000u);
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), header_commas);
    ++rows;
  }
  EXPECT_EQ(rows, 5);
}

// A value read back from series.csv is the double the solver had, bit for bit: comparisons with a
// reference at 1e-13 must not be limited by the file (12 significant digits lose 1e-12 relative).
TEST(SeriesWriter, ValuesReadBackAreTheSameDoubles) {
  const std::filesystem::path path = ::testing::TempDir() + "series_writer_round_trip.csv";
  const std::vector<double> probes = {1.0 / 3.0,  0.1 + 0.2, -2.0 / 7.0 * 1e-9, 1e300 / 3.0,
                                      std::numeric_limits<double>::denorm_min(), 123456789.123456789, -0.0};
  const double time = 0.1 * 3;  // 0.30000000000000004
  std::vector<std::string> columns;
  for (size_t k = 0; k < probes.size(); ++k) columns.push_back("probe.p" + std::to_string(k) + ".x");
  {
    SeriesWriter writer(path.string(), columns, false);
    Sample sample;
    sample.time = time;
    sample.probe_values = probes;
    ASSERT_TRUE(writer.write(sample));
  }
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::getline(in, line);
  std::vector<double> read;
  std::stringstream cells(line);
  for (std::string cell; std::getline(cells, cell, ',');) read.push_back(std::strtod(cell.c_str(), nullptr));
  ASSERT_EQ(read.size(), 11 + probes.size());
  EXPECT_EQ(std::memcmp(&read[0], &time, sizeof(double)), 0) << line;
  for (size_t k = 0; k < probes.size(); ++k) {
    const double back = read[11 + k];
    EXPECT_EQ(std::memcmp(&back, &probes[k], sizeof(double)), 0) << "column " << columns[k] << ": " << line;
  }
}

// What a run restarted into its own folder keeps of its series.csv: the whole rows before the
// restart time, and nothing from a file of other columns.
TEST(SeriesWriter, RowsBeforeARestartAreTheWholeRowsBeforeItsTime) {
  const std::string path = (std::filesystem::temp_directory_path() / "periflex_rows_before.csv").string();
  const std::vector<std::string> columns = {"t", "kinetic"};
  std::ofstream(path) << "t,kinetic\n0,1\n0.5,2\n1,3\n1.5,4\n";
  EXPECT_EQ(series_rows_before(path, columns, 1.0), "0,1\n0.5,2\n");  // the row at 1 is written again
  EXPECT_EQ(series_rows_before(path, columns, 1.2), "0,1\n0.5,2\n1,3\n");
  EXPECT_EQ(series_rows_before(path, columns, 0.0), "");
  EXPECT_EQ(series_rows_before(path, {"t", "potential_gravity"}, 1.2), "") << "another scene's file";
  // a run killed mid-row: the cut row and what follows are not kept
  std::ofstream(path) << "t,kinetic\n0,1\n0.5,2\n1,\n";
  EXPECT_EQ(series_rows_before(path, columns, 9.0), "0,1\n0.5,2\n");
  std::ofstream(path) << "t,kinetic\n0,1\n0.5,2";
  EXPECT_EQ(series_rows_before(path, columns, 9.0), "0,1\n");
  std::filesystem::remove(path);
  EXPECT_EQ(series_rows_before(path, columns, 9.0), "") << "no file";
}

}  // namespace
}  // namespace periflex
