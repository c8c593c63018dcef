// `periflex run` as typed: runs end at their end time whatever the step, rows and frames land on
// their nominal times, Ctrl-C and kill stop a run cleanly, and summary.json tells the truth on
// every way out.
#include <gtest/gtest.h>

#include <cmath>
#include <csignal>
#include <thread>

#include "child_run.h"
#include "run_output_files.h"
#include "run_program.h"
#include "study/elliptic.h"
#include "support/text_match.h"

namespace periflex::testing {
namespace {

std::string data_scene(const std::string& file) { return std::string(PERIFLEX_TEST_DATA) + "/scenes/" + file; }

// Generous wall-time limits: a hang fails the test instead of holding up the suite.
constexpr double kRunSeconds = 120.0;

// A run with a step that makes t / dt pass 1000 ended at its end time only by luck before:
// the loop and the solver disagreed on "reached", and the program spun at 100% CPU for ever.
TEST(RunCommand, RunsEndAtTheEndTimeWhateverTheStep) {
  struct Case {
    const char* scene;
    const char* dt;
    double end;
  };
  for (const Case& c : {Case{"four_bar.toml", "2e-4", 3.0}, Case{"double_pendulum.toml", "1e-4", 10.0}}) {
    const auto out = fresh_directory(std::string("end_") + c.scene);
    const auto r = run_child({"run", scene(c.scene), "--set", std::string("solver.dt=") + c.dt, "--out", out.string(),
                              "--quiet"},
                             kRunSeconds);
    ASSERT_FALSE(r.timed_out) << c.scene << " did not end: " << r.output;
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto summary = read_summary(out / "summary.json");
    EXPECT_EQ(summary["status"], "ok");
    EXPECT_DOUBLE_EQ(summary["simulated_time"].get<double>(), c.end);
    const Series s = read_series(out / "series.csv");
    ASSERT_FALSE(s.rows.empty());
    EXPECT_DOUBLE_EQ(s.rows.back()[0], c.end);
  }
}

// Over two million steps (t / dt = 2e6), every row is stamped with k * interval exactly and
// holds the state at that time: the fall y = -g t^2 / 2, which Verlet reproduces exactly.
TEST(RunCommand, LongRunRowsLandOnTheirNominalTimes) {
  const auto out = fresh_directory("long_run");
  const auto r = run_child({"run", data_scene("run/falling_body.toml"), "--out", out.string(), "--quiet"}, kRunSeconds);
  ASSERT_FALSE(r.timed_out) << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Series s = read_series(out / "series.csv");
  ASSERT_EQ(s.rows.size(), 21u);  // t = 0, 0.1, ..., 2.0
  const int y = s.column("probe.block.y");
  for (size_t k = 0; k < s.rows.size(); ++k) {
    const double t = s.rows[k][0];
    // the time written is the nominal one (12 significant digits are written)
    EXPECT_NEAR(t, 0.1 * static_cast<double>(k), 1e-12) << "row " << k;
    // and the state is the state at that time: round-off of 2e6 steps only
    EXPECT_NEAR(s.rows[k][y], -0.5 * 9.81 * t * t, 1e-8) << "row " << k << " at t = " << t;
  }
}

// A step that does not divide the output interval: rows still fall on k * 0.5 s, and their
// values are the pendulum's at those times (against the closed form), not a step later.
TEST(RunCommand, RowsWithAStepThatDoesNotDivideTheIntervalHoldTheStateAtTheirTime) {
  const auto out = fresh_directory("nominal_rows");
  const auto r = run_child({"run", scene("studies/models/pendulum.toml"), "--set", "solver.dt=3e-3", "--set",
                            "solver.output_interval=0.5", "--set", "solver.end_time=60", "--set",
                            "solver.correction.method=projection", "--out", out.string(), "--quiet"},
                           kRunSeconds);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Series s = read_series(out / "series.csv");
  ASSERT_EQ(s.rows.size(), 121u);
  // the bar (1 m, pinned at one end) is a compound pendulum of length 2/3 m released at 90 degrees:
  // theta(t) = 2 asin(k sn(K - w t | k^2)) from the downward vertical, k = sin(45 deg)
  const double k = std::sin(0.25 * M_PI), m = k * k, w = std::sqrt(9.81 / (2.0 / 3.0));
  const double quarter = elliptic_k(m);
  const int x = s.column("probe.tip.x");
  double worst = 0.0;
  for (size_t n = 0; n < s.rows.size(); ++n) {
    const double t = s.rows[n][0];
    ASSERT_NEAR(t, 0.5 * static_cast<double>(n), 1e-12) << "row " << n;
    const double theta = 2.0 * std::asin(k * jacobi_elliptic(quarter - w * t, m).sn);
    worst = std::max(worst, std::abs(s.rows[n][x] - std::sin(theta)));
  }
  // rk4 at 3 ms over 60 s is accurate to about 1e-7 m; a row one step late is off by up to
  // |v| dt = 1.3e-2 m
  EXPECT_LT(worst, 1e-5);
}

#ifdef PERIFLEX_TEST_RENDER
// The reproduction: frames every 1.26 ms with steps of 0.5 us that do not divide it.
TEST(RunCommand, FramesAtAnIntervalTheStepDoesNotDivideReachTheEnd) {
  const auto out = fresh_directory("odd_frames");
  const auto frames = out / "frames";
  const auto r = run_child({"run", scene("flexible_slider_crank.toml"), "--render", "--frames", frames.string(),
                            "--frame-every", "0.00126", "--until", "0.006", "--size", "160x96", "--out",
                            out.string(), "--quiet"},
                           kRunSeconds);
  ASSERT_FALSE(r.timed_out) << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(count_files(frames, ".png"), 5);  // t = 0, 1.26, 2.52, 3.78, 5.04 ms
  EXPECT_EQ(read_summary(out / "summary.json")["frames_written"], 5);
}

// --movie alone asks for a movie: it is recorded, not silently ignored.
TEST(RunCommand, MovieWithoutRenderFlagIsRecorded) {
  if (!have_program("ffmpeg")) GTEST_SKIP() << "ffmpeg is not installed";
  const auto out = fresh_directory("movie_alone");
  const auto movie = out / "m.mp4";
  const auto r = run_child({"run", scene("pendulum.toml"), "--movie", movie.string(), "--frame-every", "0.5",
                            "--size", "160x96", "--out", out.string(), "--quiet"},
                           kRunSeconds);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(movie_frames(movie), 11);  // t = 0, 0.5, ..., 5
}

// --camera: a fixed view is accepted, nonsense is refused naming the flag, with the other flags,
// before the scene is built and any output is written.
TEST(RunCommand, CameraOptionIsCheckedAndUsed) {
  const auto out = fresh_directory("camera");
  auto r = run_child({"run", scene("pendulum.toml"), "--frames", (out / "f").string(), "--frame-every", "1",
                      "--size", "160x96", "--camera", "0,-0.5,3", "--out", out.string(), "--quiet"},
                     kRunSeconds);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(count_files(out / "f", ".png"), 6);
  const auto refused = fresh_directory("camera_refused");
  r = run_child({"run", scene("pendulum.toml"), "--frames", (refused / "g").string(), "--camera", "0,0,-1", "--out",
                 refused.string(), "--quiet"},
                kRunSeconds);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--camera"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("stopped"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(refused / "summary.json"));
}

// --plot names series.csv columns of the run and draws into frames: a column the run does not
// write, an empty name, no frames to draw into and --plot-against alone are refused with exit 2,
// naming the flag, before the run starts.
TEST(RunCommand, PlotColumnsAreCheckedAgainstTheRunsSeries) {
  const auto out = fresh_directory("plot_refusals");
  const std::string frames = (out / "f").string();
  const struct {
    std::vector<std::string> flags;
    const char* flag;
    const char* says;
  } cases[] = {
      {{"--frames", frames, "--plot", "kinetic+no_such"}, "--plot", "no column 'no_such'"},
      {{"--frames", frames, "--plot", "kinetic++fracture"}, "--plot", "an empty column name"},
      {{"--frames", frames, "--plot", "kinetic", "--plot-against", "probe.nowhere.x"}, "--plot-against",
       "no column 'probe.nowhere.x'"},
      {{"--plot", "kinetic"}, "--plot", "add --render"},
      {{"--frames", frames, "--plot-against", "t"}, "--plot-against", "needs --plot"},
  };
  for (const auto& c : cases) {
    std::vector<std::string> args = {"run", scene("notched_plate.toml"), "--out", out.string(), "--quiet"};
    args.insert(args.end(), c.flags.begin(), c.flags.end());
    const auto r = run_child(args, kRunSeconds);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(c.flag), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(c.says), std::string::npos) << r.output;
    EXPECT_EQ(count_files(frames, ".png"), 0) << r.output;
  }
  // the refusal lists the columns there are
  const auto r = run_child({"run", scene("notched_plate.toml"), "--out", out.string(), "--quiet", "--frames", frames,
                            "--plot", "nothing"},
                           kRunSeconds);
  EXPECT_NE(r.output.find("driver_work, energy_balance"), std::string::npos) << r.output;
}

// A screenshot time after the end used to print "screenshot in ..." and write nothing, and a
// screenshot file without its time was passed over in silence.
TEST(RunCommand, ScreenshotAfterTheEndOrWithoutItsTimeIsRefused) {
  const auto out = fresh_directory("late_shot");
  auto r = run_child({"run", scene("pendulum.toml"), "--snapshot-at", "9", "--screenshot", (out / "s.png").string(),
                      "--out", out.string(), "--quiet"},
                     kRunSeconds);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--snapshot-at"), std::string::npos) << r.output;
  r = run_child({"run", scene("pendulum.toml"), "--screenshot", (out / "s.png").string(), "--out", out.string(),
                 "--quiet"},
                kRunSeconds);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("key '--screenshot': needs --snapshot-at"), std::string::npos) << r.output;
}
#endif

