// Particle contact: two elastic discs thrown at each other bounce without interpenetrating
// (every pair of particles of different discs stays more than half a spacing apart), momentum
// is conserved to round-off and the kinetic energy after the bounce is below the kinetic energy
// before (part of it stays as vibration). The Verlet list is rebuilt as the discs move, and the
// result is the same, bit for bit, on one thread and on two.
//
// Stepped with the program's Verlet integrator on the model, as the strip test is: the checks
// need every position and velocity in double precision.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <limits>

#include "contact/particle_contact.h"
#include "contact_scenes.h"
#include "model/system_model.h"
#include "scene/scene_loader.h"
#include "solve/dynamics.h"
#include "solve/integrator.h"

namespace periflex {
namespace {

struct DiscRun {
  std::unique_ptr<SystemModel> model;
  OdeState state;
  double min_distance = std::numeric_limits<double>::infinity();  // between the discs, over the run
  double worst_momentum = 0.0;                                    // max |P - P0| / |m v0|
  long most_pairs = 0;
  long rebuilds = 0;
};

// Mean velocity of the particles of flexible body k.
Vec2 mean_velocity(const SystemModel& model, const Eigen::VectorXd& qd, int k) {
  const PdBody& body = *model.flex_bodies[k];
  Vec2 v = Vec2::Zero();
  for (int i = 0; i < body.particle_count(); ++i) v += qd.segment<2>(body.coordinate_offset() + 2 * i);
  return v / body.particle_count();
}

DiscRun throw_discs(double radius, long steps, bool watch, const std::string& contact_extra = "") {
  const double dt = 1e-6;
  const SceneDef scene = parse_scene(test::discs_scene(radius, dt, steps * dt, contact_extra), "discs.toml");
  DiscRun run;
  run.model = build_system_model(scene);
  SystemModel& model = *run.model;
  Dynamics dynamics(model);
  dynamics.analyse(0.0);
  auto integrator = make_integrator("verlet", scene.solver);
  run.state = OdeState{model.q0, model.qd0};
  OdeState& s = run.state;
  const PdBody &left = *model.flex_bodies[0], &right = *model.flex_bodies[1];
  const auto momentum = [&] {
    Vec2 p = Vec2::Zero();
    for (int c = 0; c < model.coordinate_count; c += 2) p += model.mass[c] * s.qd.segment<2>(c);
    return p;
  };
  const Vec2 p0 = momentum();
  const double scale = 0.5 * model.mass.sum() * 5.0;  // sum of |m v0| over the particles
  for (long step = 0; step < steps; ++step) {
    integrator->step(dynamics, step * dt, dt, s);
    if (!watch) continue;
    run.worst_momentum = std::max(run.worst_momentum, (momentum() - p0).norm() / scale);
    run.most_pairs = std::max(run.most_pairs, model.contacts[0]->totals(s.q, s.qd).active);
    // nearest pair across the discs (only near the contact line, where they can meet)
    for (int i = 0; i < left.particle_count(); ++i) {
      const Vec2 a = s.q.segment<2>(left.coordinate_offset() + 2 * i);
      if (a.x() < -0.004) continue;
      for (int j = 0; j < right.particle_count(); ++j) {
        const Vec2 b = s.q.segment<2>(right.coordinate_offset() + 2 * j);
        if (b.x() < 0.004) run.min_distance = std::min(run.min_distance, (b - a).norm());
      }
    }
  }
  run.rebuilds = dynamic_cast<const ParticleContact&>(*model.contacts[0]).rebuilds();
  return run;
}

TEST(ParticleContact, ThrownDiscsBounceWithoutInterpenetrationAndConserveMomentum) {
  // 10 mm discs, 316 particles each; the contact lasts about 0.22 ms
  DiscRun run = throw_discs(0.01, 400, true);
  const SystemModel& model = *run.model;
  const double dx = 1e-3;
  RecordProperty("min_distance_over_dx", std::to_string(run.min_distance / dx));
  EXPECT_GT(run.min_distance, 0.5 * dx);
  EXPECT_GT(run.most_pairs, 0);
  EXPECT_LT(run.worst_momentum, 1e-12);

  // they have bounced: each disc moves back the way it came, slower than it came
  const Vec2 left = mean_velocity(model, run.state.qd, 0), right = mean_velocity(model, run.state.qd, 1);
  EXPECT_LT(left.x(), -1.0);
  EXPECT_GT(right.x(), 1.0);
  const double before = 0.5 * (model.mass.array() * model.qd0.array().square()).sum();
  const double after = 0.5 * (model.mass.array() * run.state.qd.array().square()).sum();
  RecordProperty("kinetic_after_over_before", std::to_string(after / before));
  EXPECT_LT(after, before);
  EXPECT_GT(after, 0.5 * before);
  // the list followed the discs: built again as they moved
  EXPECT_GT(run.rebuilds, 2);
}

TEST(ParticleContact, SameBitsOnOneAndTwoThreads) {
  // 25 mm discs (1,960 particles each: two chunks of the contact pass), into the contact
  omp_set_num_threads(1);
  const DiscRun one = throw_discs(0.025, 130, false);
  omp_set_num_threads(2);
  const DiscRun two = throw_discs(0.025, 130, false);
  omp_set_num_threads(1);
  ASSERT_GT(one.model->contacts[0]->totals(one.state.q, one.state.qd).active, 0);
  EXPECT_TRUE((one.state.q.array() == two.state.q.array()).all());
  EXPECT_TRUE((one.state.qd.array() == two.state.qd.array()).all());
}

}  // namespace
}  // namespace periflex
