// A slider-crank driven at constant crank speed: a kinematic (zero degree of freedom) check of
// the joint catalogue, the driver and the constraint solve against the closed form
//   x(theta) = r cos(theta) + sqrt(l^2 - r^2 sin^2(theta)).
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "solve/simulation.h"
#include "test_scenes.h"

namespace periflex {
namespace {

constexpr double kR = 0.1, kL = 0.3, kOmega = 2 * kPi;

SceneDef slider_crank(double r, double l, CorrectionDef::Method method) {
  SceneDef s = test::empty_scene("rk4", 1e-3, method);
  s.solver.correction.tolerance = 1e-12;
  s.bodies.push_back(test::body("crank", 1.0, 0.01, Vec2::Zero()));
  s.bodies.push_back(test::body("rod", 2.0, 0.02, Vec2(r + l / 2, 0.0)));
  s.bodies.push_back(test::body("slider", 0.5, 0.001, Vec2(r + l, 0.0)));
  s.joints.push_back(test::revolute("main", "ground", "crank", Vec2::Zero(), Vec2::Zero()));
  s.joints.push_back(test::revolute("crank_pin", "crank", "rod", Vec2(r, 0.0), Vec2(-l / 2, 0.0)));
  s.joints.push_back(test::revolute("wrist_pin", "rod", "slider", Vec2(l / 2, 0.0), Vec2::Zero()));
  JointDef slide;
  slide.kind = JointDef::Kind::kTranslational;
  slide.name = "guide";
  slide.body_i = "ground";
  slide.body_j = "slider";
  slide.axis_i = Vec2::UnitX();
  s.joints.push_back(slide);
  DriverDef drive;
  drive.kind = DriverDef::Kind::kAbsoluteAngle;
  drive.name = "motor";
  drive.body_i = "crank";
  drive.function = TimeFunction::linear(0.0, kOmega);
  s.drivers.push_back(drive);
  s.probes.push_back({"slider", "slider", Vec2::Zero(), {}});
  return s;
}

TEST(SliderCrank, SliderFollowsClosedFormOverTwoTurns) {
  Simulation sim(slider_crank(kR, kL, CorrectionDef::Method::kProjection));
  EXPECT_EQ(sim.info().degrees_of_freedom, 0);
  EXPECT_EQ(sim.info().drivers, 1);
  sim.initialize();
  double worst = 0.0;
  for (int k = 1; k <= 400; ++k) {
    sim.advance_to(2.0 * k / 400.0);  // two turns at one turn per second
    const double theta = kOmega * sim.time();
    const double exact = kR * std::cos(theta) + std::sqrt(kL * kL - kR * kR * std::sin(theta) * std::sin(theta));
    worst = std::max(worst, std::abs(sim.sample().probe_values[0] - exact));
  }
  // positions are projected onto the constraints to 1e-12 each step, so the slider position
  // is the kinematic solution up to that tolerance
  EXPECT_LT(worst, 1e-8);
  std::printf("slider-crank: max |x - x_exact| over two turns %.3e m\n", worst);
}

TEST(SliderCrank, DriverWorkClosesTheEnergyBalance) {
  // gravity acts and the motor keeps the speed constant: kinetic + potential changes are paid
  // by the driver, so the balance stays at the integration error (RK4, dt 1e-3: ~1e-9 J)
  Simulation sim(slider_crank(kR, kL, CorrectionDef::Method::kBaumgarte));
  sim.initialize();
  double worst = 0.0, largest_work = 0.0;
  for (int k = 1; k <= 100; ++k) {
    sim.advance_to(0.01 * k);
    const Energies e = sim.sample().energies;
    worst = std::max(worst, std::abs(e.balance));
    largest_work = std::max(largest_work, std::abs(e.driver_work));
  }
  EXPECT_GT(largest_work, 1e-2);  // the driver did real work
  EXPECT_LT(worst, 1e-6 * std::max(1.0, largest_work));
  std::printf("slider-crank: max |balance| %.3e J with |driver work| up to %.3e J\n", worst, largest_work);
}

TEST(SliderCrank, ToggleIsPassedOnTheContinuedBranch) {
  // with l = r the slider reaches the pivot at theta = 90 degrees, where the Jacobian loses a
  // row of rank and the rod could fold back over the crank; the driven motion carries on along
  // x = 2 r cos(theta) (the branch with the same velocity), through this toggle and the next
  Simulation sim(slider_crank(0.1, 0.1, CorrectionDef::Method::kProjection));
  sim.initialize();
  double worst = 0.0;
  for (int k = 1; k <= 100; ++k) {
    sim.advance_to(0.01 * k);
    const double theta = kOmega * sim.time();
    worst = std::max(worst, std::abs(sim.sample().probe_values[0] - 2 * 0.1 * std::cos(theta)));
  }
  std::printf("toggle slider-crank: max slider error over a turn %.3g m\n", worst);
  EXPECT_LT(worst, 1e-6);
}

}  // namespace
}  // namespace periflex