// --vtk-every N: snapshots every N steps and the last state, like the rows of series.csv, when
// N does not divide the run's steps (the pendulum: 50 steps, N = 20: steps 0, 20, 40 and 50).
TEST(RunCommand, VtkSnapshotsEndWithTheLastState) {
  const auto out = fresh_directory("vtk_last");
  const auto r = run_child({"run", scene("pendulum.toml"), "--until", "0.05", "--vtk-every", "20", "--out",
                            out.string(), "--quiet"},
                           kRunSeconds);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string pvd = read_text(out / "vtk" / "snapshots.pvd");
  std::vector<double> times;
  for (size_t at = pvd.find("timestep=\""); at != std::string::npos; at = pvd.find("timestep=\"", at + 1))
    times.push_back(std::stod(pvd.substr(at + 10)));
  ASSERT_EQ(times.size(), 4u) << pvd;
  EXPECT_NEAR(times[2], 0.04, 1e-12);
  EXPECT_NEAR(times.back(), 0.05, 1e-12);
}

// Stopping with a signal once `ready` holds: the run ends with 128 + the signal, closes its
// rows, frames and movie, and summary.json says it was interrupted and counts what was written.
std::filesystem::path expect_clean_interrupt(const std::string& name, int signal_number,
                                             std::vector<std::string> extra,
                                             const std::function<bool(const std::filesystem::path&)>& ready) {
  const auto out = fresh_directory(name);
  std::vector<std::string> args{"run", scene("glass_branching.toml"), "--out", out.string(), "--quiet"};
  args.insert(args.end(), extra.begin(), extra.end());
  Child child(args);
  EXPECT_TRUE(child.started());
  EXPECT_TRUE(child.wait_until([&] { return ready(out); }, 60.0)) << name << ": never got ready";
  child.send(signal_number);
  const ChildResult r = child.finish(60.0);
  EXPECT_FALSE(r.timed_out) << r.output;
  EXPECT_EQ(r.signal, 0) << "killed by signal " << r.signal << ": " << r.output;
  EXPECT_EQ(r.exit_code, 128 + signal_number) << r.output;
  EXPECT_NE(r.output.find("interrupted"), std::string::npos) << r.output;

  const auto summary = read_summary(out / "summary.json");
  EXPECT_TRUE(summary.is_object()) << "summary.json is not valid JSON";
  if (!summary.is_object()) return out;
  EXPECT_EQ(summary["status"], "interrupted");
  EXPECT_EQ(summary["exit_code"], 128 + signal_number);
  EXPECT_LT(summary["simulated_time"].get<double>(), 4.6e-5);
  const Series s = read_series(out / "series.csv");
  EXPECT_EQ(s.incomplete_rows, 0);
  EXPECT_EQ(summary["rows_written"].get<long>(), static_cast<long>(s.rows.size()));
  if (!s.rows.empty()) {
    EXPECT_DOUBLE_EQ(s.rows.back()[0], summary["simulated_time"].get<double>());
  }
  return out;
}

