// series.csv rows reach the file whole: one write() system call per row however wide the row,
// so a run killed at any instant leaves complete rows (README: outputs survive a kill).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "output/series_writer.h"

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
  const auto path = std::filesystem::current_path() / "series_writer_test.csv";
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

}  // namespace
}  // namespace periflex
