// The hot reload's watch of the scene file: one change reported once, none while unchanged or
// gone, and not checked more often than asked.
#include "app/file_watch.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace periflex {
namespace {

namespace fs = std::filesystem;

TEST(FileWatch, ReportsEachChangeOnceAfterItsInterval) {
  const fs::path path = fs::path(::testing::TempDir()) / "watched.toml";
  std::ofstream(path) << "a = 1\n";
  FileWatch watch(0.3);
  watch.watch(path.string(), 0.0);
  EXPECT_FALSE(watch.changed(1.0));
  std::ofstream(path) << "a = 22\n";  // another size: a change even within the clock's resolution
  EXPECT_FALSE(watch.changed(1.1));   // checked 0.1 s after the last check: not yet
  EXPECT_TRUE(watch.changed(1.5));
  EXPECT_FALSE(watch.changed(2.0));   // reported once
  // gone (an editor writing a new file in its place), then back with other text
  fs::remove(path);
  EXPECT_FALSE(watch.changed(3.0));
  std::ofstream(path) << "a = 333\n";
  EXPECT_TRUE(watch.changed(4.0));
}

TEST(FileWatch, SameSizeNewTimeIsAChange) {
  const fs::path path = fs::path(::testing::TempDir()) / "watched_time.toml";
  std::ofstream(path) << "a = 1\n";
  FileWatch watch(0.0);
  watch.watch(path.string(), 0.0);
  fs::last_write_time(path, fs::last_write_time(path) + std::chrono::seconds(2));
  EXPECT_TRUE(watch.changed(1.0));
  EXPECT_FALSE(watch.changed(2.0));
}

TEST(FileWatch, NoPathWatchesNothing) {
  FileWatch watch;
  watch.watch("", 0.0);
  EXPECT_FALSE(watch.changed(10.0));
}

}  // namespace
}  // namespace periflex