bool has_rows(const std::filesystem::path& out, size_t n) {
  std::ifstream in(out / "series.csv");
  return static_cast<size_t>(std::count(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>(), '\n')) >
         n;
}

TEST(RunCommand, SigintMidRunStopsCleanly) {
  expect_clean_interrupt("sigint_mid", SIGINT, {}, [](const auto& out) { return has_rows(out, 3); });
}

TEST(RunCommand, SigtermMidRunStopsCleanly) {
  expect_clean_interrupt("sigterm_mid", SIGTERM, {}, [](const auto& out) { return has_rows(out, 3); });
}

// the terminal closed (an ssh connection lost)
TEST(RunCommand, SighupMidRunStopsCleanly) {
  expect_clean_interrupt("sighup_mid", SIGHUP, {}, [](const auto& out) { return has_rows(out, 3); });
}

// A run started to outlive its terminal (nohup, here the shell's `trap '' HUP`) goes on after
// SIGHUP, and still stops cleanly on SIGTERM.
TEST(RunCommand, IgnoredSighupStaysIgnored) {
  const auto out = fresh_directory("sighup_ignored");
  const auto shell = Child::shell("trap '' HUP; exec \"" + std::string(PERIFLEX_BINARY) + "\" run \"" +
                                  scene("glass_branching.toml") + "\" --out \"" + out.string() + "\" --quiet");
  ASSERT_TRUE(shell->wait_until([&] { return has_rows(out, 3); }, 60.0)) << "never got ready";
  shell->send(SIGHUP);
  // still running a second later: more rows come
  std::this_thread::sleep_for(std::chrono::seconds(1));
  const Series before = read_series(out / "series.csv");
  EXPECT_TRUE(shell->wait_until([&] { return read_series(out / "series.csv").rows.size() > before.rows.size(); }, 30.0))
      << "the run stopped on an ignored SIGHUP";
  shell->send(SIGTERM);
  const ChildResult r = shell->finish(60.0);
  EXPECT_EQ(r.exit_code, 143) << r.output;
  EXPECT_EQ(read_summary(out / "summary.json")["status"], "interrupted");
}

