#include "io/image.h"

#include <stb_image.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "io/png_encoder.h"

namespace periflex {

void RgbaImage::resize(int w, int h) {
  width = w;
  height = h;
  pixels.assign(static_cast<size_t>(w) * h * 4, 0);
}

void flip_rows(RgbaImage& image) {
  const size_t stride = static_cast<size_t>(image.width) * 4;
  std::vector<uint8_t> row(stride);
  for (int top = 0, bottom = image.height - 1; top < bottom; ++top, --bottom) {
    uint8_t* a = image.pixels.data() + top * stride;
    uint8_t* b = image.pixels.data() + bottom * stride;
    std::memcpy(row.data(), a, stride);
    std::memcpy(a, b, stride);
    std::memcpy(b, row.data(), stride);
  }
}

std::vector<uint8_t> encode_png(const RgbaImage& image) {
  if (image.empty() || image.pixels.size() != static_cast<size_t>(image.width) * image.height * 4)
    throw std::runtime_error("PNG encoding failed: the image is " + std::to_string(image.width) + "x" +
                             std::to_string(image.height) + " but holds " + std::to_string(image.pixels.size()) +
                             " bytes");
  return encode_png_rgba(image.pixels.data(), image.width, image.height);
}

void write_png(const std::string& path, const RgbaImage& image) {
  const std::vector<uint8_t> bytes = encode_png(image);
  const std::string tmp = path + ".tmp";
  // write and flush the temporary file, checking every step
  FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw std::runtime_error("cannot create " + tmp + ": " + std::strerror(errno));
  const size_t written = std::fwrite(bytes.data(), 1, bytes.size(), f);
  const int write_errno = errno;
  const bool flushed = std::fflush(f) == 0;
  const int flush_errno = errno;
  const bool closed = std::fclose(f) == 0;
  if (written != bytes.size() || !flushed || !closed) {
    std::remove(tmp.c_str());
    const int e = written != bytes.size() ? write_errno : flush_errno;
    throw std::runtime_error("cannot write " + path + ": " + std::strerror(e ? e : EIO));
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::remove(tmp.c_str());
    throw std::runtime_error("cannot rename " + tmp + " to " + path + ": " + ec.message());
  }
}

namespace {

// Copies the RGBA pixels stb_image decoded and frees its buffer.
RgbaImage take_stb_pixels(unsigned char* data, int w, int h) {
  RgbaImage image;
  image.width = w;
  image.height = h;
  image.pixels.assign(data, data + static_cast<size_t>(w) * h * 4);
  stbi_image_free(data);
  return image;
}

}  // namespace

RgbaImage read_png(const std::string& path) {
  int w = 0, h = 0, channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &channels, 4);
  if (!data) {
    const char* reason = stbi_failure_reason();
    throw std::runtime_error("cannot read image " + path + ": " + (reason ? reason : "unknown error"));
  }
  return take_stb_pixels(data, w, h);
}

RgbaImage decode_png(const uint8_t* bytes, size_t size) {
  int w = 0, h = 0, channels = 0;
  unsigned char* data = stbi_load_from_memory(bytes, static_cast<int>(size), &w, &h, &channels, 4);
  if (!data) {
    const char* reason = stbi_failure_reason();
    throw std::runtime_error(std::string("cannot decode PNG: ") + (reason ? reason : "unknown error"));
  }
  return take_stb_pixels(data, w, h);
}

ImageDiff compare_images(const RgbaImage& expected, const RgbaImage& actual, int channel_tolerance,
                         RgbaImage* diff_image) {
  ImageDiff diff;
  diff.same_size = expected.width == actual.width && expected.height == actual.height;
  diff.total_pixels = static_cast<long>(actual.width) * actual.height;
  if (!diff.same_size) {
    diff.failing_pixels = diff.total_pixels;
    if (diff_image) *diff_image = actual;
    return diff;
  }
  if (diff_image) diff_image->resize(actual.width, actual.height);
  for (long i = 0; i < diff.total_pixels; ++i) {
    const uint8_t* e = expected.pixels.data() + 4 * i;
    const uint8_t* a = actual.pixels.data() + 4 * i;
    int worst = 0;
    for (int c = 0; c < 4; ++c) worst = std::max(worst, std::abs(int(e[c]) - int(a[c])));
    diff.max_channel_delta = std::max(diff.max_channel_delta, worst);
    const bool fails = worst > channel_tolerance;
    if (fails) ++diff.failing_pixels;
    if (diff_image) {
      uint8_t* d = diff_image->pixels.data() + 4 * i;
      if (fails) {
        d[0] = static_cast<uint8_t>(std::min(255, 128 + worst));
        d[1] = d[2] = 0;
      } else {
        const uint8_t grey = static_cast<uint8_t>((int(a[0]) + a[1] + a[2]) / 12);
        d[0] = d[1] = d[2] = grey;
      }
      d[3] = 255;
    }
  }
  return diff;
}

}  // namespace periflex
