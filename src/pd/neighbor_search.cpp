#include "pd/neighbor_search.h"

#include <algorithm>
#include <cmath>

namespace periflex {

NeighborList find_neighbors(const std::vector<double>& x, const std::vector<double>& y, double radius) {
  NeighborList out;
  const int64_t n = static_cast<int64_t>(x.size());
  out.row.assign(n + 1, 0);
  if (n == 0) return out;

  // cells of side `radius` over the bounding box: a neighbour lies in the 3 x 3 block
  const auto [xmin, xmax] = std::minmax_element(x.begin(), x.end());
  const auto [ymin, ymax] = std::minmax_element(y.begin(), y.end());
  const double x0 = *xmin, y0 = *ymin;
  const int64_t ncx = static_cast<int64_t>((*xmax - x0) / radius) + 1;
  const int64_t ncy = static_cast<int64_t>((*ymax - y0) / radius) + 1;
  auto cell_x = [&](int64_t i) { return std::min<int64_t>(static_cast<int64_t>((x[i] - x0) / radius), ncx - 1); };
  auto cell_y = [&](int64_t i) { return std::min<int64_t>(static_cast<int64_t>((y[i] - y0) / radius), ncy - 1); };

  // counting sort of particles by cell (stable: ascending index inside each cell)
  std::vector<int64_t> cell_start(ncx * ncy + 1, 0);
  std::vector<int32_t> cell_of(n);
  for (int64_t i = 0; i < n; ++i) {
    cell_of[i] = static_cast<int32_t>(cell_y(i) * ncx + cell_x(i));
    ++cell_start[cell_of[i] + 1];
  }
  for (int64_t c = 0; c < ncx * ncy; ++c) cell_start[c + 1] += cell_start[c];
  std::vector<int32_t> sorted(n);
  {
    std::vector<int64_t> fill(cell_start.begin(), cell_start.end() - 1);
    for (int64_t i = 0; i < n; ++i) sorted[fill[cell_of[i]]++] = static_cast<int32_t>(i);
  }

  const double r2 = radius * radius;
  // visits the neighbours of i in the 3 x 3 cell block
  auto visit = [&](int64_t i, auto&& on_neighbor) {
    const int64_t cx = cell_of[i] % ncx, cy = cell_of[i] / ncx;
    for (int64_t by = std::max<int64_t>(cy - 1, 0); by <= std::min(cy + 1, ncy - 1); ++by) {
      for (int64_t bx = std::max<int64_t>(cx - 1, 0); bx <= std::min(cx + 1, ncx - 1); ++bx) {
        const int64_t c = by * ncx + bx;
        for (int64_t k = cell_start[c]; k < cell_start[c + 1]; ++k) {
          const int32_t j = sorted[k];
          const double dx = x[j] - x[i], dy = y[j] - y[i];
          if (j != i && dx * dx + dy * dy <= r2) on_neighbor(j);
        }
      }
    }
  };

  // pass 1: count per particle; pass 2: fill and sort each row
#pragma omp parallel for schedule(static)
  for (int64_t i = 0; i < n; ++i) {
    int64_t count = 0;
    visit(i, [&](int32_t) { ++count; });
    out.row[i + 1] = count;
  }
  for (int64_t i = 0; i < n; ++i) out.row[i + 1] += out.row[i];
  out.col.resize(out.row[n]);
#pragma omp parallel for schedule(static)
  for (int64_t i = 0; i < n; ++i) {
    int64_t at = out.row[i];
    visit(i, [&](int32_t j) { out.col[at++] = j; });
    std::sort(out.col.begin() + out.row[i], out.col.begin() + out.row[i + 1]);
  }
  return out;
}

}  // namespace periflex
