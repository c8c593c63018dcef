// The magnified deformation through the program, as typed: `periflex run --snapshot-at T
// --screenshot ... --deform K` of the notched plate while its grips bend it. The plate's lower
// edge is found in the pictures column by column; at true scale its strains of 1e-3 leave it
// where the undeformed plate has it, at K = 100 it moves by several pixels.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "../cli/run_program.h"
#include "io/image.h"
#include "render/renderer.h"

namespace periflex::testing {
namespace {

namespace fs = std::filesystem;

// a fixed view, 2.5e-4 m per pixel: the 100 mm x 40 mm plate is 400 x 160 pixels in the middle
constexpr int kWidth = 640, kHeight = 480;
constexpr double kViewHeight = 0.12, kMetresPerPixel = kViewHeight / kHeight;
// 0.3 ms into the run: the grips have turned by 1.8 mrad, before the crack starts (near 0.4 ms)
constexpr const char* kTime = "3e-4";

RgbaImage screenshot(const std::string& deform) {
  const auto out = fresh_directory("deform_" + deform);
  const auto shot = out / "shot.png";
  const auto r = run_periflex("run " + scene("notched_plate.toml") + " --until " + kTime + " --snapshot-at " +
                              kTime + " --screenshot " + shot.string() + " --camera 0,0," +
                              std::to_string(kViewHeight) + " --size " + std::to_string(kWidth) + "x" +
                              std::to_string(kHeight) + " --deform " + deform + " --quiet --out " + out.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return read_png(shot.string());
}

// The lowest drawn pixel row of column x in the band around the plate's lower edge (the overlay
// at the picture's bottom lies below it); -1 when the column is background there.
int lower_edge(const RgbaImage& image, int x) {
  const RenderSettings defaults;
  int bg[3];
  for (int c = 0; c < 3; ++c) bg[c] = int(std::lround(defaults.background[c] * 255));
  const int edge = kHeight / 2 + int(0.02 / kMetresPerPixel);
  for (int y = std::min(kHeight - 1, edge + 60); y > edge - 60; --y) {
    const uint8_t* p = image.at(x, y);
    if (std::abs(p[0] - bg[0]) + std::abs(p[1] - bg[1]) + std::abs(p[2] - bg[2]) > 60) return y;
  }
  return -1;
}

// the columns of the plate's lower edge, away from the notch (|x| < 4 mm) and from the grips
std::vector<int> edge_columns() {
  std::vector<int> columns;
  for (int x = kWidth / 2 - int(0.044 / kMetresPerPixel); x <= kWidth / 2 + int(0.044 / kMetresPerPixel); ++x)
    if (std::abs(x - kWidth / 2) > int(0.004 / kMetresPerPixel)) columns.push_back(x);
  return columns;
}

TEST(DeformationRender, NotchedPlateLowerEdgeMovesAtHundredfoldAndNotAtZero) {
  const RgbaImage undeformed = screenshot("0"), true_scale = screenshot("1"), magnified = screenshot("100");
  ASSERT_EQ(undeformed.width, kWidth);
  // where the undeformed plate's lower edge is drawn: its particle discs reach y = -0.02 m
  const int reference = kHeight / 2 + int(std::lround(0.02 / kMetresPerPixel));
  int largest_true = 0, largest_magnified = 0;
  for (int x : edge_columns()) {
    const int e0 = lower_edge(undeformed, x), e1 = lower_edge(true_scale, x), e100 = lower_edge(magnified, x);
    ASSERT_GE(e0, 0) << "no plate drawn in column " << x;
    EXPECT_NEAR(e0, reference, 2) << "K = 0: the undeformed edge in column " << x;
    largest_true = std::max(largest_true, std::abs(e1 - e0));
    if (e100 >= 0) largest_magnified = std::max(largest_magnified, std::abs(e100 - e0));
    else largest_magnified = std::max(largest_magnified, 60);  // moved out of the searched band
  }
  std::printf("largest move of the lower edge: %d px at true scale, %d px at K = 100\n", largest_true,
              largest_magnified);
  // at true scale the bending is invisible: that is why the magnification exists
  EXPECT_LE(largest_true, 1);
  EXPECT_GE(largest_magnified, 8);
}

TEST(DeformationRender, BadFactorIsRefusedNamingTheFlag) {
  const auto out = fresh_directory("deform_bad");
  for (const std::string bad : {"-1", "lots", "nan", "1e9"}) {
    const auto r = run_periflex("run " + scene("pendulum.toml") + " --until 0.01 --render --deform " + bad +
                                " --quiet --out " + out.string());
    EXPECT_EQ(r.exit_code, 2) << bad << ": " << r.output;
    EXPECT_NE(r.output.find("--deform"), std::string::npos) << r.output;
  }
}

}  // namespace
}  // namespace periflex::testing
