// Element-wise loops over the state vectors of large models, in fixed chunks handed to the
// team's threads as they become free (core/thread_pool.h). Chunk boundaries do not depend on the thread count, so a
// loop whose chunks write disjoint entries, or whose per-chunk partial results are combined in
// chunk order, gives the same bits on any number of threads.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/thread_pool.h"

namespace periflex {

// Entries per chunk: 4k doubles (32 KB) keep scheduling small next to the work while a state
// of 72k entries still splits evenly over two threads (18 chunks, not 5).
constexpr int64_t kChunkEntries = 1 << 12;

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
  parallel_for(chunks, [&](int64_t c) { fn(c, c * kChunkEntries, std::min(n, (c + 1) * kChunkEntries)); });
}

// Sum of fn(begin, end) over fixed ranges of `per_chunk` items of [0, n), added in range order:
// the same bits on any number of threads (a reduction on the fly would add in an order that
// depends on the threads' timing). Ranges go to the threads as they become free.
template <typename Fn>
double ordered_sum(int64_t n, int64_t per_chunk, Fn&& fn) {
  const int64_t chunks = (n + per_chunk - 1) / per_chunk;
  if (chunks <= 1) return n > 0 ? fn(int64_t{0}, n) : 0.0;
  std::vector<double> partial(static_cast<size_t>(chunks), 0.0);
  parallel_for(chunks, [&](int64_t c) { partial[c] = fn(c * per_chunk, std::min(n, (c + 1) * per_chunk)); });
  double sum = 0.0;
  for (double p : partial) sum += p;
  return sum;
}

}  // namespace periflex