TEST(RunCommand, SigintDuringSetUpStopsCleanly) {
  // as soon as the first summary.json is there: the model is built, the run not yet started
  expect_clean_interrupt("sigint_setup", SIGINT, {},
                         [](const auto& out) { return std::filesystem::exists(out / "summary.json"); });
}

#ifdef PERIFLEX_TEST_RENDER
TEST(RunCommand, SigtermWhileRecordingLeavesAPlayableMovieAndFrames) {
  if (!have_program("ffmpeg")) GTEST_SKIP() << "ffmpeg is not installed";
  const auto frames = fresh_directory("sigterm_movie_frames");
  const auto movie = fresh_directory("sigterm_movie_file") / "m.mp4";
  const auto out = expect_clean_interrupt(
      "sigterm_movie", SIGTERM,
      {"--frames", frames.string(), "--movie", movie.string(), "--frame-every", "2e-7", "--size", "160x96"},
      [](const auto& dir) { return has_rows(dir, 3); });
  const long written = read_summary(out / "summary.json")["frames_written"].get<long>();
  EXPECT_GT(written, 0);
  EXPECT_EQ(count_files(frames, ".png"), written);
  EXPECT_EQ(movie_frames(movie), written);
}
#endif

// A write that fails after set-up (here: series.csv on a full disk) ends the run with a message,
// and summary.json says so instead of "running".
TEST(RunCommand, FailedWriteIsToldInTheSummary) {
  const auto out = fresh_directory("disk_full");
  std::filesystem::create_symlink("/dev/full", out / "series.csv");
  const auto r = run_child({"run", scene("pendulum.toml"), "--out", out.string(), "--quiet"}, kRunSeconds);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("series.csv"), std::string::npos) << r.output;
  const auto summary = read_summary(out / "summary.json");
  EXPECT_EQ(summary["status"], "error");
  EXPECT_EQ(summary["exit_code"], 1);
  EXPECT_NE(summary["message"].get<std::string>().find("series.csv"), std::string::npos);
}

