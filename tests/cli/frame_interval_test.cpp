// The frame interval of `periflex run` when the user gives none: the largest whole number of
// steps not above end time / 100, at least one step. It is never refused (only a --frame-every
// the user typed can be), and it never cuts a step short to land on a frame.
#include <gtest/gtest.h>

#include <cmath>

#include "child_run.h"
#include "run_output_files.h"
#include "run_program.h"

namespace periflex::testing {
namespace {

namespace fs = std::filesystem;

constexpr double kFrameRunSeconds = 180.0;

// The frames the default interval gives: k * interval for k = 0, 1, ... up to the end, the
// interval being max(1, floor(end / 100 / dt)) steps.
[[maybe_unused]] long default_frames(double end, double dt) {
  const double interval = std::max(1.0, std::floor(end / 100.0 / dt + 1e-9)) * dt;
  return static_cast<long>(std::floor(end / interval + 1e-9)) + 1;
}

#ifdef PERIFLEX_TEST_RENDER

// The two commands of the report: a hundredth of the run is shorter than a step there.
TEST(FrameInterval, DefaultOnARunShorterThanAHundredStepsIsOneStepNotARefusal) {
  if (!have_program("ffmpeg") || !have_program("ffprobe")) GTEST_SKIP() << "needs ffmpeg and ffprobe";
  struct Case {
    const char* scene;
    const char* until;
    double end, dt;  // the scene's dt
  };
  for (const Case& c : {Case{"pendulum.toml", "0.01", 0.01, 1e-3}, Case{"notched_plate.toml", "1e-5", 1e-5, 4e-7}}) {
    const auto dir = fresh_directory(std::string("default_frames_") + c.scene);
    const fs::path movie = dir / "m.mp4";
    const auto r = run_child({"run", scene(c.scene), "--until", c.until, "--movie", movie.string(), "--size", "96x64",
                              "--quiet", "--out", (dir / "run").string()},
                             kFrameRunSeconds);
    ASSERT_EQ(r.exit_code, 0) << c.scene << ": " << r.output;
    const long expected = default_frames(c.end, c.dt);
    EXPECT_EQ(expected, static_cast<long>(std::floor(c.end / c.dt + 1e-9)) + 1) << "one frame per step";
    EXPECT_EQ(movie_frames(movie), expected) << c.scene;
    EXPECT_EQ(read_summary(dir / "run" / "summary.json")["frames_written"].get<long>(), expected) << c.scene;
  }
  // an interval the user typed is still checked, and the message names it
  const auto dir = fresh_directory("typed_frame_every");
  const auto r = run_child({"run", scene("pendulum.toml"), "--until", "0.01", "--render", "--frame-every", "3e-4",
                            "--quiet", "--out", dir.string()},
                           kFrameRunSeconds);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--frame-every"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("0.0003"), std::string::npos) << r.output;
}

// dt = 1.5 ms does not divide end / 100 = 5 ms: frames every 3 steps (4.5 ms), and the run takes
// the steps it takes without frames (a frame every 5 ms would cut steps short to land on it).
// Rows every 10 steps (15 ms), so that they cut none either; the end (0.5 s, 333.3 steps) does.
TEST(FrameInterval, DefaultIsWholeStepsSoFramesCutNoStep) {
  const auto dir = fresh_directory("default_frames_whole_steps");
  const std::vector<std::string> common = {"run", scene("pendulum.toml"), "--until", "0.5", "--dt", "1.5e-3",
                                           "--set", "solver.output_interval=0.015", "--quiet"};
  std::vector<std::string> plain = common, drawn = common;
  plain.insert(plain.end(), {"--out", (dir / "plain").string()});
  drawn.insert(drawn.end(), {"--render", "--size", "64x48", "--frames", (dir / "frames").string(), "--out",
                             (dir / "drawn").string()});
  const auto a = run_child(plain, kFrameRunSeconds);
  ASSERT_EQ(a.exit_code, 0) << a.output;
  const auto b = run_child(drawn, kFrameRunSeconds);
  ASSERT_EQ(b.exit_code, 0) << b.output;
  const auto plain_summary = read_summary(dir / "plain" / "summary.json");
  const auto drawn_summary = read_summary(dir / "drawn" / "summary.json");
  // the whole steps and the one cut short at the end
  EXPECT_EQ(plain_summary["steps"].get<long>(), static_cast<long>(std::ceil(0.5 / 1.5e-3)));
  EXPECT_EQ(drawn_summary["steps"].get<long>(), plain_summary["steps"].get<long>());
  EXPECT_EQ(drawn_summary["frames_written"].get<long>(), default_frames(0.5, 1.5e-3));
  long pngs = 0;
  for (const auto& entry : fs::directory_iterator(dir / "frames")) pngs += entry.path().extension() == ".png";
  EXPECT_EQ(pngs, default_frames(0.5, 1.5e-3));
}

#endif

}  // namespace
}  // namespace periflex::testing
