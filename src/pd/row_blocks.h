// The particle rows of a peridynamic body's force, energy and state loops, in fixed blocks handed
// to the team's threads as they become free (core/thread_pool.h). Block boundaries do not depend on the thread count,
// and every row is computed the same way whichever thread takes it, so results do not depend on
// the thread count or the schedule. Shared by the bond-based and state-based kernels.
#pragma once

#include <algorithm>

#include "core/thread_pool.h"

namespace periflex {

// Below this many particles a loop runs on one thread: fork and join would cost more than the work.
constexpr int kRowParallelMin = 4096;

// Rows per block: large enough that scheduling costs nothing next to the work (about 20 bonds a
// row: a block is some 50 us), small enough that the last block leaves the other threads idle
// only briefly: the glass scene's 36k particles make 36 blocks. With 4096 rows they made 9, one
// thread took 5 and two threads ran 1.56x faster than one; with 1024, 1.6x. A thread slowed by
// another process on its core hands its share to the other.
constexpr int kRowsPerBlock = 1024;

// Calls fn(begin, end) over [0, n) block by block, or once when n is small.
template <typename Fn>
void for_row_blocks(int n, Fn&& fn) {
  if (n < kRowParallelMin) {
    fn(0, n);
    return;
  }
  const int blocks = (n + kRowsPerBlock - 1) / kRowsPerBlock;
  parallel_for(blocks, [&](int64_t c) {
    const int begin = static_cast<int>(c) * kRowsPerBlock;
    fn(begin, std::min(n, begin + kRowsPerBlock));
  });
}

}  // namespace periflex
