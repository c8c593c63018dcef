// Reading back what a fragmented MP4 holds: samples of the fragments whose moof and mdat are both
// whole, and whether the boxes end with the file. Files built box by box here, and a movie that
// ffmpeg wrote through MovieWriter (every frame in it; cut short, only the whole fragments).
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "io/frame_writer.h"
#include "io/mp4_fragments.h"

namespace periflex {
namespace {

std::string be32(uint32_t v) {
  return {char(v >> 24), char((v >> 16) & 0xFF), char((v >> 8) & 0xFF), char(v & 0xFF)};
}

std::string box(const std::string& type, const std::string& content) {
  return be32(static_cast<uint32_t>(8 + content.size())) + type + content;
}

// a moof with one traf holding a tfhd and a trun of `samples` (no per-sample fields)
std::string moof(uint32_t samples) {
  const std::string trun = box("trun", be32(0) + be32(samples));
  return box("moof", box("mfhd", be32(0) + be32(1)) + box("traf", box("tfhd", be32(0) + be32(1)) + trun));
}

std::string write_file(const std::string& name, const std::string& bytes) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

TEST(Mp4Fragments, CountsTheSamplesOfWholeFragments) {
  const std::string head = box("ftyp", "isom") + box("moov", "");
  const std::string file = head + moof(3) + box("mdat", std::string(40, 'x')) + moof(2) + box("mdat", "yyyy");
  const Mp4Fragments whole = read_mp4_fragments(write_file("mp4_whole.mp4", file));
  EXPECT_TRUE(whole.whole);
  EXPECT_EQ(whole.samples, 5);

  // the last mdat cut short: its fragment does not count
  const Mp4Fragments cut = read_mp4_fragments(write_file("mp4_cut.mp4", file.substr(0, file.size() - 2)));
  EXPECT_FALSE(cut.whole);
  EXPECT_EQ(cut.samples, 3);

  // a moof without its mdat does not count either
  const Mp4Fragments no_data = read_mp4_fragments(write_file("mp4_no_data.mp4", head + moof(3)));
  EXPECT_TRUE(no_data.whole);
  EXPECT_EQ(no_data.samples, 0);
}

TEST(Mp4Fragments, ReadsSixtyFourBitSizesAndRefusesNonsense) {
  // size 1: the 64-bit size follows the type
  const std::string large = be32(1) + "mdat" + be32(0) + be32(16 + 4) + "data";
  const Mp4Fragments r = read_mp4_fragments(write_file("mp4_large.mp4", moof(4) + large));
  EXPECT_TRUE(r.whole);
  EXPECT_EQ(r.samples, 4);
  // a size smaller than its own header, and a file that is not there
  EXPECT_FALSE(read_mp4_fragments(write_file("mp4_bad.mp4", be32(4) + "mdat")).whole);
  EXPECT_FALSE(read_mp4_fragments(::testing::TempDir() + "mp4_missing.mp4").whole);
}

// MovieWriter's own movie holds every frame sent, and a copy cut short holds fewer, whole.
TEST(Mp4Fragments, MovieOfMovieWriterHoldsEveryFrame) {
  if (find_ffmpeg().empty()) GTEST_SKIP() << "ffmpeg is not installed";
  const std::string path = ::testing::TempDir() + "mp4_writer_movie.mp4";
  RgbaImage frame;
  frame.width = 64;
  frame.height = 48;
  frame.pixels.assign(static_cast<size_t>(frame.width) * frame.height * 4, 0);
  {
    MovieWriter movie(path, frame.width, frame.height, 10.0);
    // noise, so that every frame takes room and the fragments are of like sizes
    uint32_t state = 12345;
    for (int k = 0; k < 35; ++k) {
      for (uint8_t& p : frame.pixels) p = static_cast<uint8_t>((state = state * 1664525u + 1013904223u) >> 24);
      movie.write(frame);
    }
    movie.close();
    EXPECT_EQ(movie.frames_written(), 35);
  }
  const Mp4Fragments full = read_mp4_fragments(path);
  EXPECT_TRUE(full.whole);
  EXPECT_EQ(full.samples, 35);

  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // (ffmpeg ends the file with an index box, mfra, after the last fragment: cut into the fragments)
  const Mp4Fragments cut = read_mp4_fragments(write_file("mp4_writer_cut.mp4", bytes.substr(0, bytes.size() / 2)));
  EXPECT_FALSE(cut.whole);
  EXPECT_GT(cut.samples, 0);
  EXPECT_LT(cut.samples, 35);
}

}  // namespace
}  // namespace periflex
