// The PNG encoder: the file's layout and checksums, and pictures of every kind decoded by an
// independent decoder (stb_image) back to the same pixels.
#include <gtest/gtest.h>
#include <libdeflate.h>

#include <cstring>
#include <random>
#include <string>

#include "io/image.h"
#include "io/png_encoder.h"

namespace periflex {
namespace {

uint32_t read_be32(const uint8_t* p) { return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | p[3]; }

// Encodes, decodes with stb_image and expects the very same pixels back.
void expect_round_trip(const RgbaImage& image, const std::string& what = "") {
  const std::vector<uint8_t> png = encode_png_rgba(image.pixels.data(), image.width, image.height);
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
  EXPECT_EQ(read_be32(&png[29]), libdeflate_crc32(0, &png[12], 17));  // over type and data
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
  const std::vector<uint8_t> png = encode_png_rgba(image.pixels.data(), 1280, 720);
  // deflate copies the repeated bytes: far below the raw 2.7 MB
  EXPECT_LT(png.size(), 1280u * 720u * 3u / 200u);
  expect_round_trip(image);
  expect_round_trip(flat_image(1280, 720, 0, 0, 0, 0));
}

TEST(PngEncoder, RandomPictureRoundTrips) {
  expect_round_trip(random_image(257, 131, 1, true), "opaque");
  expect_round_trip(random_image(257, 131, 2, false), "translucent");
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
  expect_round_trip(flat_image(1, 1, 200, 100, 50), "1x1 opaque");
  expect_round_trip(flat_image(1, 1, 200, 100, 50, 128), "1x1 translucent");
  for (int w : {1, 2, 3, 5, 7, 13, 101, 333})
    for (int h : {1, 2, 3, 17}) {
      expect_round_trip(random_image(w, h, w * 100 + h, true), "random");
      expect_round_trip(flat_image(w, h, 1, 2, 3), "flat");
    }
}

TEST(PngEncoder, EmptyPictureIsRefused) {
  uint8_t pixel[4] = {0, 0, 0, 255};
  EXPECT_THROW(encode_png_rgba(pixel, 0, 1), std::invalid_argument);
  EXPECT_THROW(encode_png_rgba(pixel, 1, 0), std::invalid_argument);
}

TEST(PngEncoder, WideRowsRoundTrip) {
  // 8200 RGBA pixels make a row of 32801 bytes, wider than deflate's 32 KiB window
  RgbaImage image = random_image(8200, 2, 5, false);
  std::memcpy(image.at(0, 1), image.at(0, 0), 8200 * 4);
  expect_round_trip(image);
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
