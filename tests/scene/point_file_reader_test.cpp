// Point files as other peridynamic codes write them: separators, headers, comments, units and
// blocks read as documented, and every bad row refused naming its line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "scene/point_file_reader.h"

namespace periflex {
namespace {

std::string write_file(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("periflex_points_" + name);
  std::ofstream(path) << text;
  return path.string();
}

// The line an InputError names, or -1 when none was thrown.
int error_line(const std::string& path, const PointFileOptions& options, std::string* message = nullptr) {
  try {
    read_point_file(path, options);
  } catch (const InputError& e) {
    if (message) *message = e.what();
    return e.where().line;
  }
  return -1;
}

TEST(PointFileReader, ReadsCommasBlanksHeaderAndComments) {
  const std::string csv = write_file("a.csv", "# from another code\nx, y, volume, block, no_fail\n\n"
                                              "0.5,1.5,2e-9,1,0\n-1e-3 , 2 , 3e-9 , 1 , 1   # a comment\n");
  const ParticleCloud a = read_point_file(csv, {});
  ASSERT_EQ(a.size(), 2);
  EXPECT_EQ(a.x[0], 0.5);
  EXPECT_EQ(a.y[1], 2.0);
  EXPECT_EQ(a.volume[1], 3e-9);
  EXPECT_EQ(a.no_fail[0], 0);
  EXPECT_EQ(a.no_fail[1], 1);
  EXPECT_EQ(a.line[0], 4);
  EXPECT_EQ(a.line[1], 5);
  const std::string txt = write_file("b.txt", "0.5\t1.5  2e-9\n\n  -1e-3 2 3e-9\r\n");
  const ParticleCloud b = read_point_file(txt, {});
  ASSERT_EQ(b.size(), 2);
  EXPECT_EQ(b.x[1], -1e-3);
  EXPECT_EQ(b.line[1], 3);
}

TEST(PointFileReader, ScaleConvertsLengthsAndVolumeByItsCube) {
  const std::string path = write_file("mm.csv", "2,3,4\n");
  PointFileOptions options;
  options.scale = 1e-3;
  const ParticleCloud c = read_point_file(path, options);
  EXPECT_DOUBLE_EQ(c.x[0], 2e-3);
  EXPECT_DOUBLE_EQ(c.y[0], 3e-3);
  EXPECT_DOUBLE_EQ(c.volume[0], 4e-9);
}

TEST(PointFileReader, BlockKeepsOnlyItsPoints) {
  const std::string path = write_file("blocks.csv", "0,0,1,1\n1,0,1,2\n2,0,1,2\n3,0,1\n");
  PointFileOptions options;
  options.block = 2;
  const ParticleCloud c = read_point_file(path, options);
  ASSERT_EQ(c.size(), 2);
  EXPECT_EQ(c.x[0], 1.0);
  EXPECT_EQ(c.line[1], 3);
  options.block = 7;
  std::string message;
  error_line(path, options, &message);
  EXPECT_NE(message.find("no point in block 7"), std::string::npos) << message;
}

// Each point's block is kept for materials by block; rows without the column are in no block (-1),
// and a file without the column keeps none.
TEST(PointFileReader, BlockColumnIsKeptForEachPoint) {
  const ParticleCloud c = read_point_file(write_file("kept.csv", "0,0,1\n1,0,1,2\n2,0,1,0\n"), {});
  EXPECT_EQ(c.block, (std::vector<long>{-1, 2, 0}));
  EXPECT_EQ(read_point_file(write_file("first.csv", "0,0,1,3\n1,0,1\n2,0,1,4\n"), {}).block, (std::vector<long>{3, -1, 4}));
  EXPECT_TRUE(read_point_file(write_file("none.csv", "0,0,1\n1,0,1\n"), {}).block.empty());
}

TEST(PointFileReader, BadRowsNameTheirLine) {
  std::string message;
  EXPECT_EQ(error_line(write_file("cols.csv", "0,0,1\n0,1\n"), {}, &message), 2);
  EXPECT_NE(message.find("3 to 5 columns"), std::string::npos) << message;
  EXPECT_EQ(error_line(write_file("word.csv", "0,0,1\n0,0,1\n1,abc,1\n"), {}, &message), 3);
  EXPECT_NE(message.find("'abc'"), std::string::npos) << message;
  EXPECT_EQ(error_line(write_file("nan.csv", "0,nan,1\n"), {}, &message), 1);
  EXPECT_EQ(error_line(write_file("flag.csv", "0,0,1,1,2\n"), {}, &message), 1);
  EXPECT_NE(message.find("no_fail must be 0 or 1"), std::string::npos) << message;
}

TEST(PointFileReader, ZeroAndNegativeVolumesNameTheirLine) {
  std::string message;
  EXPECT_EQ(error_line(write_file("zero.csv", "0,0,1\n# c\n1,0,0\n"), {}, &message), 3);
  EXPECT_NE(message.find("volume must be positive"), std::string::npos) << message;
  EXPECT_EQ(error_line(write_file("neg.csv", "0,0,-1e-9\n"), {}, &message), 1);
}

// The budget is checked on the count of lines, before any row is parsed: a bad row after the
// limit is never reached.
TEST(PointFileReader, TooManyPointsRefusedBeforeAnyRowIsRead) {
  std::string text;
  for (int k = 0; k < 11; ++k) text += std::to_string(k) + ",0,1\n";
  text += "this row is never parsed\n";
  PointFileOptions options;
  options.max_points = 10;
  std::string message;
  error_line(write_file("many.csv", text), options, &message);
  EXPECT_NE(message.find("holds 12 points, more than limits.max_particles = 10"), std::string::npos) << message;
}

TEST(PointFileReader, MissingAndEmptyFilesRefused) {
  std::string message;
  error_line("/nonexistent/points.csv", {}, &message);
  EXPECT_NE(message.find("cannot be opened"), std::string::npos) << message;
  error_line(write_file("empty.csv", "# nothing\nx,y,volume\n"), {}, &message);
  EXPECT_NE(message.find("has no point"), std::string::npos) << message;
}

}  // namespace
}  // namespace periflex
