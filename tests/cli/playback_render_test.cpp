// `periflex run DIR --render` on a checkpoint folder, run as a user types it: the frames of the
// replay equal, byte for byte, the frames a live run drew at the same times (checkpoints and
// frames every 1.37e-4 s, which dt = 4e-7 does not divide, through the start of the crack); a
// folder that cannot be replayed (mixed scenes, no checkpoint, no run record, a scene changed
// since) and flags that shape a simulation are refused with exit 2 naming the file or flag.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "child_run.h"
#include "run_output_files.h"
#include "run_program.h"

namespace periflex {
namespace {

namespace fs = std::filesystem;
using testing::files_with_extension;
using testing::fresh_directory;
using testing::read_text;
using testing::run_child;
using testing::scene;

std::string bytes_of(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The cracking plate with checkpoints every T, the folder it leaves in dir/live/checkpoints.
fs::path live_run(const fs::path& dir, std::vector<std::string> extra = {}) {
  std::vector<std::string> args = {"run", scene("notched_plate.toml"), "--quiet", "--until", "6e-4", "--out",
                                   (dir / "live").string(), "--checkpoint-every", "1.37e-4", "--threads", "1"};
  args.insert(args.end(), extra.begin(), extra.end());
  const auto run = run_child(args, 120);
  EXPECT_EQ(run.exit_code, 0) << run.output;
  return dir / "live" / "checkpoints";
}

#ifdef PERIFLEX_TEST_RENDER
TEST(PlaybackRender, ReplayDrawsTheFramesOfTheLiveRunAtTheSameTimes) {
  const fs::path dir = fresh_directory("playback_golden");
  const fs::path folder = live_run(dir, {"--render", "--frames", (dir / "live_frames").string(), "--frame-every",
                                         "1.37e-4", "--size", "320x200"});
  const auto replayed = run_child({"run", folder.string(), "--render", "--frames", (dir / "replay_frames").string(),
                                   "--size", "320x200", "--out", (dir / "replay").string()},
                                  60);
  ASSERT_EQ(replayed.exit_code, 0) << replayed.output;
  EXPECT_NE(replayed.output.find("5 states from t = 0 to 0.000548 s"), std::string::npos) << replayed.output;

  // frame k of both is the state at t = k T (the start, then the four checkpoints)
  const auto live = files_with_extension(dir / "live_frames", ".png");
  const auto replay = files_with_extension(dir / "replay_frames", ".png");
  ASSERT_EQ(live.size(), 5u);
  ASSERT_EQ(replay.size(), live.size());
  for (size_t k = 0; k < live.size(); ++k) {
    EXPECT_EQ(live[k].filename(), replay[k].filename());
    EXPECT_TRUE(bytes_of(live[k]) == bytes_of(replay[k])) << "frame " << k << " differs: " << replay[k];
  }
  // the frames show a moving, cracking plate, not one picture five times
  EXPECT_NE(bytes_of(replay[0]), bytes_of(replay[4]));
  EXPECT_NE(bytes_of(replay[3]), bytes_of(replay[4]));
  const auto series = testing::read_series(dir / "live" / "series.csv");
  ASSERT_FALSE(series.rows.empty());
  EXPECT_GT(series.rows.back()[series.column("broken_bonds")], 0.0) << "the crack has not started";
}

// A run's VTK series (`--vtk-every N`) replayed as a checkpoint folder is: the frames equal the
// live run's byte for byte where both were taken at the same steps, for the cracking plate (its
// particles and the virtual bodies gripping it) and for the flexible four-bar (rigid crank and
// rocker turning, their poses read from the .vtp files).
TEST(PlaybackRender, VtkSeriesReplayDrawsTheFramesOfTheLiveRun) {
  const struct {
    const char* scene;
    std::vector<std::string> timing;
    size_t frames;
  } cases[] = {
      {"notched_plate.toml", {"--until", "6e-4", "--vtk-every", "250", "--frame-every", "1e-4"}, 7},
      {"flexible_four_bar.toml", {"--until", "0.01", "--dt", "1e-6", "--vtk-every", "2000", "--frame-every", "2e-3"}, 6},
  };
  for (const auto& c : cases) {
    const fs::path dir = fresh_directory(std::string("vtk_replay_") + c.scene);
    std::vector<std::string> args = {"run", scene(c.scene), "--quiet", "--out", (dir / "live").string(), "--threads",
                                     "1", "--frames", (dir / "live_frames").string(), "--size", "320x200"};
    args.insert(args.end(), c.timing.begin(), c.timing.end());
    const auto live = run_child(args, 120);
    ASSERT_EQ(live.exit_code, 0) << live.output;
    const auto replayed = run_child({"run", (dir / "live" / "vtk").string(), "--frames",
                                     (dir / "replay_frames").string(), "--size", "320x200", "--out",
                                     (dir / "replay").string()},
                                    60);
    ASSERT_EQ(replayed.exit_code, 0) << replayed.output;
    const auto live_frames = files_with_extension(dir / "live_frames", ".png");
    const auto replay_frames = files_with_extension(dir / "replay_frames", ".png");
    ASSERT_EQ(live_frames.size(), c.frames) << c.scene;
    ASSERT_EQ(replay_frames.size(), c.frames) << c.scene;
    for (size_t k = 0; k < c.frames; ++k)
      EXPECT_TRUE(bytes_of(live_frames[k]) == bytes_of(replay_frames[k])) << c.scene << ": frame " << k << " differs";
    // the states move: not one picture over and over
    EXPECT_NE(bytes_of(replay_frames.front()), bytes_of(replay_frames.back())) << c.scene;
  }
}

TEST(PlaybackRender, ScreenshotIsTheStateNearestTheTimeAsked) {
  const fs::path dir = fresh_directory("playback_shot");
  const fs::path folder = live_run(dir, {"--snapshot-at", "2.74e-4", "--screenshot", (dir / "live.png").string(),
                                         "--size", "320x200"});
  const auto replayed = run_child({"run", folder.string(), "--snapshot-at", "2.8e-4", "--screenshot",
                                   (dir / "replay.png").string(), "--size", "320x200", "--out",
                                   (dir / "replay").string()},
                                  60);
  ASSERT_EQ(replayed.exit_code, 0) << replayed.output;
  ASSERT_TRUE(fs::exists(dir / "live.png"));
  EXPECT_TRUE(bytes_of(dir / "live.png") == bytes_of(dir / "replay.png"));
}
#endif

// A VTK series is replayed in the scene its run's summary.json names: without it, refused (exit
// 2, naming summary.json); --plot has no series rows to draw there, refused naming the flag.
TEST(PlaybackRender, VtkSeriesWithoutItsRunOrWithPlotIsRefused) {
  const fs::path dir = fresh_directory("vtk_refused");
  const auto run = run_child({"run", scene("pendulum.toml"), "--quiet", "--until", "0.05", "--out",
                              (dir / "live").string(), "--vtk-every", "20"},
                             60);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  auto r = run_child({"run", (dir / "live" / "vtk").string(), "--frames", (dir / "f").string(), "--plot", "kinetic",
                      "--out", (dir / "r").string()},
                     60);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--plot"), std::string::npos) << r.output;
  fs::copy(dir / "live" / "vtk", dir / "alone");
  r = run_child({"run", (dir / "alone").string(), "--frames", (dir / "f").string(), "--out", (dir / "r").string()},
                60);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("summary.json"), std::string::npos) << r.output;
}

TEST(PlaybackRender, FoldersThatCannotBeReplayedAreRefusedNamingTheFile) {
  const fs::path dir = fresh_directory("playback_refused");
  const fs::path folder = live_run(dir);
  auto replay = [&](const fs::path& from, std::vector<std::string> extra = {}) {
    std::vector<std::string> args = {"run", from.string(), "--render", "--out", (dir / "replay").string()};
    args.insert(args.end(), extra.begin(), extra.end());
    return run_child(args, 60);
  };

  // a flag that shapes a simulation
  for (const char* flag : {"--until", "--dt", "--checkpoint-every", "--frame-every"}) {
    const auto r = replay(folder, {flag, "1e-4"});
    EXPECT_EQ(r.exit_code, 2) << flag << ": " << r.output;
    EXPECT_NE(r.output.find(std::string("'") + flag + "'"), std::string::npos) << r.output;
  }

  // a checkpoint of another scene among the plate's
  const auto other = run_child({"run", scene("pendulum.toml"), "--quiet", "--until", "0.05", "--out",
                                (dir / "pendulum").string(), "--checkpoint-every", "0.02"},
                               60);
  ASSERT_EQ(other.exit_code, 0) << other.output;
  const fs::path mixed = dir / "mixed";
  fs::copy(folder, mixed);
  const fs::path stranger = files_with_extension(dir / "pendulum" / "checkpoints", ".pfstate").front();
  fs::copy_file(stranger, mixed / "checkpoint_000009_t0.5.pfstate");
  auto r = replay(mixed);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("checkpoint_000009_t0.5.pfstate' belongs to another scene"), std::string::npos) << r.output;

