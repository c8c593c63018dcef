#include "pd/neighbor_search.h"

#include <algorithm>
#include <cmath>

#include "core/parallel_chunks.h"

namespace periflex {

NeighborList find_neighbors(const std::vector<double>& x, const std::vector<double>& y, double radius) {
  NeighborList out;
  const int64_t n = static_cast<int64_t>(x.size());
  out.row.assign(n + 1, 0);
  if (n == 0) return out;

  // cells of side `radius` over the bounding box: a neighbour lies in the 3 x 3 block (the grid
  // of particles fits 32-bit indices, so the cell counts fit 64-bit keys)
  const auto [xmin, xmax] = std::minmax_element(x.begin(), x.end());
  const auto [ymin, ymax] = std::minmax_element(y.begin(), y.end());
  const double x0 = *xmin, y0 = *ymin;
  const int64_t ncx = static_cast<int64_t>((*xmax - x0) / radius) + 1;
  const int64_t ncy = static_cast<int64_t>((*ymax - y0) / radius) + 1;
  auto cell_x = [&](int64_t i) { return std::min<int64_t>(static_cast<int64_t>((x[i] - x0) / radius), ncx - 1); };
  auto cell_y = [&](int64_t i) { return std::min<int64_t>(static_cast<int64_t>((y[i] - y0) / radius), ncy - 1); };

  // particles sorted by cell (stable: ascending index inside each cell). Compact bodies use a
  // dense table of cell starts; a body whose bounding box holds far more cells than particles
  // (a long strip at 45 degrees) keeps only its occupied cells, found by binary search.
  const int64_t cells = ncx * ncy;
  const bool dense = cells <= 8 * n + 1024;
  std::vector<int64_t> cell_of(n);
  for (int64_t i = 0; i < n; ++i) cell_of[i] = cell_y(i) * ncx + cell_x(i);
  std::vector<int32_t> sorted(n);
  std::vector<int64_t> cell_start, cell_key;  // dense: start by cell; sparse: occupied keys and their starts
  if (dense) {
    cell_start.assign(cells + 1, 0);
    for (int64_t i = 0; i < n; ++i) ++cell_start[cell_of[i] + 1];
    for (int64_t c = 0; c < cells; ++c) cell_start[c + 1] += cell_start[c];
    std::vector<int64_t> fill(cell_start.begin(), cell_start.end() - 1);
    for (int64_t i = 0; i < n; ++i) sorted[fill[cell_of[i]]++] = static_cast<int32_t>(i);
  } else {
    for (int64_t i = 0; i < n; ++i) sorted[i] = static_cast<int32_t>(i);
    std::stable_sort(sorted.begin(), sorted.end(), [&](int32_t a, int32_t b) { return cell_of[a] < cell_of[b]; });
    for (int64_t k = 0; k < n; ++k) {
      if (k == 0 || cell_of[sorted[k]] != cell_of[sorted[k - 1]]) {
        cell_key.push_back(cell_of[sorted[k]]);
        cell_start.push_back(k);
      }
    }
    cell_start.push_back(n);
  }
  // the particles of cell c: sorted[first .. last)
  auto cell_range = [&](int64_t c, int64_t& first, int64_t& last) {
    if (dense) {
      first = cell_start[c];
      last = cell_start[c + 1];
      return;
    }
    const auto it = std::lower_bound(cell_key.begin(), cell_key.end(), c);
    if (it == cell_key.end() || *it != c) {
      first = last = 0;
      return;
    }
    const size_t at = static_cast<size_t>(it - cell_key.begin());
    first = cell_start[at];
    last = cell_start[at + 1];
  };

  const double r2 = radius * radius;
  // visits the neighbours of i in the 3 x 3 cell block
  auto visit = [&](int64_t i, auto&& on_neighbor) {
    const int64_t cx = cell_of[i] % ncx, cy = cell_of[i] / ncx;
    for (int64_t by = std::max<int64_t>(cy - 1, 0); by <= std::min(cy + 1, ncy - 1); ++by) {
      for (int64_t bx = std::max<int64_t>(cx - 1, 0); bx <= std::min(cx + 1, ncx - 1); ++bx) {
        int64_t first = 0, last = 0;
        cell_range(by * ncx + bx, first, last);
        for (int64_t k = first; k < last; ++k) {
          const int32_t j = sorted[k];
          const double dx = x[j] - x[i], dy = y[j] - y[i];
          if (j != i && dx * dx + dy * dy <= r2) on_neighbor(j);
        }
      }
    }
  };

  // pass 1: count per particle; pass 2: fill and sort each row
  parallel_chunks(n, [&](int64_t, int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      int64_t count = 0;
      visit(i, [&](int32_t) { ++count; });
      out.row[i + 1] = count;
    }
  });
  for (int64_t i = 0; i < n; ++i) out.row[i + 1] += out.row[i];
  out.col.resize(out.row[n]);
  parallel_chunks(n, [&](int64_t, int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      int64_t at = out.row[i];
      visit(i, [&](int32_t j) { out.col[at++] = j; });
      std::sort(out.col.begin() + out.row[i], out.col.begin() + out.row[i + 1]);
    }
  });
  return out;
}

}  // namespace periflex
