// A picture sampled at the grid spacing: dark pixels become the particles a box of the same
// size would have there, red ones particles that never break, blue ones grip particles, and pictures that cannot give a
// body are refused naming the file.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/error.h"
#include "io/image.h"
#include "pd/particle_grid.h"
#include "scene/image_shape.h"

namespace periflex {
namespace {

// A w x h picture, every pixel `paint(x, y)` (x right, y down, as in the file).
template <class Paint>
std::string picture(const std::string& name, int w, int h, Paint paint) {
  RgbaImage image;
  image.resize(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::array<uint8_t, 4> c = paint(x, y);
      std::copy(c.begin(), c.end(), image.at(x, y));
    }
  const auto path = std::filesystem::temp_directory_path() / ("periflex_image_" + name + ".png");
  write_png(path.string(), image);
  return path.string();
}

constexpr std::array<uint8_t, 4> kBlack = {0, 0, 0, 255}, kWhite = {255, 255, 255, 255}, kRed = {230, 20, 20, 255},
                                  kBlue = {20, 20, 230, 255};

ImageShapeOptions options(double width, double dx) {
  ImageShapeOptions o;
  o.width = width;
  o.dx = dx;
  o.thickness = 2e-3;
  return o;
}

// The left half black: the particles of the left half of the box the picture covers, at the
// very positions the box's own grid has.
TEST(ImageShape, DarkPixelsAreTheBoxGridsParticlesThere) {
  const std::string path = picture("half", 80, 40, [](int x, int) { return x < 40 ? kBlack : kWhite; });
  const ParticleCloud cloud = read_image_shape(path, options(0.08, 1e-3));
  ShapeDef box;
  box.kind = ShapeDef::Kind::kBox;
  box.width = 0.08;
  box.height = 0.04;
  const ParticleGrid grid = fill_grid(box, {}, 1e-3);
  std::vector<std::pair<double, double>> expected;
  for (int i = 0; i < grid.size(); ++i)
    if (grid.x[i] < 0.0) expected.emplace_back(grid.x[i], grid.y[i]);
  ASSERT_EQ(cloud.size(), static_cast<long>(expected.size()));
  for (long k = 0; k < cloud.size(); ++k) {
    EXPECT_EQ(cloud.x[k], expected[k].first);
    EXPECT_EQ(cloud.y[k], expected[k].second);
    EXPECT_DOUBLE_EQ(cloud.volume[k], 1e-3 * 1e-3 * 2e-3);
  }
}

// Height from the aspect ratio, or stretched to the height given; picture rows run downwards.
TEST(ImageShape, HeightFromAspectRatioOrGivenAndTopRowOnTop) {
  const std::string path = picture("top", 10, 20, [](int, int y) { return y < 5 ? kBlack : kWhite; });
  const ParticleCloud tall = read_image_shape(path, options(0.01, 1e-3));  // 10 x 20 cells, top quarter
  EXPECT_EQ(tall.size(), 10 * 5);
  for (long k = 0; k < tall.size(); ++k) EXPECT_GT(tall.y[k], 0.005);
  ImageShapeOptions squashed = options(0.01, 1e-3);
  squashed.height = 0.004;
  EXPECT_EQ(read_image_shape(path, squashed).size(), 10 * 1);
}

TEST(ImageShape, RedPixelsAreMaterialThatNeverBreaks) {
  const std::string path = picture("red", 10, 10, [](int x, int) { return x < 2 ? kRed : kBlack; });
  const ParticleCloud cloud = read_image_shape(path, options(0.01, 1e-3));
  ASSERT_EQ(cloud.size(), 100);
  long flagged = 0;
  for (long k = 0; k < cloud.size(); ++k) {
    flagged += cloud.no_fail[k];
    EXPECT_EQ(cloud.no_fail[k] != 0, cloud.x[k] < -0.003) << cloud.x[k];
  }
  EXPECT_EQ(flagged, 20);
}

// Blue pixels are material an attachment may hold (pixels = "blue"); they break like any other.
TEST(ImageShape, BluePixelsAreGripMaterial) {
  const std::string path = picture("blue", 10, 10, [](int x, int) { return x >= 7 ? kBlue : x < 2 ? kRed : kBlack; });
  const ParticleCloud cloud = read_image_shape(path, options(0.01, 1e-3));
  ASSERT_EQ(cloud.size(), 100);
  ASSERT_EQ(cloud.grip.size(), 100u);
  long grip = 0;
  for (long k = 0; k < cloud.size(); ++k) {
    grip += cloud.grip[k];
    EXPECT_EQ(cloud.grip[k] != 0, cloud.x[k] > 0.002) << cloud.x[k];
    EXPECT_FALSE(cloud.grip[k] && cloud.no_fail[k]);
  }
  EXPECT_EQ(grip, 30);
}

TEST(ImageShape, ThresholdDecidesGrey) {
  const std::string path = picture("grey", 4, 4, [](int, int) { return std::array<uint8_t, 4>{100, 100, 100, 255}; });
  ImageShapeOptions light = options(0.004, 1e-3);
  light.threshold = 0.3;  // grey 100/255 = 0.39 is lighter
  EXPECT_THROW(read_image_shape(path, light), InputError);
  light.threshold = 0.5;
  EXPECT_EQ(read_image_shape(path, light).size(), 16);
}

TEST(ImageShape, UnreadableBlankAndOverBudgetPicturesRefused) {
  std::string message;
  try {
    read_image_shape("/nonexistent/specimen.png", options(0.1, 1e-3));
  } catch (const InputError& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("cannot be read as an image"), std::string::npos) << message;
  const std::string blank = picture("blank", 8, 8, [](int, int) { return kWhite; });
  message.clear();
  try {
    read_image_shape(blank, options(0.008, 1e-3));
  } catch (const InputError& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("has no material pixel"), std::string::npos) << message;
  const std::string black = picture("black", 8, 8, [](int, int) { return kBlack; });
  ImageShapeOptions small = options(0.008, 1e-3);
  small.max_particles = 63;
  message.clear();
  try {
    read_image_shape(black, small);
  } catch (const InputError& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("gives 64 particles"), std::string::npos) << message;
}

}  // namespace
}  // namespace periflex
