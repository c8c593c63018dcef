// `periflex run --movie FILE` in every format its extension may name, run as typed: a playable
// file with every frame (counted by ffprobe, which decodes it), or a refusal with exit 2 before
// the first step; and a movie whose ffmpeg fails leaves no file under the name asked for.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <cmath>
#include <fstream>

#include "child_run.h"
#include "run_output_files.h"
#include "run_program.h"

namespace periflex::testing {
namespace {

namespace fs = std::filesystem;

constexpr double kMovieRunSeconds = 180.0;

// Whether this machine's ffmpeg lists `name` among its encoders (asked here, apart from the
// program's own probe).
[[maybe_unused]] bool ffmpeg_has_encoder(const std::string& name) {
  return std::system(("ffmpeg -hide_banner -encoders 2>/dev/null | grep -qw -- '" + name + "'").c_str()) == 0;
}

// An executable script named ffmpeg in `dir` with `body` (sh), for a PATH that puts it first.
void write_fake_ffmpeg(const fs::path& dir, const std::string& body) {
  fs::create_directories(dir);
  const fs::path script = dir / "ffmpeg";
  std::ofstream(script) << "#!/bin/sh\n" << body;
  ::chmod(script.c_str(), 0755);
}

// The real ffmpeg, for the fake ones to call.
std::string real_ffmpeg() {
  FILE* pipe = popen("command -v ffmpeg", "r");
  char buffer[512] = {0};
  const bool read = pipe && std::fgets(buffer, sizeof buffer, pipe);
  if (pipe) pclose(pipe);
  std::string path = read ? buffer : "";
  while (!path.empty() && (path.back() == '\n' || path.back() == '\r')) path.pop_back();
  return path;
}

#ifdef PERIFLEX_TEST_RENDER

// The notched plate to 2.9e-5 s (dt 4e-7 s), a frame every 1.3e-6 s: a frame interval that is
// not a whole number of steps, and an end that is neither: floor(2.9e-5 / 1.3e-6) + 1 frames.
TEST(MovieFormats, EachExtensionGivesAPlayableMovieWithEveryFrameOrIsRefusedBeforeTheFirstStep) {
  if (!have_program("ffmpeg") || !have_program("ffprobe")) GTEST_SKIP() << "needs ffmpeg and ffprobe";
  const long expected = static_cast<long>(std::floor(2.9e-5 / 1.3e-6)) + 1;
  struct Case {
    const char* extension;
    const char* encoder;
  };
  for (const Case c : {Case{"mp4", "libx264"}, Case{"webm", "libvpx-vp9"}, Case{"mkv", "libx264"}, Case{"gif", "gif"},
                       Case{"avi", "mpeg4"}, Case{"GIF", "gif"}}) {
    const auto dir = fresh_directory(std::string("movie_format_") + c.extension);
    const fs::path movie = dir / (std::string("plate.") + c.extension);
    const auto r = run_child({"run", scene("notched_plate.toml"), "--until", "2.9e-5", "--frame-every", "1.3e-6",
                              "--size", "160x96", "--movie", movie.string(), "--quiet", "--out", (dir / "run").string()},
                             kMovieRunSeconds);
    ASSERT_FALSE(r.timed_out) << c.extension;
    if (!ffmpeg_has_encoder(c.encoder)) {
      // refused up front: nothing simulated, no file
      EXPECT_EQ(r.exit_code, 2) << c.extension << ": " << r.output;
      EXPECT_NE(r.output.find("--movie"), std::string::npos) << r.output;
      EXPECT_FALSE(fs::exists(dir / "run" / "series.csv")) << c.extension;
      EXPECT_FALSE(fs::exists(movie)) << c.extension;
      continue;
    }
    ASSERT_EQ(r.exit_code, 0) << c.extension << ": " << r.output;
    EXPECT_EQ(movie_frames(movie), expected) << c.extension;
    EXPECT_EQ(read_summary(dir / "run" / "summary.json")["frames_written"].get<long>(), expected) << c.extension;
    // nothing left beside it: the temporary file was renamed
    long files = 0;
    for (const auto& entry : fs::directory_iterator(dir)) files += entry.is_regular_file();
    EXPECT_EQ(files, 1) << c.extension;
  }
}

// A checkpoint folder replayed into a GIF: one frame per state, the start and each checkpoint.
TEST(MovieFormats, ReplayOfACheckpointFolderWritesAGif) {
  if (!have_program("ffmpeg") || !have_program("ffprobe")) GTEST_SKIP() << "needs ffmpeg and ffprobe";
  const auto dir = fresh_directory("movie_replay_gif");
  const auto live = run_child({"run", scene("pendulum.toml"), "--until", "0.25", "--checkpoint-every", "0.03",
                               "--checkpoint-dir", (dir / "states").string(), "--quiet", "--out", (dir / "live").string()},
                              kMovieRunSeconds);
  ASSERT_EQ(live.exit_code, 0) << live.output;
  long states = 1;  // the start
  for (const auto& entry : fs::directory_iterator(dir / "states")) states += entry.path().extension() == ".pfstate";
  ASSERT_EQ(states, 1 + static_cast<long>(std::floor(0.25 / 0.03)));
  const fs::path movie = dir / "replay.gif";
  const auto r = run_child({"run", (dir / "states").string(), "--movie", movie.string(), "--size", "96x64", "--quiet",
                            "--out", (dir / "replay").string()},
                           kMovieRunSeconds);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(movie_frames(movie), states);
}

// An ffmpeg that takes part of the frames, writes a broken file and exits with an error: the run
// says so, and no file is left under the name asked for, in a format written under a temporary
// name (GIF) nor in the MP4 written in place (which then holds no whole frame).
TEST(MovieFormats, MovieWhoseFfmpegFailsLeavesNoFileUnderItsName) {
  const std::string real = real_ffmpeg();
  if (real.empty()) GTEST_SKIP() << "needs ffmpeg";
  const auto dir = fresh_directory("movie_ffmpeg_fails");
  // the listings pass through; an encoding reads a few frames, writes junk where it was told
  // to write the movie (the last argument) and fails
  write_fake_ffmpeg(dir / "bin", "case \" $* \" in *\" -encoders \"*|*\" -muxers \"*) exec '" + real +
                                     "' \"$@\";; esac\n"
                                     "for last; do :; done\n"
                                     "head -c 200000 >/dev/null\n"
                                     "printf 'not a movie' > \"$last\"\n"
                                     "exit 1\n");
  for (const char* name : {"plate.gif", "plate.mp4", "plate.webm"}) {
    const fs::path movie = dir / name;
    auto child = Child::shell("PATH='" + (dir / "bin").string() + "':\"$PATH\" " + PERIFLEX_BINARY + " run " +
                              scene("notched_plate.toml") + " --until 2e-5 --frame-every 4e-7 --size 160x96 --movie " +
                              movie.string() + " --quiet --out " + (dir / "run").string());
    const ChildResult r = child->finish(kMovieRunSeconds);
    ASSERT_FALSE(r.timed_out);
    EXPECT_NE(r.exit_code, 0) << name << ": " << r.output;
    EXPECT_NE(r.output.find("ffmpeg"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(movie)) << name << " was left behind";
    // nor a temporary file beside it
    long files = 0;
    for (const auto& entry : fs::directory_iterator(dir)) files += entry.is_regular_file();
    EXPECT_EQ(files, 0) << name;
    EXPECT_EQ(read_summary(dir / "run" / "summary.json")["frames_written"].get<long>(), 0) << name;
  }
}

#endif

// An extension that names no movie format, or one whose encoder this ffmpeg lacks, is refused
// with exit 2 naming --movie and what can be written, before anything is simulated.
TEST(MovieFormats, ExtensionThisFfmpegCannotWriteIsRefusedNamingWhatItCan) {
  const std::string real = real_ffmpeg();
  if (real.empty()) GTEST_SKIP() << "needs ffmpeg";
  const auto dir = fresh_directory("movie_refused");
  // an ffmpeg built without VP9
  write_fake_ffmpeg(dir / "bin", "case \" $* \" in *\" -encoders \"*) '" + real +
                                     "' \"$@\" | grep -v libvpx-vp9; exit 0;; esac\nexec '" + real + "' \"$@\"\n");
  struct Case {
    std::string movie, said;
  };
  for (const Case& c : {Case{"plate.mov", "plate.mov"}, Case{"plate", "plate"}, Case{"plate.webm", "libvpx-vp9"}}) {
    auto child = Child::shell("PATH='" + (dir / "bin").string() + "':\"$PATH\" " + PERIFLEX_BINARY + " run " +
                              scene("notched_plate.toml") + " --until 1e-3 --movie " + (dir / c.movie).string() +
                              " --quiet --out " + (dir / "run").string());
    const ChildResult r = child->finish(kMovieRunSeconds);
    EXPECT_EQ(r.exit_code, 2) << c.movie << ": " << r.output;
    EXPECT_NE(r.output.find("--movie"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(c.said), std::string::npos) << r.output;
    // what it can write is listed, VP9 not among it
    EXPECT_NE(r.output.find(".gif"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("can write .mp4, .webm"), std::string::npos) << r.output;
    EXPECT_LT(r.seconds, 30.0) << "refused only after simulating";
    EXPECT_FALSE(fs::exists(dir / "run" / "series.csv")) << c.movie;
    EXPECT_FALSE(fs::exists(dir / c.movie)) << c.movie;
  }
}

}  // namespace
}  // namespace periflex::testing
