// Off-screen recording through the program: exact frame counts at exact times, screenshots,
// and a clear refusal when a movie cannot be made.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>

#include "../cli/run_program.h"
#include "io/image.h"
#include "support/json_text.h"

namespace periflex::testing {
namespace {

namespace fs = std::filesystem;

TEST(Recording, FrameCountIsFloorOfEndOverIntervalPlusOneWithoutGaps) {
  const auto out = fresh_directory("frames");
  // end 0.3 s, a frame every 0.07 s: t = 0, 0.07, ..., 0.28 -> floor(0.3 / 0.07) + 1 = 5 frames
  const auto r = run_periflex("run " + scene("pendulum.toml") + " --until 0.3 --render --frame-every 0.07 --size 96x64" +
                              " --frames " + (out / "frames").string() + " --quiet --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  long count = 0;
  for (const auto& entry : fs::directory_iterator(out / "frames")) count += entry.path().extension() == ".png";
  EXPECT_EQ(count, static_cast<long>(std::floor(0.3 / 0.07)) + 1);
  for (long i = 0; i < count; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06ld.png", i);
    const RgbaImage frame = read_png((out / "frames" / name).string());
    EXPECT_EQ(frame.width, 96);
    EXPECT_EQ(frame.height, 64);
  }
  const auto summary = testing::parse_json(read_text(out / "summary.json"));
  EXPECT_EQ(summary["frames_written"].get<long>(), count);
}

TEST(Recording, ScreenshotAtATimeShowsTheSceneNotABlankPicture) {
  const auto out = fresh_directory("screenshot");
  const auto shot = out / "shot.png";
  const auto r = run_periflex("run " + scene("slider_crank.toml") + " --until 0.2 --snapshot-at 0.1 --screenshot " +
                              shot.string() + " --size 160x120 --quiet --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const RgbaImage image = read_png(shot.string());
  ASSERT_EQ(image.width, 160);
  // the bodies are drawn over the background: more than a handful of distinct colours
  std::set<uint32_t> colours;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const uint8_t* p = image.at(x, y);
      colours.insert(p[0] << 16 | p[1] << 8 | p[2]);
    }
  EXPECT_GT(colours.size(), 8u);
}

TEST(Recording, SamplesOptionAcceptsOneToSixteen) {
  const auto out = fresh_directory("samples");
  for (const char* bad : {"0", "17", "many"}) {
    const auto r = run_periflex("run " + scene("pendulum.toml") + " --until 0.1 --render --samples " + bad +
                                " --quiet --out " + out.string());
    EXPECT_EQ(r.exit_code, 2) << "--samples " << bad << ": " << r.output;
  }
  const auto r = run_periflex("run " + scene("pendulum.toml") + " --until 0.1 --render --frame-every 0.05 --samples 1" +
                              " --size 96x64 --frames " + (out / "frames").string() + " --quiet --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(out / "frames" / "frame_000002.png"));
  EXPECT_FALSE(fs::exists(out / "frames" / "frame_000003.png"));
}

TEST(Recording, MovieWithoutFfmpegIsRefusedBeforeSimulating) {
  const auto out = fresh_directory("no_ffmpeg");
  // a PATH that holds no ffmpeg
  const std::string command = "env PATH=/nonexistent " + std::string(PERIFLEX_BINARY) + " run " +
                              scene("pendulum.toml") + " --render --movie " + (out / "m2.mp4").string() +
                              " --quiet --out " + (out / "run").string() + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  char buffer[512];
  while (fgets(buffer, sizeof buffer, pipe)) output += buffer;
  const int status = pclose(pipe);
  EXPECT_EQ(WEXITSTATUS(status), 2) << output;
  EXPECT_NE(output.find("ffmpeg"), std::string::npos) << output;
  EXPECT_FALSE(fs::exists(out / "m2.mp4"));
}

}  // namespace
}  // namespace periflex::testing
