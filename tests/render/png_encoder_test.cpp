// The PNG encoder: checksums against published values, and pictures of every kind decoded by an
// independent decoder (stb_image) back to the same pixels, using every deflate code it emits.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>

#include "render/image.h"
#include "render/png_encoder.h"

namespace periflex {
namespace {

const uint8_t* bytes_of(const std::string& s) { return reinterpret_cast<const uint8_t*>(s.data()); }

uint32_t read_be32(const uint8_t* p) { return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | p[3]; }

// Encodes, decodes with stb_image and expects the very same pixels back.
void expect_round_trip(const RgbaImage& image, DeflateCounts* counts = nullptr, const std::string& what = "") {
  const std::vector<uint8_t> png = encode_png_rgba(image.pixels.data(), image.width, image.height, counts);
  const RgbaImage back = decode_png(png.data(), png.size());
  ASSERT_EQ(back.width, image.width) << what;
  ASSERT_EQ(back.height, image.height) << what;
  const ImageDiff diff = compare_images(image, back, 0);
  EXPECT_EQ(diff.failing_pixels, 0) << what << ": " << image.width << "x" << image.height;
}

RgbaImage flat_image(int w, int h, uint8_t r, uint8_t g, uint8_t b, uint8_t a = 255) {
  RgbaImage image;
  image.resize(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      uint8_t* p = image.at(x, y);
      p[0] = r, p[1] = g, p[2] = b, p[3] = a;
    }
  return image;
}

RgbaImage random_image(int w, int h, unsigned seed, bool opaque) {
  std::mt19937 rng(seed);
  RgbaImage image;
  image.resize(w, h);
  for (size_t i = 0; i < image.pixels.size(); ++i)
    image.pixels[i] = (opaque && i % 4 == 3) ? 255 : static_cast<uint8_t>(rng() & 0xFF);
  return image;
}

TEST(Checksums, Crc32OfTheStandardCheckString) {
  EXPECT_EQ(crc32(bytes_of("123456789"), 9), 0xCBF43926u);
  EXPECT_EQ(crc32(nullptr, 0), 0u);
  // "IEND" with no data: the CRC every PNG ends with
  EXPECT_EQ(crc32(bytes_of("IEND"), 4), 0xAE426082u);
}

TEST(Checksums, Crc32ContinuesAcrossPieces) {
  const std::string text = "The quick brown fox jumps over the lazy dog";
  EXPECT_EQ(crc32(bytes_of(text), text.size()), 0x414FA339u);
  EXPECT_EQ(crc32(bytes_of(text) + 10, text.size() - 10, crc32(bytes_of(text), 10)), 0x414FA339u);
}

TEST(Checksums, Adler32OfKnownStrings) {
  EXPECT_EQ(adler32(bytes_of("Wikipedia"), 9), 0x11E60398u);
  EXPECT_EQ(adler32(nullptr, 0), 1u);
  const std::string text = "The quick brown fox jumps over the lazy dog";
  EXPECT_EQ(adler32(bytes_of(text), text.size()), 0x5BDC0FDAu);
}

TEST(Checksums, Adler32OfLongInputMatchesTheByteByByteDefinition) {
  // long enough to cross the blocks of 5552 bytes and the 16-byte steps at odd offsets
  std::mt19937 rng(7);
  std::vector<uint8_t> data(100003);
  for (auto& b : data) b = static_cast<uint8_t>(rng() % 7 == 0 ? 255 : rng() & 0xFF);
  uint32_t a = 1, b = 0;
  for (uint8_t byte : data) {
    a = (a + byte) % 65521;
    b = (b + a) % 65521;
  }
  EXPECT_EQ(adler32(data.data(), data.size()), b << 16 | a);
  EXPECT_EQ(adler32(data.data() + 333, data.size() - 333, adler32(data.data(), 333)), b << 16 | a);
}

TEST(PngEncoder, FileLayoutIsSignatureHeaderDataEnd) {
  const RgbaImage image = flat_image(5, 3, 10, 20, 30);
  const std::vector<uint8_t> png = encode_png_rgba(image.pixels.data(), 5, 3);
  const uint8_t signature[8] = {137, 80, 78, 71, 13, 10, 26, 10};
  ASSERT_GT(png.size(), 8u + 25u + 12u + 12u);
  EXPECT_EQ(std::memcmp(png.data(), signature, 8), 0);
  EXPECT_EQ(read_be32(&png[8]), 13u);
  EXPECT_EQ(std::memcmp(&png[12], "IHDR", 4), 0);
  EXPECT_EQ(read_be32(&png[16]), 5u);
  EXPECT_EQ(read_be32(&png[20]), 3u);
  EXPECT_EQ(png[24], 8);  // bits per channel
  EXPECT_EQ(png[25], 2);  // opaque: RGB
  EXPECT_EQ(read_be32(&png[29]), crc32(&png[12], 17));
  EXPECT_EQ(std::memcmp(&png[37], "IDAT", 4), 0);
  // ends with an empty IEND chunk
  EXPECT_EQ(std::memcmp(&png[png.size() - 12], "\0\0\0\0IEND\xAE\x42\x60\x82", 12), 0);
}

TEST(PngEncoder, TranslucentPicturesKeepTheirAlpha) {
  RgbaImage image = random_image(17, 9, 3, false);
  image.at(0, 0)[3] = 0;
  const std::vector<uint8_t> png = encode_png_rgba(image.pixels.data(), image.width, image.height);
  EXPECT_EQ(png[25], 6);  // RGBA
  expect_round_trip(image);
}

TEST(PngEncoder, FlatPictureRoundTripsAndShrinks) {
  const RgbaImage image = flat_image(1280, 720, 31, 31, 36);
  DeflateCounts counts;
  const std::vector<uint8_t> png = encode_png_rgba(image.pixels.data(), 1280, 720, &counts);
  // almost all of it copies: 258 bytes cost 31 bits at most
  EXPECT_LT(png.size(), 1280u * 720u * 3u / 50u);
  EXPECT_GT(counts.length_codes[28], 10000);
  expect_round_trip(image);
  expect_round_trip(flat_image(1280, 720, 0, 0, 0, 0));
}

TEST(PngEncoder, RandomPictureRoundTrips) {
  expect_round_trip(random_image(257, 131, 1, true), nullptr, "opaque");
  expect_round_trip(random_image(257, 131, 2, false), nullptr, "translucent");
}

TEST(PngEncoder, GradientRoundTrips) {
  RgbaImage image;
  image.resize(640, 360);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      uint8_t* p = image.at(x, y);
      p[0] = static_cast<uint8_t>(x * 255 / 639);
      p[1] = static_cast<uint8_t>(y * 255 / 359);
      p[2] = static_cast<uint8_t>((x + y) / 4);
      p[3] = 255;
    }
  expect_round_trip(image);
}

TEST(PngEncoder, TinyAndOddSizesRoundTrip) {
  expect_round_trip(flat_image(1, 1, 200, 100, 50), nullptr, "1x1 opaque");
  expect_round_trip(flat_image(1, 1, 200, 100, 50, 128), nullptr, "1x1 translucent");
  for (int w : {1, 2, 3, 5, 7, 13, 101, 333})
    for (int h : {1, 2, 3, 17}) {
      expect_round_trip(random_image(w, h, w * 100 + h, true), nullptr, "random");
      expect_round_trip(flat_image(w, h, 1, 2, 3), nullptr, "flat");
    }
}

TEST(PngEncoder, EmptyPictureIsRefused) {
  uint8_t pixel[4] = {0, 0, 0, 255};
  EXPECT_THROW(encode_png_rgba(pixel, 0, 1), std::invalid_argument);
  EXPECT_THROW(encode_png_rgba(pixel, 1, 0), std::invalid_argument);
}

// Rows of noise broken by flat runs of every length from 1 to 300 pixels (longer than one copy of
// 258 bytes; short ones more often), each row repeated a few times so copies from the row above
// happen too.
TEST(PngEncoder, EveryLengthCodeRoundTrips) {
  DeflateCounts total;
  std::mt19937 rng(11);
  for (bool opaque : {true, false}) {
    RgbaImage image;
    image.resize(997, 64);
    for (int y = 0; y < image.height; ++y) {
      if (y % 4 != 0) {
        std::memcpy(image.at(0, y), image.at(0, y - 1), image.width * 4);
        continue;
      }
      int x = 0;
      uint32_t colour = rng();
      while (x < image.width) {
        // a pixel that shares 0..3 leading channels with the run before it (so copies end at
        // any byte), then a run of a random length of one colour
        const int shared = static_cast<int>(rng() % 4);
        uint8_t* p = image.at(x++, y);
        for (int c = 0; c < 4; ++c) p[c] = static_cast<uint8_t>(c < shared ? colour >> (8 * c) : rng());
        const int run = 1 + static_cast<int>(rng() % (rng() % 2 ? 300 : 8));
        colour = rng();
        for (int k = 0; k < run && x < image.width; ++k, ++x) {
          uint8_t* q = image.at(x, y);
          for (int c = 0; c < 4; ++c) q[c] = static_cast<uint8_t>(colour >> (8 * c));
        }
      }
      if (opaque)
        for (int x2 = 0; x2 < image.width; ++x2) image.at(x2, y)[3] = 255;
    }
    DeflateCounts counts;
    expect_round_trip(image, &counts, opaque ? "opaque runs" : "translucent runs");
    EXPECT_GT(counts.literals, 0);
    for (int i = 0; i < 29; ++i) total.length_codes[i] += counts.length_codes[i];
  }
  for (int i = 0; i < 29; ++i) EXPECT_GT(total.length_codes[i], 0) << "length symbol " << 257 + i;
}

// Copies from the left are one pixel back (3 or 4 bytes); copies from the row above one row's
// bytes back (1 + 3 or 4 bytes per pixel): widths from 1 to 8191 pixels reach every distance code
// up to deflate's 32 KiB window.
TEST(PngEncoder, EveryDistanceCodeRoundTrips) {
  DeflateCounts total;
  std::vector<int> widths;
  for (int w = 1; w < 8192; w = w < 16 ? w + 1 : w * 5 / 4) widths.push_back(w);
  widths.push_back(6144);  // 4 * 6144 + 1 = 24577, the last code's first distance
  widths.push_back(8191);  // the widest whose rows fit the window
  for (int w : widths)
    for (bool opaque : {true, false}) {
      // two identical noise rows, so the second copies the first; a repeated pixel at the start
      // for the copy from the left
      RgbaImage image = random_image(w, 2, w, opaque);
      if (w >= 2) std::memcpy(image.at(1, 0), image.at(0, 0), 4);
      std::memcpy(image.at(0, 1), image.at(0, 0), w * 4);
      DeflateCounts counts;
      expect_round_trip(image, &counts, "width " + std::to_string(w));
      for (int i = 0; i < 30; ++i) total.distance_codes[i] += counts.distance_codes[i];
    }
  // codes 0 and 1 (distances 1 and 2) are never tried
  for (int i = 2; i < 30; ++i) EXPECT_GT(total.distance_codes[i], 0) << "distance code " << i;
}

TEST(PngEncoder, RowsWiderThanTheWindowStillRoundTrip) {
  // 8192 RGBA pixels make a row of 32769 bytes: no copies from above, only from the left
  RgbaImage image = random_image(8200, 2, 5, false);
  std::memcpy(image.at(0, 1), image.at(0, 0), 8200 * 4);
  DeflateCounts counts;
  expect_round_trip(image, &counts);
  EXPECT_EQ(counts.distance_codes[29], 0);
}

TEST(PngEncoder, WritePngIsReadBackUnchanged) {
  const RgbaImage image = random_image(33, 21, 9, true);
  const std::string path = ::testing::TempDir() + "periflex_png_encoder_test.png";
  write_png(path, image);
  const RgbaImage back = read_png(path);
  EXPECT_EQ(compare_images(image, back, 0).failing_pixels, 0);
  std::remove(path.c_str());
}

}  // namespace
}  // namespace periflex
