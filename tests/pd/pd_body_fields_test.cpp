// Per-particle fields of a PdBody (src/pd/pd_body_fields.cpp): damage and the largest stretch.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "pd/pd_body.h"
#include "pd_test_support.h"

namespace periflex {
namespace {

TEST(PdBodyFields, DamageIsZeroWhereIntactAndOneForAParticleCutFree) {
  const double dx = 1e-3;
  auto body = PdBody::build(test::glass_plate(0.012, 0.008, dx), 0);
  const Eigen::VectorXd q = test::affine_positions(*body, Eigen::Matrix2d::Zero());
  std::vector<float> damage;
  body->damage(damage);
  for (float d : damage) ASSERT_EQ(d, 0.0f);
  // two cuts around the lower-left corner particle (-5.5, -3.5) dx: between its column and the
  // next, and between its row and the next
  const int corner = body->nearest_particle(Vec2(-0.0055, -0.0035));
  body->cut_bonds(q, {}, Vec2(-0.005, -0.0045), Vec2(-0.005, 0.0045));
  body->cut_bonds(q, {}, Vec2(-0.0065, -0.003), Vec2(0.0065, -0.003));
  body->damage(damage);
  EXPECT_EQ(damage[corner], 1.0f);
  // a particle three horizons from both cuts keeps every bond
  EXPECT_EQ(damage[body->nearest_particle(Vec2(0.0045, 0.0035))], 0.0f);
}

TEST(PdBodyFields, TheLargestStretchOfAStretchAlongXIsThatStretch) {
  auto body = PdBody::build(test::glass_plate(0.012, 0.008, 1e-3), 0);
  Eigen::Matrix2d h;
  h << 3e-4, 0.0, 0.0, 0.0;
  std::vector<float> most;
  body->max_stretch(test::affine_positions(*body, h), most);
  // the bonds along x stretch by exactly 3e-4, every other one by less (float rounding: 1e-6 relative)
  for (float s : most) ASSERT_NEAR(s, 3e-4, 3e-10);
}

}  // namespace
}  // namespace periflex
