// The sparsity pattern's compressed columns and the greedy column colouring the implicit
// integrator perturbs by.
#include <gtest/gtest.h>

#include <vector>

#include "core/sparsity_pattern.h"

namespace periflex {
namespace {

// A 1D chain with couplings up to `reach` apart: every row reads the columns within reach.
SparsityPattern chain(int n, int reach) {
  SparsityPattern p;
  p.reset(n);
  for (int i = 0; i < n; ++i)
    for (int j = i - reach; j <= i + reach; ++j)
      if (j >= 0 && j < n) p.add(i, j);
  p.add(3, 4);  // a repeat
  p.finish();
  return p;
}

TEST(SparsityPattern, ColumnsAreSortedUniqueWithTheDiagonal) {
  SparsityPattern p;
  p.reset(3);
  p.add(2, 0);
  p.add(1, 0);
  p.add(2, 0);
  p.finish();
  EXPECT_EQ(p.start(), (std::vector<int>{0, 3, 4, 5}));
  EXPECT_EQ(p.rows(), (std::vector<int>{0, 1, 2, 1, 2}));
}

TEST(SparsityPattern, ColoursShareNoRowAndMatchTheBandwidth) {
  const int n = 200, reach = 2;
  const SparsityPattern p = chain(n, reach);
  const auto colours = colour_columns(p);
  // columns of one colour never meet in a row
  std::vector<int> owner(n);
  for (const auto& columns : colours) {
    std::fill(owner.begin(), owner.end(), -1);
    for (int j : columns)
      for (int k = p.start()[j]; k < p.start()[j + 1]; ++k) {
        EXPECT_EQ(owner[p.rows()[k]], -1) << "columns " << owner[p.rows()[k]] << " and " << j;
        owner[p.rows()[k]] = j;
      }
  }
  // columns up to 2 r apart meet in a row, so same-coloured ones lie 2 r + 1 apart: 2 r + 1
  // colours, however long the chain; every column is coloured once
  EXPECT_EQ(colours.size(), static_cast<size_t>(2 * reach + 1));
  size_t coloured = 0;
  for (const auto& columns : colours) coloured += columns.size();
  EXPECT_EQ(coloured, static_cast<size_t>(n));
}

}  // namespace
}  // namespace periflex
