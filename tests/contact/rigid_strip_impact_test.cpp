// Validation of rigid-particle contact against 1D wave theory (e.g. Graff, Wave Motion in
// Elastic Solids, 1975, sec. 1.3): a rigid mass M at V0 strikes the end of a free slender bar of
// mass m, wave speed c0 = sqrt(E / rho) and impedance Z = rho c0 A. The contact force is
// F(t) = Z V0 exp(-t Z / M), the bar's end leaves the mass at exactly 2 L / c0 for any mass
// ratio, and the mass leaves with V0 exp(-2 m / M).
//
// The strip is coarse on purpose (100 x 5 particles, a second of run time): measured at this
// discretisation the contact lasts 2.3% less than 2 L / c0, the exit velocity is 1.8% above
// theory and the fitted force amplitude 3.7% above Z V0 (5 particles across a horizon of 3
// spacings make the strip a few percent stiffer than a bar of modulus E, and the lattice
// disperses the front). Halving dx brings the duration to -1.6%. The tolerances below (3%, 3%,
// 5%) hold that error and no more; a wrong law (no moment on the body, a force on one side
// only, a wrong normal) misses them by far or breaks the momentum check, which is exact.
//
// The model is stepped here with the program's own Verlet integrator rather than through
// Simulation, because the momentum check needs every velocity in double precision.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "contact_scenes.h"
#include "model/system_model.h"
#include "scene/scene_loader.h"
#include "solve/dynamics.h"
#include "solve/integrator.h"

namespace periflex {
namespace {

struct ImpactRecord {
  double contact_start = -1.0, contact_end = -1.0;  // first and last instants in contact
  double exit_velocity = 0.0;
  double worst_momentum_error = 0.0;                // max |P - P0| / P0
  double worst_balance = 0.0;                       // max |energy balance| / initial energy
  std::vector<std::pair<double, double>> force;     // (t, contact force) while in contact
  double dissipated = 0.0;
};

ImpactRecord strike(double striker_mass, const std::string& contact_extra = "") {
  const double dt = 1.1e-6, end = 5e-4;
  const SceneDef scene = parse_scene(test::strip_scene(striker_mass, dt, end, contact_extra), "strip.toml");
  std::unique_ptr<SystemModel> model = build_system_model(scene);
  Dynamics dynamics(*model);
  dynamics.analyse(0.0);
  auto integrator = make_integrator("verlet", scene.solver);
  OdeState s{model->q0, model->qd0};
  ContactElement& contact = *model->contacts.at(0);

  // momentum along x: striker plus every particle
  const auto momentum = [&] {
    double p = 0.0;
    for (int c = 0; c < model->coordinate_count; c += (c < model->rigid_coordinates ? 3 : 2))
      p += model->mass[c] * s.qd[c];
    return p;
  };
  const auto energy = [&] {
    double e = 0.5 * (model->mass.array() * s.qd.array().square()).sum() + s.work[kWorkDissipated];
    for (const auto& flex : model->flex_bodies) e += flex->potential_energy(s.q);
    return e + contact.potential_energy(s.q);
  };
  const double p0 = momentum(), e0 = energy();

  ImpactRecord out;
  double t = 0.0;
  for (long step = 1; t < end - 1e-12; ++step) {
    integrator->step(dynamics, t, dt, s);
    t = step * dt;
    const ContactTotals totals = contact.totals(s.q, s.qd);
    if (totals.active > 0) {
      if (out.contact_start < 0.0) out.contact_start = t;
      out.contact_end = t;
      out.force.emplace_back(t, totals.normal_force);
    }
    out.worst_momentum_error = std::max(out.worst_momentum_error, std::abs(momentum() - p0) / p0);
    out.worst_balance = std::max(out.worst_balance, std::abs(energy() - e0) / e0);
  }
  out.exit_velocity = s.qd[0];
  out.dissipated = s.work[kWorkDissipated];
  return out;
}

// The strip and the theory's constants.
constexpr double kE = 200e9, kRho = 7850.0, kArea = 0.05 * 0.02, kLength = 1.0, kV0 = 1.0;
const double kC0 = std::sqrt(kE / kRho), kZ = kRho * kC0 * kArea, kStripMass = kRho * kArea * kLength;

TEST(RigidStripImpact, SeparationTimeExitVelocityAndForceMatchWaveTheory) {
  const double striker = 2.0 * kStripMass;
  const ImpactRecord r = strike(striker);
  ASSERT_GT(r.contact_start, 0.0);

  const double duration = r.contact_end - r.contact_start, theory = 2.0 * kLength / kC0;
  RecordProperty("duration_over_2L_c0", std::to_string(duration / theory));
  EXPECT_NEAR(duration / theory, 1.0, 0.03);

  const double exit = kV0 * std::exp(-2.0 * kStripMass / striker);
  RecordProperty("exit_velocity_over_theory", std::to_string(r.exit_velocity / exit));
  EXPECT_NEAR(r.exit_velocity / exit, 1.0, 0.03);

  // F(t) = F0 exp(-t / tau): a least-squares line through ln F over the middle 80% of the
  // contact (the first tenth rings with the lattice) gives F0 and the decay rate
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const auto& [t, f] : r.force) {
    const double x = t - r.contact_start;
    if (x < 0.1 * theory || x > 0.9 * theory) continue;
    n += 1;
    sx += x;
    sy += std::log(f);
    sxx += x * x;
    sxy += x * std::log(f);
  }
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx), f0 = std::exp((sy - slope * sx) / n);
  RecordProperty("force_amplitude_over_Z_V0", std::to_string(f0 / (kZ * kV0)));
  EXPECT_NEAR(f0 / (kZ * kV0), 1.0, 0.05);
  EXPECT_NEAR(-slope / (kZ / striker), 1.0, 0.06);

  // momentum exchanged exactly; energy kept by the elastic contact
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", r.worst_momentum_error);
  RecordProperty("momentum_error", text);
  EXPECT_LT(r.worst_momentum_error, 1e-12);
  EXPECT_LT(r.worst_balance, 1e-3);
}

TEST(RigidStripImpact, LighterStrikerLeavesSlowerAndSeparatesAtTheSameTime) {
  // the separation time does not depend on the mass ratio; the exit velocity does
  const ImpactRecord r = strike(kStripMass);
  const double theory = 2.0 * kLength / kC0;
  EXPECT_NEAR((r.contact_end - r.contact_start) / theory, 1.0, 0.04);
  EXPECT_NEAR(r.exit_velocity, kV0 * std::exp(-2.0), 0.02 * kV0);
  EXPECT_LT(r.worst_momentum_error, 1e-12);
}

TEST(RigidStripImpact, RestitutionDampsTheContactAndTheBalanceStillCloses) {
  // a dashpot at the interface dissipates energy; the accounts include it
  const ImpactRecord r = strike(2.0 * kStripMass, "restitution = 0.3\n");
  EXPECT_GT(r.dissipated, 1e-4);
  EXPECT_LT(r.worst_balance, 1e-3);
  EXPECT_LT(r.worst_momentum_error, 1e-12);
}

}  // namespace
}  // namespace periflex
