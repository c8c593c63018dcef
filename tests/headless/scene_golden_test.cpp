// Screenshot tests: every shipped scene, stepped to a fixed time and drawn off-screen at 320x240,
// must match its golden image in tests/golden/. A pixel fails when a channel differs by more than
// 5/255 (llvmpipe builds differ by a level or two at anti-aliased edges); a picture fails above
// 0.1% failing pixels. On failure the actual and a difference image are written next to the test
// output. Regenerate after an intended change with scripts/update-goldens.sh.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "headless/offscreen_renderer.h"
#include "io/image.h"
#include "render/view.h"
#include "scene/scene_loader.h"
#include "solve/simulation.h"

namespace periflex {
namespace {

namespace fs = std::filesystem;

constexpr int kGoldenWidth = 320, kGoldenHeight = 240;
constexpr int kChannelTolerance = 5;
constexpr double kMaxFailingFraction = 0.001;

std::vector<std::string> shipped_scenes() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(fs::path(PERIFLEX_SOURCE_ROOT) / "scenes"))
    if (entry.path().extension() == ".toml") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

// The scene after min(half its run, 1000 steps), on one thread so the picture is reproducible.
Snapshot snapshot_of(const std::string& name) {
  omp_set_num_threads(1);
  const SceneDef scene = load_scene(std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/" + name + ".toml");
  Simulation sim(scene);
  sim.initialize();
  sim.advance_to(std::min(0.5 * scene.solver.end_time, 1000.0 * scene.solver.dt));
  Snapshot snapshot;
  sim.fill_snapshot(snapshot);
  return snapshot;
}

fs::path golden_path(const std::string& name) {
  return fs::path(PERIFLEX_SOURCE_ROOT) / "tests" / "golden" / (name + ".png");
}

bool updating_goldens() {
  const char* flag = std::getenv("PERIFLEX_UPDATE_GOLDENS");
  return flag && std::string(flag) == "1";
}

// Compares with the golden; on failure writes <name>_actual.png and <name>_diff.png here.
ImageDiff compare_with_golden(const std::string& name, const RgbaImage& actual) {
  const RgbaImage expected = read_png(golden_path(name).string());
  RgbaImage diff;
  const ImageDiff result = compare_images(expected, actual, kChannelTolerance, &diff);
  if (!result.same_size || result.failing_fraction() > kMaxFailingFraction) {
    const fs::path out = fs::current_path() / "golden_out";
    fs::create_directories(out);
    write_png((out / (name + "_actual.png")).string(), actual);
    if (result.same_size) write_png((out / (name + "_diff.png")).string(), diff);
    std::printf("golden mismatch for %s: actual and difference images in %s\n", name.c_str(), out.c_str());
  }
  return result;
}

class SceneGolden : public ::testing::TestWithParam<std::string> {};

TEST_P(SceneGolden, MatchesGoldenImage) {
  const std::string name = GetParam();
  const RgbaImage actual = render_snapshot_image(snapshot_of(name), RenderSettings{}, kGoldenWidth, kGoldenHeight);
  if (updating_goldens()) {
    write_png(golden_path(name).string(), actual);
    GTEST_SKIP() << "golden written: " << golden_path(name);
  }
  ASSERT_TRUE(fs::exists(golden_path(name))) << "no golden for " << name << "; run scripts/update-goldens.sh";
  const ImageDiff result = compare_with_golden(name, actual);
  ASSERT_TRUE(result.same_size);
  EXPECT_LE(result.failing_fraction(), kMaxFailingFraction)
      << result.failing_pixels << " of " << result.total_pixels << " pixels differ by more than "
      << kChannelTolerance << "/255";
}

INSTANTIATE_TEST_SUITE_P(ShippedScenes, SceneGolden, ::testing::ValuesIn(shipped_scenes()),
                         [](const ::testing::TestParamInfo<std::string>& scene) { return scene.param; });

// The notched plate with its deformation magnified 100 times (render/deformation.h), the bend
// and the opening notch drawn as the window and `run --deform 100` draw them. Without the overlay
// (the other goldens hold it), so that only the particles' places can make the difference.
RenderSettings magnified_settings(float deform = 100.0f) {
  RenderSettings settings;
  settings.deform = deform;
  settings.show_overlay = false;
  return settings;
}

TEST(MagnifiedGolden, NotchedPlateAtHundredfold) {
  const std::string name = "notched_plate_deform100";
  const RgbaImage actual = render_snapshot_image(snapshot_of("notched_plate"), magnified_settings(), kGoldenWidth, kGoldenHeight);
  if (updating_goldens()) {
    write_png(golden_path(name).string(), actual);
    GTEST_SKIP() << "golden written: " << golden_path(name);
  }
  ASSERT_TRUE(fs::exists(golden_path(name))) << "no golden for " << name << "; run scripts/update-goldens.sh";
  const ImageDiff result = compare_with_golden(name, actual);
  ASSERT_TRUE(result.same_size);
  EXPECT_LE(result.failing_fraction(), kMaxFailingFraction)
      << result.failing_pixels << " of " << result.total_pixels << " pixels differ by more than "
      << kChannelTolerance << "/255";
}

// The comparison must catch real changes: each of these alterations of the notched plate's
// picture has to fail it.
class GoldenCatches : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { plate_ = new Snapshot(snapshot_of("notched_plate")); }
  static void TearDownTestSuite() { delete plate_; }
  static double failing_fraction(const RgbaImage& altered) {
    const RgbaImage expected = read_png(golden_path("notched_plate").string());
    return compare_images(expected, altered, kChannelTolerance).failing_fraction();
  }
  static Snapshot* plate_;
};
Snapshot* GoldenCatches::plate_ = nullptr;

TEST_F(GoldenCatches, AChangedColourMap) {
  if (updating_goldens()) GTEST_SKIP();
  RenderSettings settings;
  settings.colormap = "viridis";
  EXPECT_GT(failing_fraction(render_snapshot_image(*plate_, settings, kGoldenWidth, kGoldenHeight)), kMaxFailingFraction);
}

TEST_F(GoldenCatches, AMissingParticleSet) {
  if (updating_goldens()) GTEST_SKIP();
  Snapshot without = *plate_;
  without.px.clear();
  without.py.clear();
  without.damage.clear();
  without.displacement.clear();
  without.speed.clear();
  without.strain.clear();
  const Camera camera = fit_camera(*plate_, kGoldenWidth, kGoldenHeight);
  EXPECT_GT(failing_fraction(render_snapshot_image(without, RenderSettings{}, kGoldenWidth, kGoldenHeight, &camera)),
            kMaxFailingFraction);
}

TEST_F(GoldenCatches, AMissingMagnification) {
  if (updating_goldens()) GTEST_SKIP();
  // the plate at true scale against the magnified golden
  const RgbaImage expected = read_png(golden_path("notched_plate_deform100").string());
  const RgbaImage true_scale = render_snapshot_image(*plate_, magnified_settings(1.0f), kGoldenWidth, kGoldenHeight);
  EXPECT_GT(compare_images(expected, true_scale, kChannelTolerance).failing_fraction(), kMaxFailingFraction);
}

TEST_F(GoldenCatches, AWrongCamera) {
  if (updating_goldens()) GTEST_SKIP();
  Camera camera = fit_camera(*plate_, kGoldenWidth, kGoldenHeight);
  camera.view_height *= 1.2;
  EXPECT_GT(failing_fraction(render_snapshot_image(*plate_, RenderSettings{}, kGoldenWidth, kGoldenHeight, &camera)),
            kMaxFailingFraction);
}

}  // namespace
}  // namespace periflex
