// A fast PNG encoder for rendered frames, with no zlib and no global state: any number of threads
// may encode at once.
//
// Rendered frames are mostly flat background and rows that repeat the row above, so instead of
// searching for matches like zlib, the deflate stream only tries two copies per position: the
// pixel to the left and the pixel above. Everything is coded with deflate's fixed Huffman codes
// (no code tables to build or send). This runs at a few nanoseconds per byte and still shrinks a
// rendered 1280x720 frame by one to two orders of magnitude; noisy pictures come out about as
// large as the raw pixels.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace periflex {

// CRC-32 as used by PNG chunks, gzip and zip (polynomial 0xEDB88320, reflected), of `size` bytes,
// continuing from `crc` (0 to start a new one).
uint32_t crc32(const uint8_t* data, size_t size, uint32_t crc = 0);
// Adler-32 as used by zlib streams, of `size` bytes, continuing from `adler` (1 to start).
uint32_t adler32(const uint8_t* data, size_t size, uint32_t adler = 1);

// What a deflate stream was made of: for tests (every code must round-trip) and for tuning.
struct DeflateCounts {
  long literals = 0;                      // bytes sent as literals
  long matches = 0;                       // copies of earlier bytes
  std::array<long, 29> length_codes{};    // uses of length symbol 257 + i
  std::array<long, 30> distance_codes{};  // uses of distance code i
};

// Encodes width x height 8-bit RGBA pixels (rows top to bottom, 4 * width bytes each, no padding)
// as a PNG file in memory. Pictures whose alpha is 255 everywhere are stored as RGB (they decode
// to the same RGBA), others as RGBA. When given, counts receives what the deflate stream used.
// Throws std::invalid_argument for an empty picture (width or height below 1).
std::vector<uint8_t> encode_png_rgba(const uint8_t* pixels, int width, int height,
                                     DeflateCounts* counts = nullptr);

}  // namespace periflex
