// The sparsity pattern's compressed columns and the greedy column colouring the implicit
// integrator perturbs by.
#include <gtest/gtest.h>

#include <random>
#include <set>
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

// The column-by-column first fit, written plainly: column j takes the least colour no earlier
// column sharing a row with it has.
std::vector<std::vector<int>> first_fit(const SparsityPattern& p) {
  const int n = p.size();
  std::vector<std::set<int>> rows_of(n);
  for (int j = 0; j < n; ++j) rows_of[j].insert(p.rows().begin() + p.start()[j], p.rows().begin() + p.start()[j + 1]);
  std::vector<int> colour(n);
  std::vector<std::vector<int>> colours;
  for (int j = 0; j < n; ++j) {
    std::set<int> met;
    for (int k = 0; k < j; ++k)
      for (int r : rows_of[j])
        if (rows_of[k].count(r)) met.insert(colour[k]);
    int c = 0;
    while (met.count(c)) ++c;
    colour[j] = c;
    if (c == static_cast<int>(colours.size())) colours.emplace_back();
    colours[c].push_back(j);
  }
  return colours;
}

// Particles on a line (x and y columns alike), a rigid body's three coordinates coupled to a
// few of them, one-sided entries and a coordinate that meets only itself: the grouped colouring gives the colours
// of the plain first fit.
TEST(SparsityPattern, GroupedColouringIsTheColumnByColumnFirstFit) {
  std::mt19937 random(7);
  for (int trial = 0; trial < 20; ++trial) {
    const int particles = 40, n = 2 * particles + 3 + 1;
    const int body = 2 * particles, empty = n - 1;
    SparsityPattern p;
    p.reset(n);
    std::uniform_int_distribution<int> reach(1, 4), pick(0, particles - 1);
    const int r = reach(random);
    for (int a = 0; a < particles; ++a)
      for (int b = std::max(0, a - r); b <= std::min(particles - 1, a + r); ++b)
        p.add_block({2 * a, 2 * a + 1}, {2 * b, 2 * b + 1});
    for (int k = 0; k < 3; ++k) {
      const int a = pick(random);
      p.add_block({body, body + 1, body + 2, 2 * a, 2 * a + 1}, {body, body + 1, body + 2, 2 * a, 2 * a + 1});
    }
    p.add(2 * pick(random), 2 * pick(random) + 1);  // one-sided
    p.finish();
    std::vector<std::vector<int>> expected = first_fit(p);
    // the empty column has its diagonal only: it meets no other
    ASSERT_EQ(p.start()[empty + 1] - p.start()[empty], 1);
    EXPECT_EQ(colour_columns(p), expected) << "trial " << trial;
  }
}

}  // namespace
}  // namespace periflex
