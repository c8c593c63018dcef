// `run --plot` as typed: the plot of series.csv columns at the top right of each frame holds
// every row the run wrote up to the frame's time (a single screenshot shows the whole curve, not
// one point), and a checkpoint folder replayed with --plot changes nothing outside the plot's
// box. The refusals of bad names are in run_command_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "child_run.h"
#include "io/image.h"
#include "run_output_files.h"
#include "run_program.h"

namespace periflex::testing {
namespace {

#ifdef PERIFLEX_TEST_RENDER
namespace fs = std::filesystem;

// the plot's box at 320x200: 150 x 110 pixels, 6 from the top and right edges (plot_box)
constexpr int kWidth = 320, kBoxLeft = 320 - 6 - 150, kBoxBottom = 6 + 110;

// Pixels of the plot's box below its title and legend (from y = 50) within 40 (summed over r, g,
// b) of a colour: the box's dark background dims the scene under it, and the text in the series'
// colours sits above, so only the plot's own lines come near those colours there.
long box_pixels_near(const RgbaImage& image, int r, int g, int b) {
  long n = 0;
  for (int y = 50; y < kBoxBottom; ++y) {
    for (int x = kBoxLeft; x < image.width; ++x) {
      const unsigned char* p = &image.pixels[4 * (static_cast<size_t>(y) * image.width + x)];
      if (std::abs(p[0] - r) + std::abs(p[1] - g) + std::abs(p[2] - b) < 40) ++n;
    }
  }
  return n;
}

// One screenshot at 0.4 ms of the cracking plate: its plot of the driver's work is a line
// through the rows written every 10 steps, where the screenshot's own row alone would be a point.
TEST(RunPlot, ScreenshotPlotsEveryRowUpToItsTime) {
  const fs::path dir = fresh_directory("plot_shot");
  const auto r = run_child({"run", scene("notched_plate.toml"), "--quiet", "--until", "4e-4", "--snapshot-at", "4e-4",
                            "--screenshot", (dir / "shot.png").string(), "--size", "320x200", "--plot",
                            "driver_work", "--out", (dir / "out").string(), "--threads", "1"},
                           120);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const RgbaImage shot = read_png((dir / "shot.png").string());
  ASSERT_EQ(shot.width, kWidth);
  // the line rises across the lower part of the frame: dozens of pixels of its colour there
  EXPECT_GT(box_pixels_near(shot, 255, 190, 60), 40) << "no driver_work line in the screenshot's plot";
}

// The folder of a run replayed with and without --plot: the frames differ inside the plot's box
// only, and there both series' lines are drawn.
TEST(RunPlot, ReplayedPlotStaysInItsBox) {
  const fs::path dir = fresh_directory("plot_replay");
  const auto live = run_child({"run", scene("notched_plate.toml"), "--quiet", "--until", "6e-4", "--out",
                               (dir / "live").string(), "--checkpoint-every", "1.37e-4", "--threads", "1"},
                              120);
  ASSERT_EQ(live.exit_code, 0) << live.output;
  const auto replay_into = [&](const std::string& name, std::vector<std::string> extra) {
    std::vector<std::string> args = {"run", (dir / "live" / "checkpoints").string(), "--render", "--frames",
                                     (dir / name).string(), "--size", "320x200", "--out",
                                     (dir / (name + "_out")).string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = run_child(args, 60);
    EXPECT_EQ(r.exit_code, 0) << r.output;
  };
  replay_into("plotted", {"--plot", "driver_work+fracture"});
  replay_into("plain", {});
  const auto plotted = files_with_extension(dir / "plotted", ".png");
  const auto plain = files_with_extension(dir / "plain", ".png");
  ASSERT_EQ(plotted.size(), 5u);
  ASSERT_EQ(plain.size(), 5u);

  const RgbaImage with = read_png(plotted[4].string()), without = read_png(plain[4].string());
  ASSERT_EQ(with.width, kWidth);
  ASSERT_EQ(without.width, kWidth);
  long inside = 0, outside = 0;
  for (int y = 0; y < with.height; ++y) {
    for (int x = 0; x < with.width; ++x) {
      const size_t i = 4 * (static_cast<size_t>(y) * with.width + x);
      const bool differs = std::memcmp(&with.pixels[i], &without.pixels[i], 3) != 0;
      ((x >= kBoxLeft && y < kBoxBottom) ? inside : outside) += differs;
    }
  }
  EXPECT_EQ(outside, 0);
  EXPECT_GT(inside, 150 * 110 / 2) << "the plot's box is not drawn";
  EXPECT_GT(box_pixels_near(with, 255, 190, 60), 20) << "no driver_work line";
  EXPECT_GT(box_pixels_near(with, 90, 160, 255), 20) << "no fracture line";
  EXPECT_EQ(box_pixels_near(without, 255, 190, 60), 0);
}
#endif

}  // namespace
}  // namespace periflex::testing