// Runs `periflex run SCENE --out run ARGS` in DISK, a disk that really fills up: a tmpfs of
// `kilobytes`, mounted in a mount namespace of the test's own, which vanishes with it. What the
// run left is copied to `kept` (cli_test_out_NAME); the output ends with "exit=N". False when no such disk can be made.
bool run_on_small_disk(const std::string& name, int kilobytes, const std::string& scene_file,
                       const std::vector<std::string>& args, std::filesystem::path& kept, ChildResult& result) {
  kept = fresh_directory(name);
  // a mount point of the test's own: ctest runs tests side by side
  const auto disk = fresh_directory(name + "_mount");
  const std::string mount = "unshare -rm sh -c 'mount -t tmpfs -o size=" + std::to_string(kilobytes) + "k tmpfs \"" +
                            disk.string() + "\"";
  if (Child::shell(mount + "'")->finish(kRunSeconds).exit_code != 0) return false;
  std::string run = "cd \"" + disk.string() + "\" && \"" + PERIFLEX_BINARY + "\" run \"" + scene(scene_file) +
                    "\" --out run --quiet";
  for (const std::string& a : args) run += " " + a;
  run += "; echo \"exit=$?\"; cp -r \"" + disk.string() + "/run/.\" \"" + kept.string() + "\"";
  result = Child::shell(mount + " && " + run + "'")->finish(kRunSeconds);
  return true;
}

// What every run stopped by the full disk shows: exit 1, and a summary.json that is valid JSON,
// says `error` and names the file the disk refused. Returns the summary.
nlohmann::json expect_stopped_by_the_disk(const ChildResult& r, const std::filesystem::path& kept,
                                          const std::string& file) {
  EXPECT_FALSE(r.timed_out) << r.output;
  EXPECT_NE(r.output.find("exit=1"), std::string::npos) << r.output;
  const auto summary = read_summary(kept / "summary.json");
  EXPECT_FALSE(summary.is_discarded()) << "summary.json is not valid JSON";
  if (summary.is_discarded()) return nlohmann::json::object();
  EXPECT_EQ(summary["status"], "error");
  EXPECT_EQ(summary["exit_code"], 1);
  EXPECT_NE(summary["message"].get<std::string>().find(file), std::string::npos) << summary["message"];
  return summary;
}

