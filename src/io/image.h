// An 8-bit RGBA image in memory, rows from top to bottom, and the small set of operations the
// renderer, the frame writers and the screenshot tests share: PNG read/write and comparison.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace periflex {

struct RgbaImage {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> pixels;  // width * height * 4 bytes, row 0 at the top

  // Allocates width * height pixels, all zero.
  void resize(int w, int h);
  // Pointer to pixel (x, y), (0, 0) being the top-left corner.
  uint8_t* at(int x, int y) { return pixels.data() + 4 * (static_cast<size_t>(y) * width + x); }
  const uint8_t* at(int x, int y) const { return pixels.data() + 4 * (static_cast<size_t>(y) * width + x); }
  bool empty() const { return pixels.empty(); }
};

// Reverses the row order in place (OpenGL reads bottom row first).
void flip_rows(RgbaImage& image);

// Encodes to PNG with the fast encoder of io/png_encoder.h (safe on any thread; opaque
// pictures are stored as RGB).
std::vector<uint8_t> encode_png(const RgbaImage& image);
// Writes a PNG atomically: to "<path>.tmp" first, then renamed, so an interrupted run never
// leaves a truncated file under the final name. Throws std::runtime_error naming the path and
// the system's reason (disk full, no permission, missing folder).
void write_png(const std::string& path, const RgbaImage& image);
// Reads any PNG as RGBA. Throws std::runtime_error naming the path when it cannot.
RgbaImage read_png(const std::string& path);
// Decodes a PNG held in memory as RGBA. Throws std::runtime_error when it cannot.
RgbaImage decode_png(const uint8_t* bytes, size_t size);

// Result of a per-pixel comparison.
struct ImageDiff {
  bool same_size = false;
  long failing_pixels = 0;    // pixels where some channel differs by more than the tolerance
  long total_pixels = 0;
  int max_channel_delta = 0;  // largest difference of any channel
  double failing_fraction() const { return total_pixels ? double(failing_pixels) / total_pixels : 1.0; }
};

// Compares two images channel by channel. A pixel fails when any channel differs by more than
// channel_tolerance (0..255). When diff_image is given it receives a picture of the differences:
// failing pixels red, scaled by the difference; passing pixels a faint grey copy of `actual`.
ImageDiff compare_images(const RgbaImage& expected, const RgbaImage& actual, int channel_tolerance,
                         RgbaImage* diff_image = nullptr);

}  // namespace periflex
