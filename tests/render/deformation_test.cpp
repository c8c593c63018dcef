// Deformation magnification: the rigid motion of a body is never magnified, its deformation is,
// by exactly the factor; the automatic factor follows the deformation's size; virtual bodies and
// probes go with what carries them. No GL needed.
#include "render/deformation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

namespace periflex {
namespace {

// A flexible body of nx x ny particles at spacing h, its lower left particle at the origin.
Snapshot grid_body(int nx, int ny, double h) {
  auto geometry = std::make_shared<SceneGeometry>();
  SceneGeometry::FlexBody body;
  body.name = "plate";
  body.particle_count = nx * ny;
  body.grid_spacing = h;
  geometry->flex_bodies.push_back(body);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      geometry->reference_x.push_back(float(i * h));
      geometry->reference_y.push_back(float(j * h));
    }
  Snapshot s;
  s.px = geometry->reference_x;
  s.py = geometry->reference_y;
  s.geometry = geometry;
  return s;
}

// moves every particle by the rigid motion: turn by `angle` about the origin, then shift
void move_rigidly(Snapshot& s, double angle, double tx, double ty) {
  for (size_t i = 0; i < s.px.size(); ++i) {
    const double x = s.px[i], y = s.py[i];
    s.px[i] = float(std::cos(angle) * x - std::sin(angle) * y + tx);
    s.py[i] = float(std::sin(angle) * x + std::cos(angle) * y + ty);
  }
}

TEST(Deformation, RigidMotionIsNotMagnified) {
  // a swinging pendulum: turned by 1 rad and carried 2 m away; any factor draws it as it is
  Snapshot s = grid_body(20, 4, 0.01);
  move_rigidly(s, 1.0, 2.0, -1.0);
  for (double k : {0.0, 1.0, 100.0}) {
    std::vector<float> x, y;
    magnify_deformation(s, k, x, y);
    ASSERT_EQ(x.size(), s.px.size());
    // the snapshot's positions are floats: about 2.4e-7 m apart near 2 m, and K times a few of
    // those is all that may differ (a body turned without the fit would be off by centimetres)
    const double tolerance = (k + 1.0) * 1e-6;
    for (size_t i = 0; i < x.size(); ++i) {
      EXPECT_NEAR(x[i], s.px[i], tolerance) << "factor " << k << " particle " << i;
      EXPECT_NEAR(y[i], s.py[i], tolerance) << "factor " << k << " particle " << i;
    }
  }
  EXPECT_LT(largest_relative_deformation(s), 1e-6);
}

TEST(Deformation, DeformationIsMagnifiedByTheFactorOnTopOfTheRigidMotion) {
  // a stretch of 1e-3 along x about the body's centre, then a turn and a shift
  Snapshot s = grid_body(21, 5, 0.01);
  const double cx = 0.1, strain = 1e-3, angle = 0.3;
  for (float& x : s.px) x = float(cx + (1.0 + strain) * (x - cx));
  move_rigidly(s, angle, 0.5, 0.2);
  std::vector<float> x0, y0, x100, y100;
  magnify_deformation(s, 0.0, x0, y0);
  magnify_deformation(s, 100.0, x100, y100);
  // the last particle of the first row: 0.1 m right of the centre, moved 1e-4 m by the stretch
  const size_t last = 20;
  const double along = std::hypot(x100[last] - x0[last], y100[last] - y0[last]);
  EXPECT_NEAR(along, 100.0 * strain * 0.1, 1e-5);
  // along the body's turned axis
  EXPECT_NEAR(std::atan2(y100[last] - y0[last], x100[last] - x0[last]), angle, 1e-3);
  // factor 0: the undeformed body, turned and shifted: the first row stays 0.2 m long
  EXPECT_NEAR(std::hypot(x0[last] - x0[0], y0[last] - y0[0]), 0.2, 1e-6);
  // the largest deformation is the end's 1e-4 m over the body's diagonal
  EXPECT_NEAR(largest_relative_deformation(s), 1e-4 / std::hypot(0.2, 0.04), 1e-6);
}

TEST(Deformation, AutomaticFactorBringsSmallStrainsToATenthOfTheSize) {
  Snapshot s = grid_body(21, 5, 0.01);
  const double size = std::hypot(0.2, 0.04);
  // the end particles moved by 1e-4 m: 0.1 * size / 1e-4 = 204, rounded down to 200
  for (float& x : s.px) x = float(0.1 + 1.001 * (x - 0.1));
  EXPECT_DOUBLE_EQ(auto_deform_factor(s), 200.0);
  EXPECT_GT(0.1 * size / 1e-4, 200.0);
  // a body already deformed by a fifth of its size: true scale
  Snapshot large = grid_body(21, 5, 0.01);
  for (float& x : large.px) x = float(0.1 + 3.0 * (x - 0.1));
  EXPECT_DOUBLE_EQ(auto_deform_factor(large), 1.0);
  // nothing deformed yet: the largest factor; no particles at all: true scale
  EXPECT_DOUBLE_EQ(auto_deform_factor(grid_body(5, 5, 0.01)), kMaxAutoDeform);
  EXPECT_DOUBLE_EQ(auto_deform_factor(Snapshot{}), 1.0);
}

TEST(Deformation, RoundsDownToOneTwoFive) {
  EXPECT_DOUBLE_EQ(round_down_125(100.0), 100.0);
  EXPECT_DOUBLE_EQ(round_down_125(99.0), 50.0);
  EXPECT_DOUBLE_EQ(round_down_125(0.0031), 0.002);
  EXPECT_DOUBLE_EQ(round_down_125(7.0), 5.0);
  EXPECT_DOUBLE_EQ(round_down_125(1e-3), 1e-3);
}

// A 20 x 4 beam at 10 mm spacing bent gently (y -= c x^2): its left column held by a virtual
// body (geometry body 1), its right column by an ordinary rigid body (body 2); body 0 the ground.
Snapshot bent_held_beam() {
  Snapshot s = grid_body(20, 4, 0.01);
  auto geometry = std::make_shared<SceneGeometry>(*s.geometry);
  geometry->bodies.resize(3);
  geometry->bodies[0].ground = true;
  geometry->bodies[1].is_virtual = true;
  geometry->particle_body.assign(s.px.size(), 0);
  for (int j = 0; j < 4; ++j) {
    geometry->particle_body[j * 20] = 1;
    geometry->particle_body[j * 20 + 19] = 2;
  }
  s.geometry = geometry;
  for (size_t i = 0; i < s.px.size(); ++i) s.py[i] -= float(0.05 * s.px[i] * s.px[i]);
  return s;
}

TEST(Deformation, VirtualBodyMovesWithTheParticlesItHoldsOrdinaryBodiesStay) {
  // the bent beam magnified ten times: its left column held by a virtual body, its right column
  // by an ordinary rigid body
  const Snapshot s = bent_held_beam();
  std::vector<float> x, y;
  magnify_deformation(s, 10.0, x, y);
  const std::vector<RigidShift> shifts = magnified_body_shifts(s, x, y);
  ASSERT_EQ(shifts.size(), 3u);
  EXPECT_FALSE(shifts[0].moves);
  EXPECT_FALSE(shifts[2].moves);
  ASSERT_TRUE(shifts[1].moves);
  // the held column is carried to its magnified place (within 0.1 mm: a magnified turn is a turn
  // and a slight stretch, which no rigid motion follows)
  double largest_move = 0.0;
  for (int j = 0; j < 4; ++j) {
    const size_t i = j * 20;
    const Vec2 drawn = shifts[1].apply(Vec2(s.px[i], s.py[i]));
    EXPECT_NEAR(drawn.x(), x[i], 1e-4) << "held particle " << i;
    EXPECT_NEAR(drawn.y(), y[i], 1e-4) << "held particle " << i;
    largest_move = std::max(largest_move, std::hypot(double(x[i]) - s.px[i], double(y[i]) - s.py[i]));
  }
  // the magnification did move it (else the check above proves nothing), and the ordinary
  // body's point stays where it is
  std::printf("held column moved by up to %.3g m\n", largest_move);
  EXPECT_GT(largest_move, 1e-3);
  const Vec2 p(0.19, -0.02);
  EXPECT_EQ(shifts[2].apply(p), p);
}

TEST(Deformation, ProbesAreDrawnOnWhatCarriesThem) {
  // the bent beam again, magnified ten times: a probe on a particle of its right end, a probe
  // on the virtual body holding its left column, one on the ordinary body and one on the ground
  const Snapshot s = bent_held_beam();
  std::vector<float> x, y;
  magnify_deformation(s, 10.0, x, y);
  const std::vector<RigidShift> shifts = magnified_body_shifts(s, x, y);
  const size_t tip = 3 * 20 + 19;  // upper right particle
  const Snapshot::Probe on_particle{"tip", Vec2(s.px[tip], s.py[tip]), static_cast<int>(tip), 0};
  const Snapshot::Probe on_virtual{"grip", Vec2(0.0, 0.01), -1, 1};
  const Snapshot::Probe on_rigid{"support", Vec2(0.19, -0.02), -1, 2};
  const Snapshot::Probe on_ground{"origin", Vec2(0.05, 0.0), -1, 0};
  // the particle's probe is where its particle is drawn, 3 mm from its true place
  const Vec2 tip_drawn = magnified_probe(on_particle, x, y, shifts);
  EXPECT_EQ(tip_drawn, Vec2(x[tip], y[tip]));
  EXPECT_GT((tip_drawn - on_particle.position).norm(), 1e-3);
  // the grip's probe moves as the grip does, the others stay
  EXPECT_EQ(magnified_probe(on_virtual, x, y, shifts), shifts[1].apply(on_virtual.position));
  EXPECT_GT((magnified_probe(on_virtual, x, y, shifts) - on_virtual.position).norm(), 1e-3);
  EXPECT_EQ(magnified_probe(on_rigid, x, y, shifts), on_rigid.position);
  EXPECT_EQ(magnified_probe(on_ground, x, y, shifts), on_ground.position);
}

}  // namespace
}  // namespace periflex
