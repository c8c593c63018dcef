#include "io/png_encoder.h"

#include <libdeflate.h>

#include <algorithm>
#include <cstdlib>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>

namespace periflex {

namespace {

// libdeflate's level 1: rendered frames are flat background and rows that repeat, which its
// fastest level already finds. Measured on 1280x720 frames of the shipped scenes (CPU ms / kB,
// bench/render_bench BM_EncodeSceneFrame): see docs/rendering.md.
constexpr int kCompressionLevel = 1;

void put_u32(std::vector<uint8_t>& out, uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<uint8_t>(v >> shift));
}

// A chunk: length, type, data, CRC-32 of type and data.
void put_chunk(std::vector<uint8_t>& out, const char type[4], const uint8_t* data, size_t size) {
  put_u32(out, static_cast<uint32_t>(size));
  const size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  if (size) out.insert(out.end(), data, data + size);
  put_u32(out, libdeflate_crc32(0, out.data() + start, out.size() - start));
}

struct CompressorFree {
  void operator()(libdeflate_compressor* c) const { libdeflate_free_compressor(c); }
};

// One compressor per thread, kept: allocating one costs more than compressing a small frame.
libdeflate_compressor* thread_compressor() {
  thread_local std::unique_ptr<libdeflate_compressor, CompressorFree> compressor(
      libdeflate_alloc_compressor(kCompressionLevel));
  if (!compressor) throw std::bad_alloc();
  return compressor.get();
}

}  // namespace

std::vector<uint8_t> encode_png_rgba(const uint8_t* pixels, int width, int height) {
  if (width < 1 || height < 1) {
    throw std::invalid_argument("cannot encode an empty picture (" + std::to_string(width) + " x " +
                                std::to_string(height) + ")");
  }
  const size_t count = static_cast<size_t>(width) * static_cast<size_t>(height);
  bool opaque = true;
  for (size_t i = 0; i < count && opaque; ++i) opaque = pixels[4 * i + 3] == 255;
  const int bpp = opaque ? 3 : 4;
  const int stride = bpp * width;

  // rows in the stored format, each after its filter-type byte. Every row goes unfiltered
  // (type 0): on rendered frames deflate finds the flat runs and repeated rows itself, and PNG's
  // predictors break the antialiased edges into noise. Measured on the shipped scenes' frames,
  // choosing the smallest of None, Sub, Up and Paeth per row made files 40 % larger and took
  // twice the time.
  std::vector<uint8_t> raw(static_cast<size_t>(height) * (stride + 1));
  for (int y = 0; y < height; ++y) {
    const uint8_t* source = pixels + static_cast<size_t>(y) * 4 * width;
    uint8_t* out = raw.data() + static_cast<size_t>(y) * (stride + 1);
    *out++ = 0;
    if (opaque) {
      for (int x = 0; x < width; ++x)
        for (int k = 0; k < 3; ++k) out[3 * x + k] = source[4 * x + k];
    } else {
      std::copy(source, source + stride, out);
    }
  }

  libdeflate_compressor* compressor = thread_compressor();
  std::vector<uint8_t> zlib(libdeflate_zlib_compress_bound(compressor, raw.size()));
  const size_t zlib_size = libdeflate_zlib_compress(compressor, raw.data(), raw.size(), zlib.data(), zlib.size());
  if (zlib_size == 0) throw std::runtime_error("PNG compression failed");

  std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  png.reserve(zlib_size + 64);
  uint8_t header[13];
  for (int k = 0; k < 4; ++k) {
    header[k] = static_cast<uint8_t>(static_cast<uint32_t>(width) >> (24 - 8 * k));
    header[4 + k] = static_cast<uint8_t>(static_cast<uint32_t>(height) >> (24 - 8 * k));
  }
  header[8] = 8;                  // bits per sample
  header[9] = opaque ? 2 : 6;     // colour type: RGB or RGBA
  header[10] = header[11] = header[12] = 0;  // deflate, adaptive filtering, no interlace
  put_chunk(png, "IHDR", header, sizeof header);
  put_chunk(png, "IDAT", zlib.data(), zlib_size);
  put_chunk(png, "IEND", nullptr, 0);
  return png;
}

}  // namespace periflex
