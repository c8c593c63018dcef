// Framing beside the panel column: the scene lands in the free part of the window, and a view
// that grows with a moving scene keeps it in sight without its margins compounding.
#include "app/view_fit.h"

#include <gtest/gtest.h>

#include <memory>

namespace periflex {
namespace {

// a flexible body of two particles at (lo) and (hi); its initial bounds are the same box
Snapshot two_particles(Vec2 lo, Vec2 hi) {
  auto g = std::make_shared<SceneGeometry>();
  g->bodies.resize(1);
  g->bodies[0].ground = true;
  g->flex_bodies.push_back({"plate", 0, 2, 0.01});
  g->reference_x = {float(lo.x()), float(hi.x())};
  g->reference_y = {float(lo.y()), float(hi.y())};
  g->bounds_min = lo;
  g->bounds_max = hi;
  Snapshot s;
  s.geometry = g;
  s.bodies.resize(1);
  s.px = g->reference_x;
  s.py = g->reference_y;
  return s;
}

TEST(ViewFit, SceneIsCentredInTheFreePartOfTheWindow) {
  const Snapshot s = two_particles(Vec2(-1.0, -0.5), Vec2(1.0, 0.5));
  constexpr int kWidth = 1280, kHeight = 800;
  const Camera camera = fit_camera_beside_panels(s, kWidth, kHeight, kPanelWidth);
  const Vec2 lo = camera.to_pixels(Vec2(-1.0, -0.5), kWidth, kHeight);
  const Vec2 hi = camera.to_pixels(Vec2(1.0, 0.5), kWidth, kHeight);
  // the box's centre sits in the middle of the free part (half a pixel for rounding)
  EXPECT_NEAR(0.5 * (lo.x() + hi.x()), kPanelWidth + 0.5 * (kWidth - kPanelWidth), 0.5);
  EXPECT_NEAR(0.5 * (lo.y() + hi.y()), 0.5 * kHeight, 0.5);
  // and the whole box is visible right of the panels
  EXPECT_GT(std::min(lo.x(), hi.x()), kPanelWidth);
  EXPECT_LT(std::max(lo.x(), hi.x()), kWidth);
}

TEST(ViewFit, GrowingViewKeepsTheSceneInSightWithoutCompoundingMargins) {
  Snapshot s = two_particles(Vec2(0.0, 0.0), Vec2(1.0, 1.0));
  Framing f = start_framing(s);
  // nothing moved: the view stays
  EXPECT_FALSE(grow_framing(f, s, 0.1));
  // a particle moves out step by step to x = 3; the view follows
  int growths = 0;
  for (int k = 1; k <= 200; ++k) {
    s.px[1] = float(1.0 + 2.0 * k / 200.0);
    if (grow_framing(f, s, 0.1)) ++growths;
    ASSERT_LE(s.px[1], f.shown.hi.x());
  }
  EXPECT_GT(growths, 0);
  // the shown box is what was seen (x in [0, 3]) plus 10 % of it on each side, not more
  EXPECT_NEAR(f.seen.hi.x(), 3.0, 1e-6);  // float particle positions
  EXPECT_NEAR(f.shown.hi.x(), 3.0 + 0.1 * 3.0, 1e-6);
  EXPECT_NEAR(f.shown.lo.x(), 0.0 - 0.1 * 3.0, 1e-6);
}

}  // namespace
}  // namespace periflex