  // no checkpoint, only the record
  const fs::path empty = dir / "empty";
  fs::create_directories(empty);
  fs::copy_file(folder / "run.json", empty / "run.json");
  r = replay(empty);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("holds no checkpoint"), std::string::npos) << r.output;

  // checkpoints without the record of their scene
  const fs::path bare = dir / "bare";
  fs::copy(folder, bare);
  fs::remove(bare / "run.json");
  r = replay(bare);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("run.json' is missing"), std::string::npos) << r.output;

#ifdef PERIFLEX_TEST_RENDER
  // a damaged checkpoint: refused when its turn comes (while drawing), naming it; a build
  // without the off-screen renderer refuses --render before any checkpoint is read
  const fs::path damaged = dir / "damaged";
  fs::copy(folder, damaged);
  const fs::path victim = files_with_extension(damaged, ".pfstate")[1];
  std::string bytes = bytes_of(victim);
  bytes[bytes.size() / 2] ^= 0x5a;
  std::ofstream(victim, std::ios::binary) << bytes;
  r = replay(damaged);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(victim.filename().string() + "': damaged"), std::string::npos) << r.output;
#endif
}

TEST(PlaybackRender, SceneChangedSinceTheRunIsRefused) {
  const fs::path dir = fresh_directory("playback_changed");
  fs::copy_file(scene("pendulum.toml"), dir / "pendulum.toml");
  const auto run = run_child({"run", (dir / "pendulum.toml").string(), "--quiet", "--until", "0.05", "--out",
                              (dir / "live").string(), "--checkpoint-every", "0.02", "--set", "solver.dt=1e-3"},
                             60);
  ASSERT_EQ(run.exit_code, 0) << run.output;
#ifdef PERIFLEX_TEST_RENDER
  // replayed on its own: the record brings the scene and its --set
  auto r = run_child({"run", (dir / "live" / "checkpoints").string(), "--render", "--size", "64x64", "--out",
                      (dir / "replay").string()},
                     60);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(testing::count_files(dir / "replay" / "frames", ".png"), 3);
#endif
  std::ofstream(dir / "pendulum.toml", std::ios::app) << "\n# edited\n";
  const auto changed = run_child({"run", (dir / "live" / "checkpoints").string(), "--render", "--out",
                                  (dir / "replay").string()},
                                 60);
  EXPECT_EQ(changed.exit_code, 2) << changed.output;
  EXPECT_NE(changed.output.find("has changed since the checkpoints"), std::string::npos) << changed.output;
}

}  // namespace
}  // namespace periflex
