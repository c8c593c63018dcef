// The recording pipeline (headless/recorder.h): frames keep their order and numbers across the
// draw and encoder threads, screenshots stay out of the sequence, the camera follows particles
// that leave the view, and failures in the threads reach the caller.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>

#include "headless/recorder.h"
#include "io/frame_writer.h"
#include "io/image.h"

namespace periflex::testing {
namespace {

namespace fs = std::filesystem;

constexpr int kFrameWidth = 64, kFrameHeight = 48;

// A square plate of side x side particles over [x0, x0 + 1] x [0, 1], every particle with the
// same damage, so that the frame's centre shows `damage` through the colour map.
Snapshot plate(double damage, double x0 = 0.0, int side = 24) {
  const double dx = 1.0 / side;
  auto geometry = std::make_shared<SceneGeometry>();
  geometry->scene_name = "recorder test plate";
  geometry->bodies.push_back({"ground", true, false, {}});
  SceneGeometry::FlexBody flex;
  flex.name = "plate";
  flex.particle_count = side * side;
  flex.grid_spacing = dx;
  geometry->flex_bodies.push_back(flex);
  geometry->bounds_min = Vec2(0.0, 0.0);
  geometry->bounds_max = Vec2(1.0, 1.0);
  Snapshot s;
  s.bodies.resize(1);
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i) {
      const float x = static_cast<float>((i + 0.5) * dx), y = static_cast<float>((j + 0.5) * dx);
      geometry->reference_x.push_back(x);
      geometry->reference_y.push_back(y);
      s.px.push_back(static_cast<float>(x + x0));
      s.py.push_back(y);
      s.damage.push_back(static_cast<float>(damage));
      s.displacement.push_back(0.0f);
      s.speed.push_back(0.0f);
      s.strain.push_back(0.0f);
    }
  geometry->particle_attached.assign(s.px.size(), 0);
  s.geometry = geometry;
  return s;
}

// Small frames, damage on a fixed 0..1 range through the grey map, no overlay.
RecorderOptions small_options() {
  RecorderOptions options;
  options.width = kFrameWidth;
  options.height = kFrameHeight;
  options.settings.colormap = "grey";
  options.settings.auto_range = false;
  options.settings.range_min = 0.0f;
  options.settings.range_max = 1.0f;
  options.settings.show_overlay = false;
  return options;
}

fs::path fresh_directory(const std::string& name) {
  const fs::path dir = fs::current_path() / ("recorder_test_out_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

int centre_grey(const RgbaImage& image) { return image.at(image.width / 2, image.height / 2)[0]; }

std::string frame_name(long i) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%06ld.png", i);
  return name;
}

TEST(Recorder, FramesAreNumberedWithoutGapsInSubmissionOrder) {
  const fs::path dir = fresh_directory("order");
  RecorderOptions options = small_options();
  options.frames_dir = (dir / "frames").string();
  Recorder recorder(options);
  // more frames than the pipeline has slots, each brighter than the one before
  constexpr int kFrames = 20;
  for (int k = 0; k < kFrames; ++k) recorder.submit(plate(static_cast<double>(k) / (kFrames - 1)));
  const RecorderStats stats = recorder.finish();
  EXPECT_EQ(stats.frames, kFrames);
  EXPECT_EQ(stats.screenshots, 0);
  // each thread accounts for its own work, and there was no movie
  EXPECT_GT(stats.draw_seconds, 0.0);
  EXPECT_GT(stats.png_seconds, 0.0);
  EXPECT_EQ(stats.movie_seconds, 0.0);
  EXPECT_GT(stats.wall_seconds, 0.0);

  // exactly the numbered files, nothing left under a temporary name
  long files = 0;
  for (const auto& entry : fs::directory_iterator(dir / "frames")) {
    ++files;
    EXPECT_EQ(entry.path().extension(), ".png") << entry.path();
  }
  EXPECT_EQ(files, kFrames);
  int previous = -1;
  for (int k = 0; k < kFrames; ++k) {
    const RgbaImage frame = read_png((dir / "frames" / frame_name(k)).string());
    ASSERT_EQ(frame.width, kFrameWidth);
    ASSERT_EQ(frame.height, kFrameHeight);
    EXPECT_GT(centre_grey(frame), previous) << "frame " << k << " is out of order";
    previous = centre_grey(frame);
  }
  // the grey map spans most of 0..255 over the damage range
  EXPECT_GT(previous - centre_grey(read_png((dir / "frames" / frame_name(0)).string())), 150);
}

TEST(Recorder, ScreenshotIsWrittenApartFromTheSequence) {
  const fs::path dir = fresh_directory("screenshot");
  RecorderOptions options = small_options();
  options.frames_dir = (dir / "frames").string();
  options.screenshot_path = (dir / "shot.png").string();
  Recorder recorder(options);
  recorder.submit(plate(0.2));
  recorder.submit(plate(0.9), true);
  recorder.submit(plate(0.5));
  const RecorderStats stats = recorder.finish();
  EXPECT_EQ(stats.frames, 2);
  EXPECT_EQ(stats.screenshots, 1);
  // the sequence has no hole where the screenshot was taken
  const int first = centre_grey(read_png((dir / "frames" / frame_name(0)).string()));
  const int second = centre_grey(read_png((dir / "frames" / frame_name(1)).string()));
  EXPECT_FALSE(fs::exists(dir / "frames" / frame_name(2)));
  const int shot = centre_grey(read_png((dir / "shot.png").string()));
  // damage 0.2, 0.5 and 0.9: ever brighter through the grey map, and well apart
  EXPECT_GT(second, first + 30);
  EXPECT_GT(shot, second + 30);
}

TEST(Recorder, ScreenshotWithoutAPathIsRefused) {
  RecorderOptions options = small_options();
  Recorder recorder(options);
  EXPECT_THROW(recorder.submit(plate(0.5), true), std::invalid_argument);
  EXPECT_EQ(recorder.finish().screenshots, 0);
}

TEST(Recorder, CameraWidensWhenParticlesLeaveTheView) {
  const fs::path dir = fresh_directory("camera");
  RecorderOptions options = small_options();
  options.frames_dir = (dir / "frames").string();
  Recorder recorder(options);
  recorder.submit(plate(1.0));
  recorder.submit(plate(1.0, 5.0));  // the whole plate moved far to the right
  recorder.finish();
  // the second frame still shows the white plate (a camera left in place would show none of it)
  const RgbaImage moved = read_png((dir / "frames" / frame_name(1)).string());
  long white = 0;
  for (int y = 0; y < moved.height; ++y)
    for (int x = 0; x < moved.width; ++x) white += moved.at(x, y)[0] > 200;
  EXPECT_GT(white, kFrameWidth * kFrameHeight / 10);
}

// White pixels of frame i of a recording of the plate that moves far to the right after frame 0.
long white_after_moving(const std::string& name, RecorderOptions options) {
  const fs::path dir = fresh_directory(name);
  options.frames_dir = (dir / "frames").string();
  Recorder recorder(options);
  recorder.submit(plate(1.0));
  recorder.submit(plate(1.0, 5.0));
  recorder.finish();
  const RgbaImage moved = read_png((dir / "frames" / frame_name(1)).string());
  long white = 0;
  for (int y = 0; y < moved.height; ++y)
    for (int x = 0; x < moved.width; ++x) white += moved.at(x, y)[0] > 200;
  return white;
}

// --camera fit: the view of the first frame is kept, so the moved plate is out of the picture.
TEST(Recorder, FittedCameraStaysWhereTheFirstFrameWas) {
  RecorderOptions options = small_options();
  options.camera_mode = RecorderOptions::CameraMode::kFit;
  EXPECT_EQ(white_after_moving("camera_fit", options), 0);
}

// --camera X,Y,HEIGHT: a view set by the user, here centred on where the plate moves to.
TEST(Recorder, FixedCameraShowsTheViewTheUserSet) {
  RecorderOptions options = small_options();
  options.camera_mode = RecorderOptions::CameraMode::kFixed;
  options.camera.center = Vec2(5.5, 0.5);
  options.camera.view_height = 3.0;
  EXPECT_GT(white_after_moving("camera_fixed", options), kFrameWidth * kFrameHeight / 20);
}

// The frames folder replaced by a file once the recorder has started: the file thread cannot write.
std::unique_ptr<Recorder> recorder_with_broken_folder(const fs::path& dir) {
  RecorderOptions options = small_options();
  options.frames_dir = (dir / "frames").string();
  auto recorder = std::make_unique<Recorder>(options);
  fs::remove_all(dir / "frames");
  std::ofstream(dir / "frames") << "not a folder";
  return recorder;
}

TEST(Recorder, EncoderFailureIsThrownByFinish) {
  const fs::path dir = fresh_directory("broken_finish");
  auto recorder = recorder_with_broken_folder(dir);
  recorder->submit(plate(0.5));
  try {
    recorder->finish();
    ADD_FAILURE() << "finish() did not report the failed write";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(frame_name(0)), std::string::npos) << e.what();
  }
}

TEST(Recorder, EncoderFailureIsThrownByALaterSubmit) {
  const fs::path dir = fresh_directory("broken_submit");
  auto recorder = recorder_with_broken_folder(dir);
  // the slots are few: once they are full, submit waits for the pipeline and finds the failure
  bool thrown = false;
  for (int k = 0; k < 50 && !thrown; ++k) {
    try {
      recorder->submit(plate(0.5));
    } catch (const std::runtime_error&) {
      thrown = true;
    }
  }
  EXPECT_TRUE(thrown);
  EXPECT_THROW(recorder->finish(), std::runtime_error);
}

TEST(Recorder, MissingFramesFolderParentIsReportedAtConstruction) {
  const fs::path dir = fresh_directory("bad_parent");
  std::ofstream(dir / "file") << "x";
  RecorderOptions options = small_options();
  options.frames_dir = (dir / "file" / "frames").string();
  EXPECT_THROW(Recorder recorder(options), std::runtime_error);
}

TEST(Recorder, MultisamplingIsUsedWhenAsked) {
  RecorderOptions options = small_options();
  options.samples = 4;
  Recorder four(options);
  four.submit(plate(0.3));
  EXPECT_EQ(four.finish().samples, 4);
  options.samples = 1;
  Recorder one(options);
  EXPECT_EQ(one.finish().samples, 1);
}

TEST(Recorder, MovieAndSequenceTogetherHoldEveryFrame) {
  if (find_ffmpeg().empty()) GTEST_SKIP() << "ffmpeg is not on PATH";
  const std::string ffprobe = (fs::path(find_ffmpeg()).parent_path() / "ffprobe").string();
  const fs::path dir = fresh_directory("movie");
  RecorderOptions options = small_options();
  options.frames_dir = (dir / "frames").string();
  options.movie_path = (dir / "movie.mp4").string();
  Recorder recorder(options);
  constexpr int kFrames = 9;
  for (int k = 0; k < kFrames; ++k) recorder.submit(plate(k / 8.0));
  const RecorderStats stats = recorder.finish();
  EXPECT_EQ(stats.frames, kFrames);
  EXPECT_TRUE(fs::exists(dir / "frames" / frame_name(kFrames - 1)));
  EXPECT_FALSE(fs::exists(dir / "frames" / frame_name(kFrames)));
  ASSERT_TRUE(fs::exists(dir / "movie.mp4"));
  EXPECT_GT(fs::file_size(dir / "movie.mp4"), 0u);
  if (!fs::exists(ffprobe)) return;
  // the movie has exactly the frames submitted
  const std::string command = ffprobe + " -v error -count_frames -select_streams v:0 -show_entries "
                              "stream=nb_read_frames -of csv=p=0 " + (dir / "movie.mp4").string();
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  char line[64] = {};
  const bool got = std::fgets(line, sizeof line, pipe) != nullptr;
  pclose(pipe);
  ASSERT_TRUE(got);
  EXPECT_EQ(std::atoi(line), kFrames);
}

}  // namespace
}  // namespace periflex::testing
