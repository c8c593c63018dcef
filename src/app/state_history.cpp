// The window's history ring: cadence, budget, thinning and compression.
#include "app/state_history.h"

#include <libdeflate.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <utility>

#include "output/state_codec.h"

namespace periflex {

namespace {

// the fastest level: the coordinates barely compress at any level, their high-byte planes and
// the broken-bond bits already at this one (as in checkpoint files)
constexpr int kCompressionLevel = 1;

struct CompressorFree {
  void operator()(libdeflate_compressor* c) const { libdeflate_free_compressor(c); }
};
struct DecompressorFree {
  void operator()(libdeflate_decompressor* d) const { libdeflate_free_decompressor(d); }
};

// one compressor and decompressor per thread, kept (allocating them costs more than a small state)
libdeflate_compressor* compressor() {
  thread_local std::unique_ptr<libdeflate_compressor, CompressorFree> c(libdeflate_alloc_compressor(kCompressionLevel));
  if (!c) throw std::runtime_error("history: cannot allocate a compressor");
  return c.get();
}
libdeflate_decompressor* decompressor() {
  thread_local std::unique_ptr<libdeflate_decompressor, DecompressorFree> d(libdeflate_alloc_decompressor());
  if (!d) throw std::runtime_error("history: cannot allocate a decompressor");
  return d.get();
}

}  // namespace

void StateHistory::configure(double interval, size_t budget, double now) {
  // a new cadence counts its marks from now, the first one now
  if (interval != interval_) {
    origin_ = now;
    marks_ = 0;
  }
  interval_ = interval > 0.0 && std::isfinite(interval) ? interval : 0.0;
  budget_ = budget;
  too_large_ = false;
  thin();
}

void StateHistory::clear(double origin) {
  entries_.clear();
  bytes_ = 0;
  origin_ = origin;
  marks_ = 0;
  too_large_ = false;
}

void StateHistory::add(SimState&& state, double time, long step) {
  // the marks this state stands for are passed, whether it is kept or not
  pass(time);
  // the instant of the newest state again (a cadence changed right after a save): kept already
  if (has(time)) return;

  Entry e;
  e.time = time;
  e.step = step;
  const size_t raw = state_bytes(state);
  compressed_ = raw >= (compress_from_ > 0 ? compress_from_ : budget_ / kCompressBelowStates);
  if (compressed_) {
    // large: the codec's bytes deflated, in a buffer trimmed to what they take
    const std::vector<uint8_t> bytes = encode_state(state);
    std::vector<uint8_t> packed(libdeflate_deflate_compress_bound(compressor(), bytes.size()));
    const size_t size = libdeflate_deflate_compress(compressor(), bytes.data(), bytes.size(), packed.data(), packed.size());
    if (size == 0) throw std::runtime_error("history: cannot compress a state");
    packed.resize(size);
    packed.shrink_to_fit();
    e.packed = std::move(packed);
    e.raw_size = bytes.size();
    e.bytes = sizeof(Entry) + e.packed.capacity();
  } else {
    e.state = std::move(state);
    e.bytes = sizeof(Entry) - sizeof(SimState) + raw;
  }

  // one state over the whole budget is not kept: it would push out everything else
  too_large_ = e.bytes > budget_;
  if (too_large_) return;
  bytes_ += e.bytes;
  entries_.push_back(std::move(e));
  thin();
}

void StateHistory::pass(double time) {
  if (interval_ <= 0.0) return;
  while (mark(marks_) <= time + 1e-9 * interval_) ++marks_;
}

void StateHistory::thin() {
  while (bytes_ > budget_ && !entries_.empty()) {
    // two or fewer: the oldest goes (the newest is the one just saved)
    if (entries_.size() <= 2) {
      bytes_ -= entries_.front().bytes;
      entries_.erase(entries_.begin());
      continue;
    }
    // the oldest half keeps every other state, its first one included
    const size_t half = entries_.size() / 2;
    std::vector<Entry> kept;
    kept.reserve(entries_.size() - half / 2);
    for (size_t i = 0; i < entries_.size(); ++i) {
      if (i < half && i % 2 == 1) {
        bytes_ -= entries_[i].bytes;
        continue;
      }
      kept.push_back(std::move(entries_[i]));
    }
    entries_ = std::move(kept);
  }
}

void StateHistory::drop_after(size_t index) {
  if (index >= entries_.size()) return;
  for (size_t i = index + 1; i < entries_.size(); ++i) bytes_ -= entries_[i].bytes;
  if (index + 1 < entries_.size()) entries_.erase(entries_.begin() + static_cast<std::ptrdiff_t>(index) + 1, entries_.end());
  if (interval_ <= 0.0 || entries_.empty()) return;
  // the next mark is the first after the kept state (before the origin too, when the cadence
  // was changed after it)
  const double t = entries_[index].time + 1e-9 * interval_;
  marks_ = static_cast<long>(std::floor((t - origin_) / interval_));
  while (mark(marks_) > t) --marks_;
  while (mark(marks_) <= t) ++marks_;
}

size_t StateHistory::nearest(double time) const {
  // the entries are in time order: the first at or after `time`, or the one before it
  const auto after = std::lower_bound(entries_.begin(), entries_.end(), time,
                                      [](const Entry& e, double t) { return e.time < t; });
  if (after == entries_.begin()) return 0;
  if (after == entries_.end()) return entries_.size() - 1;
  const auto before = after - 1;
  const size_t i = static_cast<size_t>(after - entries_.begin());
  return time - before->time <= after->time - time ? i - 1 : i;
}

void StateHistory::get(size_t index, SimState& out) const {
  const Entry& e = entries_[index];
  if (e.packed.empty()) {
    out = e.state;
    return;
  }
  std::vector<uint8_t> bytes(e.raw_size);
  size_t got = 0;
  const libdeflate_result result =
      libdeflate_deflate_decompress(decompressor(), e.packed.data(), e.packed.size(), bytes.data(), bytes.size(), &got);
  if (result != LIBDEFLATE_SUCCESS || got != bytes.size()) throw std::runtime_error("history: a state does not decompress");
  out = decode_state(bytes.data(), bytes.size());
}

}  // namespace periflex