// series.csv fills the disk half-way through a row: the file keeps whole rows only, and
// summary.json, which can no longer be written beside itself and renamed, still ends up saying
// how the run ended, with the closing line printed.
TEST(RunCommand, FullDiskKeepsWholeRowsAndATruthfulSummary) {
  std::filesystem::path kept;
  ChildResult r;
  if (!run_on_small_disk("full_disk", 64, "pendulum.toml", {}, kept, r))
    GTEST_SKIP() << "no small disk here: unshare -rm and a tmpfs mount are not allowed";
  const auto summary = expect_stopped_by_the_disk(r, kept, "series.csv");
  EXPECT_NE(r.output.find("series.csv (No space left on device)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("pendulum stopped"), std::string::npos) << r.output;

  const Series s = read_series(kept / "series.csv");
  EXPECT_EQ(s.incomplete_rows, 0);
  EXPECT_GT(s.rows.size(), 10u);
  EXPECT_LT(s.rows.size(), 500u);  // the whole run has 501 rows: the disk did fill
  EXPECT_EQ(summary.value("rows_written", size_t{0}), s.rows.size());
}

#ifdef PERIFLEX_TEST_RENDER
// The frames fill the disk: the summary counts the frames that are there, each a whole PNG.
TEST(RunCommand, FullDiskCountsTheFramesWritten) {
  std::filesystem::path kept;
  ChildResult r;
  if (!run_on_small_disk("full_disk_frames", 600, "slider_crank.toml",
                         {"--render", "--size", "640x360", "--frames", "run/frames"}, kept, r))
    GTEST_SKIP() << "no small disk here: unshare -rm and a tmpfs mount are not allowed";
  const auto summary = expect_stopped_by_the_disk(r, kept, "No space left");
  const auto frames = files_with_extension(kept / "frames", ".png");
  EXPECT_GT(frames.size(), 5u);
  EXPECT_LT(frames.size(), 101u);  // 101 in the whole run: the disk did fill
  EXPECT_EQ(summary.value("frames_written", size_t{0}), frames.size());
  EXPECT_NE(r.output.find(std::to_string(frames.size()) + " frames"), std::string::npos) << r.output;
}

// The movie fills the disk. ffmpeg itself exits with success; the run reads the file back and
// tells the frames it holds, each of which plays.
TEST(RunCommand, FullDiskCutsTheMovieAndSaysSo) {
  if (!have_program("ffmpeg")) GTEST_SKIP() << "ffmpeg is not installed";
  std::filesystem::path kept;
  ChildResult r;
  if (!run_on_small_disk("full_disk_movie", 150, "slider_crank.toml",
                         {"--render", "--size", "640x360", "--movie", "run/m.mp4", "--set", "solver.output_interval=0.1"},
                         kept, r))
    GTEST_SKIP() << "no small disk here: unshare -rm and a tmpfs mount are not allowed";
  const auto summary = expect_stopped_by_the_disk(r, kept, "m.mp4");
  const long written = summary.value("frames_written", 0L);
  EXPECT_GT(written, 0);
  EXPECT_LT(written, 101);  // 101 in the whole run: the disk did fill
  EXPECT_GE(movie_frames(kept / "m.mp4"), written);
}
#endif

// The closing line and summary.json give the same steps per second, and the solver's processor
// time beside its wall time.
TEST(RunCommand, ClosingLineAndSummaryAgree) {
  const auto out = fresh_directory("agree");
  const auto r = run_child({"run", scene("double_pendulum.toml"), "--out", out.string(), "--quiet"}, kRunSeconds);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto summary = read_summary(out / "summary.json");
  const auto m = testing::first_match(r.output, R"(([0-9]+) steps/s)");
  ASSERT_FALSE(m.empty()) << r.output;
  EXPECT_NEAR(std::stod(m[1]), summary["steps_per_second"].get<double>(), 0.5);
  ASSERT_TRUE(summary.contains("solver_cpu_time"));
  EXPECT_GT(summary["solver_cpu_time"].get<double>(), 0.0);
  EXPECT_EQ(summary["steps"], 10000);
}

// HHT far above the step its Newton iterations can take on the flexible slider-crank: a Newton
// iterate lands where the constraints cannot be solved. That is told as a trial of a step too
// large (exit 3, a smaller step proposed first, the summary agreeing), not as a mechanism at a
// toggle position; the step proposed runs to the end.
TEST(RunCommand, HhtStepTooLargeForNewtonAsksForASmallerStep) {
  const auto run_hht = [](const std::string& dt, const std::filesystem::path& out) {
    return run_child({"run", scene("flexible_slider_crank.toml"), "--set", "solver.integrator=\"hht\"", "--set",
                      "solver.dt=" + dt, "--out", out.string(), "--quiet"},
                     kRunSeconds);
  };
  const auto out = fresh_directory("hht_too_large");
  const auto r = run_hht("2e-3", out);
  ASSERT_FALSE(r.timed_out) << r.output;
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("Newton iterate (a trial, not a state of the run)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("Try: lower solver.dt (e.g. to 0.0005)"), std::string::npos) << r.output;
  const auto summary = read_summary(out / "summary.json");
  EXPECT_EQ(summary["status"], "numerical_failure");
  EXPECT_EQ(summary["exit_code"], 3);

  const auto ok = run_hht("5e-4", fresh_directory("hht_smaller"));
  ASSERT_FALSE(ok.timed_out) << ok.output;
  EXPECT_EQ(ok.exit_code, 0) << ok.output;
}

}  // namespace
}  // namespace periflex::testing
