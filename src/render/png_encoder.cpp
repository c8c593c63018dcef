#include "render/png_encoder.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>

namespace periflex {

namespace {

// ---------------------------------------------------------------------------
// Tables, all built at compile time

// CRC-32 of every byte value, for the byte-at-a-time update.
constexpr std::array<uint32_t, 256> make_crc_table() {
  std::array<uint32_t, 256> table{};
  for (uint32_t n = 0; n < 256; ++n) {
    uint32_t c = n;
    for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    table[n] = c;
  }
  return table;
}
constexpr std::array<uint32_t, 256> kCrcTable = make_crc_table();

// Deflate packs its fields least significant bit first but reads Huffman codes most significant
// bit first; a code stored bit-reversed can be appended like any other field.
constexpr uint32_t reverse_bits(uint32_t code, int length) {
  uint32_t reversed = 0;
  for (int i = 0; i < length; ++i) reversed |= ((code >> i) & 1u) << (length - 1 - i);
  return reversed;
}

// Bits ready to append (code reversed, followed by its extra bits) and how many there are.
struct Code {
  uint32_t bits = 0;
  int length = 0;
};

// The fixed literal/length code of RFC 1951, section 3.2.6.
constexpr Code fixed_symbol_code(int symbol) {
  if (symbol < 144) return {reverse_bits(0x30 + symbol, 8), 8};
  if (symbol < 256) return {reverse_bits(0x190 + symbol - 144, 9), 9};
  if (symbol < 280) return {reverse_bits(symbol - 256, 7), 7};
  return {reverse_bits(0xC0 + symbol - 280, 8), 8};
}

// Match lengths 3..258 and distances 1..32768 as a code plus extra bits (RFC 1951, 3.2.5).
constexpr int kLengthBase[29] = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23, 27,
                                 31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
constexpr int kLengthExtra[29] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                  2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
constexpr int kDistanceBase[30] = {1,    2,    3,    4,    5,    7,     9,     13,    17,    25,
                                   33,   49,   65,   97,   129,  193,   257,   385,   513,   769,
                                   1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
constexpr int kDistanceExtra[30] = {0, 0, 0, 0, 1, 1, 2, 2,  3,  3,  4,  4,  5,  5,  6,
                                    6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};
constexpr int kMaxMatch = 258;
constexpr size_t kWindow = 32768;

struct FixedCodes {
  std::array<Code, 256> literal{};
  std::array<Code, kMaxMatch + 1> length{};        // for lengths 3..258: symbol code + extra bits
  std::array<uint8_t, kMaxMatch + 1> length_code{};  // which of the 29 length symbols
  Code end_of_block{};
};

constexpr FixedCodes make_fixed_codes() {
  FixedCodes codes;
  for (int v = 0; v < 256; ++v) codes.literal[v] = fixed_symbol_code(v);
  for (int length = 3; length <= kMaxMatch; ++length) {
    int i = 28;
    while (kLengthBase[i] > length) --i;
    const Code symbol = fixed_symbol_code(257 + i);
    codes.length[length] = {symbol.bits | uint32_t(length - kLengthBase[i]) << symbol.length,
                            symbol.length + kLengthExtra[i]};
    codes.length_code[length] = static_cast<uint8_t>(i);
  }
  codes.end_of_block = fixed_symbol_code(256);
  return codes;
}
constexpr FixedCodes kFixed = make_fixed_codes();

int distance_code(size_t distance) {
  int i = 29;
  while (static_cast<size_t>(kDistanceBase[i]) > distance) --i;
  return i;
}

// A distance as its fixed 5-bit code followed by its extra bits.
Code distance_bits(size_t distance) {
  const int i = distance_code(distance);
  return {reverse_bits(static_cast<uint32_t>(i), 5) | uint32_t(distance - kDistanceBase[i]) << 5,
          5 + kDistanceExtra[i]};
}

// ---------------------------------------------------------------------------
// Deflate

// Appends fields to a byte buffer, least significant bit first, four bytes at a time. The buffer
// must have room for everything written.
class BitWriter {
 public:
  explicit BitWriter(uint8_t* out) : out_(out) {}
  // Appends the low n bits of bits (n <= 32).
  void put(uint64_t bits, int n) {
    pending_ |= bits << count_;
    count_ += n;
    if (count_ >= 32) {
      for (int k = 0; k < 4; ++k) out_[k] = static_cast<uint8_t>(pending_ >> (8 * k));
      out_ += 4;
      pending_ >>= 32;
      count_ -= 32;
    }
  }
  // Writes the last partial byte (padded with zeros); returns the end of the output.
  uint8_t* finish() {
    for (; count_ > 0; count_ -= 8, pending_ >>= 8) *out_++ = static_cast<uint8_t>(pending_);
    count_ = 0;
    return out_;
  }

 private:
  uint8_t* out_;
  uint64_t pending_ = 0;
  int count_ = 0;  // bits in pending_, always below 32 between calls
};

// How many bytes at a and b are equal, up to limit; eight at a time where bytes are little endian.
inline size_t common_length(const uint8_t* a, const uint8_t* b, size_t limit) {
  size_t n = 0;
  if constexpr (std::endian::native == std::endian::little) {
    for (; n + 8 <= limit; n += 8) {
      uint64_t x, y;
      std::memcpy(&x, a + n, 8);
      std::memcpy(&y, b + n, 8);
      if (x != y) return n + static_cast<size_t>(std::countr_zero(x ^ y) >> 3);
    }
  }
  while (n < limit && a[n] == b[n]) ++n;
  return n;
}

// Compresses data into out as one final block with the fixed Huffman codes. At each position it
// tries a copy from each of the given distances (ascending, each at most 32768), takes the longest
// if it is 3 bytes or more, and otherwise sends one literal. A byte never costs more than 9 bits,
// so out needs size * 9 / 8 + 8 bytes. Returns the end of the output.
uint8_t* deflate_fixed(const uint8_t* data, size_t size, const size_t* distances, int distance_count,
                       uint8_t* out, DeflateCounts* counts) {
  Code distance_codes[4];
  int distance_index[4];
  for (int k = 0; k < distance_count; ++k) {
    distance_codes[k] = distance_bits(distances[k]);
    distance_index[k] = distance_code(distances[k]);
  }
  BitWriter bits(out);
  bits.put(0b011, 3);  // BFINAL = 1, BTYPE = 01 (fixed Huffman codes)
  size_t i = 0;
  while (i < size) {
    // the longest copy among the candidates
    const size_t limit = std::min<size_t>(kMaxMatch, size - i);
    size_t best_length = 0;
    int best = 0;
    for (int k = 0; k < distance_count && distances[k] <= i; ++k) {
      const size_t n = common_length(data + i, data + i - distances[k], limit);
      if (n > best_length) {
        best_length = n;
        best = k;
        if (n == limit) break;
      }
    }
    if (best_length >= 3) {
      // length and distance in one append: at most 8 + 5 + 5 + 13 = 31 bits
      const Code& length = kFixed.length[best_length];
      const Code& distance = distance_codes[best];
      bits.put(length.bits | uint64_t(distance.bits) << length.length, length.length + distance.length);
      if (counts) {
        ++counts->matches;
        ++counts->length_codes[kFixed.length_code[best_length]];
        ++counts->distance_codes[distance_index[best]];
      }
      i += best_length;
    } else {
      const Code& literal = kFixed.literal[data[i]];
      bits.put(literal.bits, literal.length);
      if (counts) ++counts->literals;
      ++i;
    }
  }
  bits.put(kFixed.end_of_block.bits, kFixed.end_of_block.length);
  return bits.finish();
}

// ---------------------------------------------------------------------------
// PNG container

void put_be32(uint8_t* p, uint32_t v) {
  p[0] = static_cast<uint8_t>(v >> 24);
  p[1] = static_cast<uint8_t>(v >> 16);
  p[2] = static_cast<uint8_t>(v >> 8);
  p[3] = static_cast<uint8_t>(v);
}

// Length, type, data and the CRC of type and data.
void append_chunk(std::vector<uint8_t>& png, const char type[4], const uint8_t* data, size_t size) {
  uint8_t head[8];
  put_be32(head, static_cast<uint32_t>(size));
  std::memcpy(head + 4, type, 4);
  png.insert(png.end(), head, head + 8);
  if (size) png.insert(png.end(), data, data + size);
  uint8_t crc[4];
  put_be32(crc, crc32(data, size, crc32(head + 4, 4)));
  png.insert(png.end(), crc, crc + 4);
}

// Compressed data is split into IDAT chunks of at most this many bytes.
constexpr size_t kMaxIdatBytes = size_t(1) << 20;

}  // namespace

uint32_t crc32(const uint8_t* data, size_t size, uint32_t crc) {
  uint32_t c = ~crc;
  for (size_t i = 0; i < size; ++i) c = kCrcTable[(c ^ data[i]) & 0xFFu] ^ (c >> 8);
  return ~c;
}

uint32_t adler32(const uint8_t* data, size_t size, uint32_t adler) {
  constexpr uint32_t kModulus = 65521;
  // the largest run of bytes after which the sums still fit 32 bits (zlib's NMAX)
  constexpr size_t kRun = 5552;
  uint32_t a = adler & 0xFFFFu, b = adler >> 16;
  while (size > 0) {
    size_t n = std::min(size, kRun);
    size -= n;
    // 16 bytes at a time: b gains 16 a plus each byte times the number of sums it enters
    for (; n >= 16; n -= 16, data += 16) {
      uint32_t sum = 0, weighted = 0;
      for (int k = 0; k < 16; ++k) {
        sum += data[k];
        weighted += uint32_t(16 - k) * data[k];
      }
      b += 16 * a + weighted;
      a += sum;
    }
    for (; n > 0; --n) {
      a += *data++;
      b += a;
    }
    a %= kModulus;
    b %= kModulus;
  }
  return b << 16 | a;
}

std::vector<uint8_t> encode_png_rgba(const uint8_t* pixels, int width, int height, DeflateCounts* counts) {
  if (width < 1 || height < 1)
    throw std::invalid_argument("cannot encode an empty " + std::to_string(width) + "x" + std::to_string(height) +
                                " picture as PNG");
  const size_t w = static_cast<size_t>(width), h = static_cast<size_t>(height);

  // opaque pictures lose nothing as RGB, and are a quarter smaller
  bool opaque = true;
  for (size_t i = 3; i < w * h * 4; i += 4)
    if (pixels[i] != 255) {
      opaque = false;
      break;
    }
  const size_t bpp = opaque ? 3 : 4;

  // the scanlines as PNG stores them: filter type 0 (none), then the row's bytes
  const size_t row_bytes = 1 + w * bpp;
  const size_t raw_size = row_bytes * h;
  std::unique_ptr<uint8_t[]> raw(new uint8_t[raw_size]);
  for (size_t y = 0; y < h; ++y) {
    uint8_t* row = raw.get() + y * row_bytes;
    const uint8_t* source = pixels + y * w * 4;
    row[0] = 0;
    if (opaque) {
      for (size_t x = 0; x < w; ++x) {
        row[1 + 3 * x] = source[4 * x];
        row[2 + 3 * x] = source[4 * x + 1];
        row[3 + 3 * x] = source[4 * x + 2];
      }
    } else {
      std::memcpy(row + 1, source, w * 4);
    }
  }

  // zlib stream: header, deflate data, Adler-32 of the scanlines. The copies tried are the pixel
  // to the left and, when within deflate's 32 KiB window, the same byte one row up.
  const size_t bound = 2 + raw_size + raw_size / 8 + 16 + 4;
  std::unique_ptr<uint8_t[]> zlib(new uint8_t[bound]);
  zlib[0] = 0x78;  // deflate with a 32 KiB window
  zlib[1] = 0x01;  // "fastest" level, and (0x78 * 256 + 0x01) is a multiple of 31 as required
  size_t distances[2] = {bpp, row_bytes};
  const int distance_count = row_bytes <= kWindow ? 2 : 1;
  uint8_t* end = deflate_fixed(raw.get(), raw_size, distances, distance_count, zlib.get() + 2, counts);
  put_be32(end, adler32(raw.get(), raw_size));
  const size_t zlib_size = static_cast<size_t>(end + 4 - zlib.get());

  // the file: signature, header, compressed data, end
  static constexpr uint8_t kSignature[8] = {137, 80, 78, 71, 13, 10, 26, 10};
  std::vector<uint8_t> png;
  png.reserve(8 + 25 + zlib_size + 12 * (zlib_size / kMaxIdatBytes + 1) + 12);
  png.insert(png.end(), kSignature, kSignature + 8);
  uint8_t header[13];
  put_be32(header, static_cast<uint32_t>(width));
  put_be32(header + 4, static_cast<uint32_t>(height));
  header[8] = 8;                 // bits per channel
  header[9] = opaque ? 2 : 6;    // colour type: RGB or RGBA
  header[10] = 0;                // deflate
  header[11] = 0;                // adaptive filtering (every row uses filter 0)
  header[12] = 0;                // not interlaced
  append_chunk(png, "IHDR", header, sizeof header);
  for (size_t offset = 0; offset < zlib_size; offset += kMaxIdatBytes)
    append_chunk(png, "IDAT", zlib.get() + offset, std::min(kMaxIdatBytes, zlib_size - offset));
  append_chunk(png, "IEND", nullptr, 0);
  return png;
}

}  // namespace periflex
