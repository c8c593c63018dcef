// Movie formats by extension, what an ffmpeg can write of them, and MovieWriter in each: every
// frame in the file (counted by ffprobe, which decodes it), nothing under the movie's name when
// ffmpeg fails.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "io/frame_writer.h"
#include "io/movie_format.h"

namespace periflex {
namespace {

namespace fs = std::filesystem;

fs::path fresh_folder(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("movie_format_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Frames decoded by ffprobe beside ffmpeg, or -1.
long decoded_frames(const fs::path& movie) {
  const fs::path ffprobe = fs::path(find_ffmpeg()).parent_path() / "ffprobe";
  if (!fs::exists(ffprobe)) return -1;
  const std::string command = ffprobe.string() + " -v error -count_frames -select_streams v:0 -show_entries "
                              "stream=nb_read_frames -of csv=p=0 '" + movie.string() + "' 2>/dev/null";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return -1;
  char buffer[64] = {0};
  const bool read = std::fgets(buffer, sizeof buffer, pipe) != nullptr;
  return pclose(pipe) == 0 && read ? std::atol(buffer) : -1;
}

// A frame of smooth colours that change with k, of an odd size (the codecs pad it).
RgbaImage test_frame(int k) {
  RgbaImage frame;
  frame.resize(67, 45);
  for (int y = 0; y < frame.height; ++y)
    for (int x = 0; x < frame.width; ++x) {
      uint8_t* p = frame.pixels.data() + 4 * (static_cast<size_t>(y) * frame.width + x);
      p[0] = static_cast<uint8_t>(3 * x + 5 * k);
      p[1] = static_cast<uint8_t>(4 * y);
      p[2] = static_cast<uint8_t>(7 * k);
      p[3] = 255;
    }
  return frame;
}

TEST(MovieFormat, ListingsOfEncodersAndMuxersAreReadBelowTheirRule) {
  const std::string encoders =
      "Encoders:\n V..... = Video\n A..... = Audio\n ------\n V....D libx264              libx264 H.264\n"
      " V..... gif                  GIF (Graphics Interchange Format)\n A....D aac                  AAC\n";
  const std::string muxers = " File formats:\n D. = Demuxing supported\n .E = Muxing supported\n --\n"
                             "  E mp4             MP4 (MPEG-4 Part 14)\n  E mov,m4a        QuickTime\n";
  const std::set<std::string> e = parse_ffmpeg_listing(encoders);
  EXPECT_EQ(e, (std::set<std::string>{"libx264", "gif", "aac"}));
  const std::set<std::string> m = parse_ffmpeg_listing(muxers);
  EXPECT_EQ(m, (std::set<std::string>{"mp4", "mov", "m4a"}));
  FfmpegAbilities abilities{e, m};
  EXPECT_TRUE(abilities.can_write(*movie_format_of("a.mp4")));
  EXPECT_FALSE(abilities.can_write(*movie_format_of("a.gif")));  // no gif muxer
  EXPECT_EQ(writable_extensions(abilities), ".mp4");
}

TEST(MovieFormat, ExtensionChoosesTheFormatInAnyCase) {
  EXPECT_EQ(movie_format_of("dir.x/plate.GIF")->muxer, "gif");
  EXPECT_EQ(movie_format_of("plate.webm")->encoder, "libvpx-vp9");
  EXPECT_EQ(movie_format_of("plate.mkv")->muxer, "matroska");
  EXPECT_TRUE(movie_format_of("plate.mp4")->fragmented);
  EXPECT_EQ(movie_format_of("plate.mov"), nullptr);
  EXPECT_EQ(movie_format_of("plate"), nullptr);
  EXPECT_EQ(movie_format_of("gif"), nullptr);
}

TEST(MovieFormat, WriterPutsEveryFrameInEachFormatThisFfmpegWrites) {
  if (find_ffmpeg().empty()) GTEST_SKIP() << "ffmpeg is not installed";
  const FfmpegAbilities& abilities = ffmpeg_abilities(find_ffmpeg());
  for (const MovieFormat& format : movie_formats()) {
    if (!abilities.can_write(format)) continue;
    const fs::path dir = fresh_folder(format.muxer);
    const fs::path path = dir / ("m" + format.extension);
    MovieWriter movie(path.string(), 67, 45, 12.0);
    for (int k = 0; k < 29; ++k) movie.write(test_frame(k));
    movie.close();
    EXPECT_EQ(movie.frames_written(), 29) << format.extension;
    ASSERT_TRUE(fs::exists(path)) << format.extension;
    EXPECT_EQ(movie_file_frames(find_ffmpeg(), path.string()), 29) << format.extension;
    const long decoded = decoded_frames(path);
    if (decoded >= 0) {
      EXPECT_EQ(decoded, 29) << format.extension;
    }
    // the temporary file was renamed, not copied
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1) << format.extension;
  }
}

TEST(MovieFormat, FailingFfmpegLeavesNothingUnderTheMoviesName) {
  if (find_ffmpeg().empty()) GTEST_SKIP() << "ffmpeg is not installed";
  const fs::path dir = fresh_folder("failing");
  // lists what the real one lists; asked to encode, takes two frames, writes junk and fails
  const fs::path fake = dir / "ffmpeg";
  std::ofstream(fake) << "#!/bin/sh\ncase \" $* \" in *\" -encoders \"*|*\" -muxers \"*) exec '" << find_ffmpeg()
                      << "' \"$@\";; esac\nfor last; do :; done\nhead -c 24120 >/dev/null\n"
                         "printf 'not a movie' > \"$last\"\nexit 1\n";
  ::chmod(fake.c_str(), 0755);
  for (const char* name : {"m.gif", "m.mp4", "m.avi"}) {
    const fs::path path = dir / name;
    MovieWriter movie(path.string(), 67, 45, 12.0, fake.string());
    // the frames may be refused already (ffmpeg gone), the closing must be
    try {
      for (int k = 0; k < 200; ++k) movie.write(test_frame(k));
    } catch (const std::runtime_error&) {
    }
    bool close_failed = false;
    try {
      movie.close();
    } catch (const std::runtime_error& e) {
      close_failed = true;
      EXPECT_NE(std::string(e.what()).find("ffmpeg"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(close_failed) << name;
    EXPECT_NO_THROW(movie.close()) << "a second close does nothing";
    EXPECT_EQ(movie.frames_written(), 0) << name;
    EXPECT_FALSE(fs::exists(path)) << name;
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1) << name << ": only the script";
  }
}

}  // namespace
}  // namespace periflex
