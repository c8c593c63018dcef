// The test helpers' matcher, against answers worked by hand.
#include "text_match.h"

#include <gtest/gtest.h>

namespace periflex::testing {
namespace {

TEST(TextMatch, FindsAPatternAnywhereAndOnlyWhereItIs) {
  EXPECT_TRUE(contains_match("x 12 steps/s y", R"([0-9]+ steps/s)"));
  EXPECT_FALSE(contains_match("x 12 steps y", R"([0-9]+ steps/s)"));
  // ^ anchors at the start of the text, not of a line inside it
  EXPECT_FALSE(contains_match("a\nperiflex run", R"(^periflex run)"));
}

TEST(TextMatch, FirstMatchGivesTheWholeMatchThenEachGroup) {
  const auto m = first_match("rate 340 steps/s, then 12 steps/s", R"(([0-9]+) steps/s)");
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[0], "340 steps/s");
  EXPECT_EQ(m[1], "340");
  EXPECT_TRUE(first_match("none here", R"(([0-9]+) steps/s)").empty());
}

TEST(TextMatch, AllMatchesInOrder) {
  const auto all = all_matches("1.5e3 and 20, 7", R"([0-9]+(\.[0-9]+)?([eE][+]?[0-9]+)?)");
  EXPECT_EQ(all, (std::vector<std::string>{"1.5e3", "20", "7"}));
  EXPECT_TRUE(all_matches("", "[0-9]").empty());
}

}  // namespace
}  // namespace periflex::testing
