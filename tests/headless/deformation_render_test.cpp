// The magnified deformation through the program, as typed: `periflex run --snapshot-at T
// --screenshot ... --deform K` of the notched plate while its grips bend it. The plate's lower
// edge is found in the pictures column by column; at true scale its strains of 1e-3 leave it
// where the undeformed plate has it, at K = 100 it moves by several pixels.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
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
constexpr int kDeformWidth = 640, kDeformHeight = 480;
constexpr double kViewHeight = 0.12, kMetresPerPixel = kViewHeight / kDeformHeight;
// 0.3 ms into the run: the grips have turned by 1.8 mrad, before the crack starts (near 0.4 ms)
constexpr const char* kTime = "3e-4";

RgbaImage screenshot(const std::string& deform) {
  // a folder of the test's own: ctest runs the tests of this file at the same time, and two
  // taking the same factor would empty each other's folder
  const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  const auto out = fresh_directory("deform_" + deform + "_" + test);
  const auto shot = out / "shot.png";
  const auto r = run_periflex("run " + scene("notched_plate.toml") + " --until " + kTime + " --snapshot-at " +
                              kTime + " --screenshot " + shot.string() + " --camera 0,0," +
                              std::to_string(kViewHeight) + " --size " + std::to_string(kDeformWidth) + "x" +
                              std::to_string(kDeformHeight) + " --deform " + deform + " --quiet --out " + out.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return read_png(shot.string());
}

// The lowest drawn pixel row of column x in the band around the plate's lower edge (the overlay
// at the picture's bottom lies below it); -1 when the column is background there.
int lower_edge(const RgbaImage& image, int x) {
  const RenderSettings defaults;
  int bg[3];
  for (int c = 0; c < 3; ++c) bg[c] = int(std::lround(defaults.background[c] * 255));
  const int edge = kDeformHeight / 2 + int(0.02 / kMetresPerPixel);
  for (int y = std::min(kDeformHeight - 1, edge + 60); y > edge - 60; --y) {
    const uint8_t* p = image.at(x, y);
    if (std::abs(p[0] - bg[0]) + std::abs(p[1] - bg[1]) + std::abs(p[2] - bg[2]) > 60) return y;
  }
  return -1;
}

// the columns of the plate's lower edge, away from the notch (|x| < 4 mm) and from the grips
std::vector<int> edge_columns() {
  std::vector<int> columns;
  for (int x = kDeformWidth / 2 - int(0.044 / kMetresPerPixel); x <= kDeformWidth / 2 + int(0.044 / kMetresPerPixel); ++x)
    if (std::abs(x - kDeformWidth / 2) > int(0.004 / kMetresPerPixel)) columns.push_back(x);
  return columns;
}

TEST(DeformationRender, NotchedPlateLowerEdgeMovesAtHundredfoldAndNotAtZero) {
  const RgbaImage undeformed = screenshot("0"), true_scale = screenshot("1"), magnified = screenshot("100");
  ASSERT_EQ(undeformed.width, kDeformWidth);
  // where the undeformed plate's lower edge is drawn: its particle discs reach y = -0.02 m
  const int reference = kDeformHeight / 2 + int(std::lround(0.02 / kMetresPerPixel));
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

// The box (x0, y0, x1, y1) of the pixels around the plate's left end matching `is`; x0 > x1
// when none does.
template <class Colour>
std::array<int, 4> left_end_box(const RgbaImage& image, Colour is) {
  // the band of the plate's height and 15 mm more each way, left of the notch's damage
  std::array<int, 4> box = {kDeformWidth, kDeformHeight, -1, -1};
  const int band = int(0.035 / kMetresPerPixel);
  for (int y = kDeformHeight / 2 - band; y < kDeformHeight / 2 + band; ++y)
    for (int x = 0; x < kDeformWidth / 2 - int(0.02 / kMetresPerPixel); ++x) {
      const uint8_t* p = image.at(x, y);
      if (!is(p[0], p[1], p[2])) continue;
      box = {std::min(box[0], x), std::min(box[1], y), std::max(box[2], x), std::max(box[3], y)};
    }
  return box;
}

TEST(DeformationRender, NotchedPlateGripsMoveWithTheirMagnifiedParticles) {
  // at K = 100 the plate's ends swing far from their true places; the left grip (a virtual
  // body, drawn with an orange dashed edge) must still enclose the particles it holds (drawn
  // with magenta rings), not stay behind where the true grip is
  const RgbaImage magnified = screenshot("100");
  const auto held = left_end_box(magnified, [](int r, int g, int b) { return r > 170 && g < 140 && b > 170; });
  const auto grip = left_end_box(magnified, [](int r, int g, int b) {
    return r > 200 && g > 140 && g < 200 && b < 110;
  });
  ASSERT_LE(held[0], held[2]) << "no held particle drawn";
  ASSERT_LE(grip[0], grip[2]) << "no grip drawn";
  std::printf("held particles x %d..%d y %d..%d, grip x %d..%d y %d..%d\n", held[0], held[2], held[1], held[3],
              grip[0], grip[2], grip[1], grip[3]);
  // the held column, 3 mm wide, leans by several pixels at K = 100 (else nothing is tested)
  EXPECT_GT(held[2] - held[0], int(0.003 / kMetresPerPixel) + 6);
  // the grip's outline around them, within the width of its dashed line
  EXPECT_LE(grip[0], held[0] + 2);
  EXPECT_GE(grip[2], held[2] - 2);
  EXPECT_GE(grip[3], held[3] - 2);
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
