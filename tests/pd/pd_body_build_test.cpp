// Building a PdBody (src/pd/pd_body_build.cpp): notches cut the bonds across them, and a grid
// beyond the particle limit is refused before anything is allocated.
#include <gtest/gtest.h>

#include <string>

#include "core/error.h"
#include "pd/pd_body.h"
#include "pd_test_support.h"

namespace periflex {
namespace {

TEST(PdBodyBuild, ANotchLeavesNoBondAcrossItAndKeepsTheOthers) {
  FlexBodyDef def = test::glass_plate(0.02, 0.012, 1e-3);
  // a vertical notch up from the lower edge at x = 0 (between two particle columns) to y = 0
  def.notches.push_back({Vec2(0.0, -0.007), Vec2(0.0, 0.0)});
  auto body = PdBody::build(def, 0);
  const BondStore& b = body->bonds();
  const std::vector<double>& x = body->reference_positions();
  long across_below = 0, across_above = 0;
  for (int i = 0; i < body->particle_count(); ++i) {
    for (int64_t k = b.row[i]; k < b.row[i + 1]; ++k) {
      const int j = b.neighbor[k];
      const double xi = x[2 * i], yi = x[2 * i + 1], xj = x[2 * j], yj = x[2 * j + 1];
      if (!(xi < 0.0 && xj > 0.0)) continue;
      // where the bond crosses x = 0, by linear interpolation
      const double y_cross = yi + (yj - yi) * (0.0 - xi) / (xj - xi);
      if (y_cross <= 0.0) ++across_below;
      else ++across_above;
    }
  }
  EXPECT_EQ(across_below, 0);
  EXPECT_GT(across_above, 0);
}

TEST(PdBodyBuild, RefusesAGridBeyondTheParticleLimitNamingGridSpacing) {
  FlexBodyDef def = test::glass_plate(10.0, 10.0, 1e-3);  // 1e8 particles
  try {
    PdBody::build(def, 0);
    FAIL() << "a grid of 1e8 particles was built";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("grid_spacing"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("raise grid_spacing"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace periflex
