#include "io/mp4_fragments.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <fstream>
#include <vector>

namespace periflex {

namespace {

uint32_t big_endian_32(const uint8_t* p) {
  return (uint32_t(p[0]) << 24) | (uint32_t(p[1]) << 16) | (uint32_t(p[2]) << 8) | uint32_t(p[3]);
}

uint64_t big_endian_64(const uint8_t* p) { return (uint64_t(big_endian_32(p)) << 32) | big_endian_32(p + 4); }

// The samples of the track runs (trun) of every track fragment (traf) in a moof's content.
long moof_samples(const std::vector<uint8_t>& moof) {
  long samples = 0;
  // children of moof, then of each traf: size (32 bits) and type (4 characters) each
  for (size_t at = 0; at + 8 <= moof.size();) {
    const uint32_t size = big_endian_32(&moof[at]);
    if (size < 8 || at + size > moof.size()) break;
    if (std::equal(&moof[at + 4], &moof[at + 8], "traf")) {
      for (size_t in = at + 8; in + 8 <= at + size;) {
        const uint32_t inner = big_endian_32(&moof[in]);
        if (inner < 8 || in + inner > at + size) break;
        // trun: version and flags (4 bytes), then the sample count
        if (std::equal(&moof[in + 4], &moof[in + 8], "trun") && inner >= 16) samples += big_endian_32(&moof[in + 12]);
        in += inner;
      }
    }
    at += size;
  }
  return samples;
}

}  // namespace

Mp4Fragments read_mp4_fragments(const std::string& path) {
  Mp4Fragments result;
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return result;
  const uint64_t file_size = static_cast<uint64_t>(in.tellg());
  uint64_t at = 0;
  long pending = 0;  // samples of a moof whose mdat has not been seen whole yet
  while (at < file_size) {
    std::array<uint8_t, 16> header{};
    in.seekg(static_cast<std::streamoff>(at));
    const uint64_t header_bytes = file_size - at < 16 ? file_size - at : 16;
    if (header_bytes < 8 || !in.read(reinterpret_cast<char*>(header.data()), static_cast<std::streamsize>(header_bytes)))
      return result;
    uint64_t size = big_endian_32(header.data());
    uint64_t content = 8;
    if (size == 1) {  // a 64-bit size follows the type
      if (header_bytes < 16) return result;
      size = big_endian_64(header.data() + 8);
      content = 16;
    } else if (size == 0) {  // the last box, to the end of the file
      size = file_size - at;
    }
    if (size < content || size > file_size - at) return result;  // cut short
    const bool moof = std::equal(header.begin() + 4, header.begin() + 8, "moof");
    const bool mdat = std::equal(header.begin() + 4, header.begin() + 8, "mdat");
    if (moof) {
      std::vector<uint8_t> box(size - content);
      in.seekg(static_cast<std::streamoff>(at + content));
      if (!in.read(reinterpret_cast<char*>(box.data()), static_cast<std::streamsize>(box.size()))) return result;
      pending = moof_samples(box);
    } else if (mdat) {
      result.samples += pending;
      pending = 0;
    }
    at += size;
  }
  result.whole = at == file_size;
  return result;
}

}  // namespace periflex
