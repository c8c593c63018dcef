// Element-wise loops over the state vectors of large models, in fixed chunks handed to the
// OpenMP threads as they become free. Chunk boundaries do not depend on the thread count, so a
// loop whose chunks write disjoint entries, or whose per-chunk partial results are combined in
// chunk order, gives the same bits on any number of threads.
#pragma once

#include <algorithm>
#include <cstdint>

namespace periflex {

// Entries per chunk: 16k doubles (128 KB) keep fork and join small next to the work.
constexpr int64_t kChunkEntries = 1 << 14;

// Number of chunks parallel_chunks splits n entries into (1 below two chunks' worth: one call).
inline int64_t chunk_count(int64_t n) { return n < 2 * kChunkEntries ? 1 : (n + kChunkEntries - 1) / kChunkEntries; }

// Calls fn(chunk, begin, end) for every chunk of [0, n).
template <typename Fn>
void parallel_chunks(int64_t n, Fn&& fn) {
  const int64_t chunks = chunk_count(n);
  if (chunks == 1) {
    fn(int64_t{0}, int64_t{0}, n);
    return;
  }
#pragma omp parallel for schedule(dynamic, 1)
  for (int64_t c = 0; c < chunks; ++c) fn(c, c * kChunkEntries, std::min(n, (c + 1) * kChunkEntries));
}

}  // namespace periflex
