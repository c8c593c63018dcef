// Checkpoint files: header, deflate-compressed state, CRC-32; written atomically.
#include "output/checkpoint_file.h"

#include <libdeflate.h>

#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <vector>

#include "output/atomic_file.h"
#include "output/state_codec.h"

namespace periflex {

namespace {

constexpr char kMagic[8] = {'P', 'F', 'L', 'X', 'S', 'T', 'A', 'T'};
// libdeflate's level 1: the particle coordinates barely compress at any level, the planes of
// their high bytes and the broken-bond bits compress at the fastest one already (docs/state.md)
constexpr int kCompressionLevel = 1;
// magic, format, version length (the version itself follows), hash, time, steps, checkpoint
// interval, raw and compressed sizes; the CRC-32 comes after the version
constexpr size_t kFixedHeader = 8 + 4 + 4 + 8 + 8 + 8 + 8 + 8 + 8;

template <typename T>
void put(std::string& out, T value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}
template <typename T>
T get(const char*& at) {
  T value;
  std::memcpy(&value, at, sizeof(T));
  at += sizeof(T);
  return value;
}

struct CompressorFree {
  void operator()(libdeflate_compressor* c) const { libdeflate_free_compressor(c); }
};
struct DecompressorFree {
  void operator()(libdeflate_decompressor* d) const { libdeflate_free_decompressor(d); }
};

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CheckpointError("cannot open the file");
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The header fields of `bytes`, and where the compressed state starts; sizes still unchecked.
struct Parsed {
  CheckpointHeader header;
  uint64_t raw_size = 0, compressed_size = 0;
  uint32_t crc = 0;
  size_t payload = 0;   // offset of the compressed bytes
};

Parsed parse_header(const std::string& bytes) {
  Parsed p;
  if (bytes.size() < 8 || std::memcmp(bytes.data(), kMagic, 8) != 0)
    throw CheckpointError("not a periflex checkpoint (no 'PFLXSTAT' at its start)");
  if (bytes.size() < kFixedHeader) throw CheckpointError("truncated: the file ends inside its header");
  const char* at = bytes.data() + 8;
  p.header.format = get<uint32_t>(at);
  if (p.header.format != kCheckpointFormat) {
    throw CheckpointError("checkpoint format version " + std::to_string(p.header.format) + "; this program reads version " +
                          std::to_string(kCheckpointFormat));
  }
  const uint32_t version_length = get<uint32_t>(at);
  p.header.scene_hash = get<uint64_t>(at);
  p.header.time = get<double>(at);
  p.header.steps = get<int64_t>(at);
  p.header.checkpoint_every = get<double>(at);
  p.raw_size = get<uint64_t>(at);
  p.compressed_size = get<uint64_t>(at);
  if (version_length > 256 || bytes.size() < kFixedHeader + version_length + 4)
    throw CheckpointError("truncated: the file ends inside its header");
  p.header.program_version.assign(at, version_length);
  at += version_length;
  p.crc = get<uint32_t>(at);
  p.payload = static_cast<size_t>(at - bytes.data());
  return p;
}

}  // namespace

uint64_t text_hash(const std::string& text, uint64_t seed) {
  uint64_t h = seed;
  for (unsigned char c : text) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  return h;
}

size_t write_checkpoint(const std::string& path, const CheckpointHeader& header, const SimState& state) {
  const std::vector<uint8_t> raw = encode_state(state);
  thread_local std::unique_ptr<libdeflate_compressor, CompressorFree> compressor(
      libdeflate_alloc_compressor(kCompressionLevel));
  if (!compressor) throw std::runtime_error("cannot allocate a compressor for " + path);
  std::vector<uint8_t> packed(libdeflate_deflate_compress_bound(compressor.get(), raw.size()));
  const size_t packed_size =
      libdeflate_deflate_compress(compressor.get(), raw.data(), raw.size(), packed.data(), packed.size());
  if (packed_size == 0) throw std::runtime_error("cannot compress the state for " + path);

  // the header, then the CRC over it and the compressed bytes, then those bytes
  std::string out(kMagic, 8);
  put<uint32_t>(out, kCheckpointFormat);
  put<uint32_t>(out, static_cast<uint32_t>(header.program_version.size()));
  put<uint64_t>(out, header.scene_hash);
  put<double>(out, header.time);
  put<int64_t>(out, header.steps);
  put<double>(out, header.checkpoint_every);
  put<uint64_t>(out, raw.size());
  put<uint64_t>(out, packed_size);
  out += header.program_version;
  uint32_t crc = libdeflate_crc32(0, out.data(), out.size());
  crc = libdeflate_crc32(crc, packed.data(), packed_size);
  put<uint32_t>(out, crc);
  out.append(reinterpret_cast<const char*>(packed.data()), packed_size);
  write_file_atomically(path, out);
  return out.size();
}

CheckpointHeader read_checkpoint_header(const std::string& path) {
  // the header's bytes only: listing a folder of large states reads a few hundred bytes of each
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CheckpointError("cannot open the file");
  std::string head(kFixedHeader + 256 + 4, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  return parse_header(head).header;
}

SimState read_checkpoint(const std::string& path, CheckpointHeader& header) {
  const std::string bytes = read_all(path);
  const Parsed p = parse_header(bytes);
  header = p.header;
  // the size first (a cut-off file), then the checksum (damage)
  if (bytes.size() - p.payload < p.compressed_size) {
    throw CheckpointError("truncated: " + std::to_string(bytes.size()) + " bytes of the " +
                          std::to_string(p.payload + p.compressed_size) + " its header announces");
  }
  if (bytes.size() - p.payload > p.compressed_size)
    throw CheckpointError(std::to_string(bytes.size() - p.payload - p.compressed_size) + " bytes follow the state");
  uint32_t crc = libdeflate_crc32(0, bytes.data(), p.payload - 4);
  crc = libdeflate_crc32(crc, bytes.data() + p.payload, p.compressed_size);
  if (crc != p.crc) throw CheckpointError("damaged: the checksum does not match its contents");
  std::unique_ptr<libdeflate_decompressor, DecompressorFree> decompressor(libdeflate_alloc_decompressor());
  if (!decompressor) throw CheckpointError("cannot allocate a decompressor");
  if (p.raw_size > (uint64_t{1} << 40)) throw CheckpointError("damaged: an impossible state size");
  std::vector<uint8_t> raw(p.raw_size);
  size_t got = 0;
  const libdeflate_result result = libdeflate_deflate_decompress(
      decompressor.get(), bytes.data() + p.payload, p.compressed_size, raw.data(), raw.size(), &got);
  if (result != LIBDEFLATE_SUCCESS || got != raw.size()) throw CheckpointError("damaged: the state does not decompress");
  try {
    return decode_state(raw.data(), raw.size());
  } catch (const std::runtime_error& e) {
    throw CheckpointError(std::string("damaged: ") + e.what());
  }
}

}  // namespace periflex
