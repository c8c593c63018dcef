// The spatial study: the cantilever's first bending frequency approaches Euler-Bernoulli as the
// peridynamic grid is refined, and the extreme finder it rests on is exact on a parabola.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/vec2.h"
#include "study/refine_study.h"
#include "study/study_def.h"

namespace periflex {
namespace {

TEST(RefineStudy, ExtremeOfASampledParabolaIsItsVertex) {
  std::vector<double> t, v;
  for (int k = 0; k < 20; ++k) {
    t.push_back(0.1 * k);
    v.push_back((0.1 * k - 1.234) * (0.1 * k - 1.234));
  }
  // the three-point parabola is exact for a parabola: round-off only
  EXPECT_NEAR(first_extreme_time(t, v, true), 1.234, 1e-12);
  EXPECT_LT(first_extreme_time(t, v, false), 0.0);
}

TEST(RefineStudy, CantileverFrequencyApproachesEulerBernoulliAsTheGridIsRefined) {
  const std::string text = std::string(R"(
[study]
scene = ")") + PERIFLEX_SOURCE_ROOT + R"(/scenes/studies/models/cantilever.toml"
mode = "refine"
[refine]
quantity = "cantilever_frequency"
grid_spacing = [0.005, 0.0025]
horizon_ratio = 2.0
)";
  const StudyResult r = run_refine_study(parse_study(text, "refine_test.toml"));
  ASSERT_EQ(r.rows.size(), 2u);
  for (const StudyRow& row : r.rows) ASSERT_TRUE(row.ok()) << row.status;
  // f1 = 1.8751^2 / (2 pi L^2) * h sqrt(E / (12 rho)), L = 0.2, h = 0.02, E = 1e8, rho = 1000
  const double f1 = 1.875104068711961 * 1.875104068711961 / (2.0 * kPi * 0.04) * 0.02 * std::sqrt(1e8 / 12000.0);
  EXPECT_NEAR(r.rows[0].expected, f1, 1e-9 * f1);
  // halving dx at least halves the error (the grid's discretisation error is about first order
  // in dx here, with the clamp edge and the surface of the beam resolved to within dx)
  EXPECT_LT(r.rows[1].error_max_rel, 0.5 * r.rows[0].error_max_rel);
  // bond-based PD with m = 2 on 4 particles across the depth: within 15%; on 8: within 5%
  EXPECT_LT(r.rows[0].error_max_rel, 0.15);
  EXPECT_LT(r.rows[1].error_max_rel, 0.05);
}

}  // namespace
}  // namespace periflex
