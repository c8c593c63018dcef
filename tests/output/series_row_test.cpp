// The series.csv columns the writer and the window's plots share, and their units.
#include "output/series_row.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace periflex {
namespace {

TEST(SeriesRow, ValuesFollowTheColumns) {
  const std::vector<std::string> columns = series_columns({"probe.tip.x", "probe.tip.y"}, true, false);
  Sample s;
  s.time = 0.5;
  s.energies.kinetic = 2.0;
  s.max_damage = 0.25;
  s.probe_values = {0.1, -0.2};
  std::vector<double> values;
  series_values(s, true, false, values);
  ASSERT_EQ(values.size(), columns.size());
  const auto at = [&](const std::string& name) {
    return values[std::find(columns.begin(), columns.end(), name) - columns.begin()];
  };
  EXPECT_EQ(columns.front(), "t");
  EXPECT_EQ(at("t"), 0.5);
  EXPECT_EQ(at("kinetic"), 2.0);
  EXPECT_EQ(at("max_damage"), 0.25);
  EXPECT_EQ(at("probe.tip.y"), -0.2);
  EXPECT_EQ(std::count(columns.begin(), columns.end(), "contact_count"), 0);
}

TEST(SeriesRow, EveryColumnHasAUnit) {
  for (const std::string& c : series_columns({"probe.bob.x", "probe.bob.vy", "probe.bob.angle", "probe.bob.omega"},
                                             true, true)) {
    EXPECT_FALSE(series_unit(c).empty()) << c;
  }
  EXPECT_EQ(series_unit("probe.bob.x"), "m");
  EXPECT_EQ(series_unit("probe.a.b.vy"), "m/s");
  EXPECT_EQ(series_unit("energy_balance"), "J");
  EXPECT_EQ(series_unit("broken_bonds"), "-");
  EXPECT_EQ(series_unit("no_such_column"), "");
}

}  // namespace
}  // namespace periflex
